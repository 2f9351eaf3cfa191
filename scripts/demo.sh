#!/usr/bin/env bash
# README quick start, first command: installs what is missing, builds topple, and runs its main job on the embedded
# default input (no data files needed): the inversion of the synthetic example survey examples/survey.toml into PGA
# and predominant-frequency bounds, with its HTML report.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh --run  # only what building and running need (no test libraries, clang, chromium)
cmake --preset release -DTOPPLE_BUILD_TESTS=OFF -DTOPPLE_BUILD_BENCH=OFF >/dev/null
cmake --build --preset release -j "$(nproc)" --target topple_cli
topple=build/release/cli/topple

echo
echo "== topple invert examples/survey.toml  (a synthetic survey: 8 objects, 30 x 25 cells x 40 motions)"
"$topple" invert examples/survey.toml --report build/report
echo
echo "Report: build/report/index.html (open it in a browser); likelihood grid: build/report/grid.csv"
