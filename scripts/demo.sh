#!/usr/bin/env bash
# README quick start, first command: installs what is missing, builds topple, and runs its main job on the embedded
# default input (no data files needed).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake --preset release -DTOPPLE_BUILD_TESTS=OFF -DTOPPLE_BUILD_BENCH=OFF >/dev/null
cmake --build --preset release -j "$(nproc)" --target topple_cli
topple=build/release/cli/topple

echo
echo "== Sliding of a block (mu = 0.3) under the double triangular pulse of the thesis (Fig. 3.4: A = 2 g, t0 = 0.2 s)"
"$topple" slide --pulse double-tri --amp-g 2 --duration 0.2 --mu 0.3 --g 9.81 --out build/demo_slide_history.csv
