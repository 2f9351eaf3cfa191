#!/usr/bin/env bash
# The project's test command (README quick start; CI runs exactly this): installs what is missing, builds the
# optimised and the sanitizer (ASan + UBSan) configurations, runs every test in both, then fuzzes each reader briefly.
# One statistical test runs in the optimised build only (the asan test preset excludes it): the three-component
# recovery trials (Recovery3c.RecoversPgaFrequencyAndDirection), a minute of the same solvers and likelihood that the
# other Inversion3c/Survey3c tests already run under the sanitizers.
# Tests that read ../shared/ (records, verification data) skip when it is absent.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="${TOPPLE_JOBS:-$(nproc)}"

scripts/install-deps.sh --test  # everything: the run packages plus test libraries, MPI, clang, chromium
scripts/test-venv.sh || echo "test-venv: no .venv-test; the pyrotd/eqsig comparisons will be skipped"

echo "== [${SECONDS} s] release build and tests"
cmake --preset release -DTOPPLE_BUILD_TESTS=ON -DTOPPLE_BUILD_BENCH=ON >/dev/null  # on after a demo.sh build
cmake --build --preset release -j "$jobs"
ctest --preset release -j "$jobs"

echo "== [${SECONDS} s] sanitizer build (ASan + UBSan) and the tests labelled memory"
cmake --preset asan -DTOPPLE_BUILD_TESTS=ON >/dev/null
cmake --build --preset asan -j "$jobs" --target topple_memory_tests
ctest --preset asan -j "$jobs" -L memory

if [[ -x scripts/fuzz.sh ]] && command -v clang++ >/dev/null; then
  echo "== [${SECONDS} s] fuzzing each reader for ${TOPPLE_FUZZ_SECONDS:-10} s"
  scripts/fuzz.sh "${TOPPLE_FUZZ_SECONDS:-10}"
fi
echo "== [${SECONDS} s] Python package: build topple._core into .venv-py (scripts/python-venv.sh), pytest against the release CLI"
scripts/python-venv.sh
# The suite holds tests that need neither ../shared nor the CLI, so pytest never ends with "no tests ran" (exit 5);
# any non-zero status fails this script.
TOPPLE_CLI="$PWD/build/release/cli/topple" .venv-py/bin/python -m pytest -q -p no:cacheprovider python/tests
echo "== [${SECONDS} s] all tests passed"
