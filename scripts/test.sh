#!/usr/bin/env bash
# The project's test command (README quick start; CI runs exactly this, on 2 cores, and must stay under 35 minutes):
# installs what is missing, builds the optimised configuration and runs every test in it, builds the sanitizer
# configuration (ASan + UBSan, -O1 -g1) and runs in it the tests that exercise memory and parsing, fuzzes each reader
# briefly, then builds the Python package and runs its tests. Each phase's header shows the seconds elapsed.
# The sanitizer phase builds only the target topple_memory_tests and runs `ctest -L memory`: the tests labelled
# `memory` in tests/CMakeLists.txt, i.e. every test under tests/io and tests/cli (readers, writers, survey, sweep and
# mesh files; the sanitized CLI on good and bad input, which runs every solver too) and a stated list (units, object
# choices, ground motions, input grids, motion sets, the ensemble store, bodies, the inversions' survey keys). The
# solver-only tests run in the optimised build only: the whole suite under the sanitizers took 19 of this script's
# 38-40 minutes (docs/performance.md, "The test command"). The statistical recovery trials of the list are left out
# there too (the asan test preset excludes them; they run in the optimised build): Recovery3c.RecoversPgaFrequency-
# AndDirection, Inversion.RecoversKnownShakingWithCalibratedIntervals, PosteriorWithPrior.SyntheticCalibrationWithThe-
# EarthquakePrior, CoupledSurvey.RecoversKnownShakingWithCoupledObjectsAndCalibratedIntervals and RegionRecovery.-
# IntervalsCoverTheTruthAndPoolingNarrowsThem: 2.5 CPU minutes under the sanitizers, repeating on many synthetic
# surveys the inversions that the other tests of the same executables run once there. Also left out there: the three
# end-to-end runs of whole examples through the CLI (CliInvert.ExampleSurveyJsonMatchesThePinnedOutput, CliInvert.-
# CemeteryExampleIsItsScriptsOutputAndRecoversThePga, RegionCli.ExampleRunsEndToEnd): 126 of the phase's 263 test
# seconds at 8d76373, whole inversions on default grids whose readers, writers and CLI paths the shorter CLI tests of
# the label run under the sanitizers too; all three run in the optimised build. A test's own code and the CLI
# compile at -O0 in that build (tests/CMakeLists.txt, cmake/ToppleOptions.cmake), the library at -O1. In the optimised
# build they compile at -O1, the library at -O3 (cli/CMakeLists.txt, tests/CMakeLists.txt); the test executables share
# one precompiled header of third-party and standard headers per build. The fuzz phase compiles at OSS-Fuzz's default
# flags, -O1 -gline-tables-only (the `fuzz` preset). docs/performance.md, "The test command", has the measurements.
# Tests that read ../shared/ (records, verification data) skip when it is absent.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="${TOPPLE_JOBS:-$(nproc)}"
# A phase's header: wall seconds since the start, and the CPU seconds (user + system) of the commands run so far, which
# a busy machine does not inflate as it does wall time.
phase() {
  local stat
  read -r -a stat </proc/$$/stat  # fields 16 and 17: CPU ticks of the waited-for children, user and system
  echo "== [${SECONDS} s, CPU $(((stat[15] + stat[16]) / $(getconf CLK_TCK))) s] $*"
}

scripts/install-deps.sh --test  # everything: the run packages plus test libraries, MPI, clang, chromium
scripts/test-venv.sh || echo "test-venv: no .venv-test; the pyrotd/eqsig comparisons will be skipped"

# ccache (Debian's, from install-deps --test) between the release and the Python phases only: the Python package's
# build (build/python, scikit-build-core) compiles the library's sources with exactly the release preset's command
# lines (-O3 -DNDEBUG -fPIC, the same includes and definitions; python-venv.sh names the same compiler), so with the
# cache they are hits instead of a third compile of the library (358 of the phase's 444 CPU seconds). Depend mode:
# the hash comes from the compiler's own -MD output, without running the preprocessor a second time on a miss. A
# cache already configured (CCACHE_DIR) is used as it is; otherwise one in build/ccache, empty on a clean clone.
launcher=()
if command -v ccache >/dev/null; then
  export CCACHE_DIR="${CCACHE_DIR:-$PWD/build/ccache}" CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}" CCACHE_DEPEND=true
  # The test executables' sources use a precompiled header (TOPPLE_PRECOMPILE_HEADERS, tests/CMakeLists.txt); ccache
  # caches such compiles only with this sloppiness (ccache's manual, "Precompiled headers"). No source of the project
  # uses __DATE__ or __TIME__. The library's sources, which the Python phase reuses, have no precompiled header.
  export CCACHE_SLOPPINESS="${CCACHE_SLOPPINESS:+$CCACHE_SLOPPINESS,}pch_defines,time_macros"
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  export TOPPLE_PYTHON_CCACHE=1
fi

phase "release build and tests"
cmake --preset release -DTOPPLE_BUILD_TESTS=ON -DTOPPLE_BUILD_BENCH=ON "${launcher[@]}" >/dev/null  # bench: on after a demo.sh build
cmake --build --preset release -j "$jobs"
ctest --preset release -j "$jobs"

phase "sanitizer build (ASan + UBSan) and the tests labelled memory"
cmake --preset asan -DTOPPLE_BUILD_TESTS=ON >/dev/null
cmake --build --preset asan -j "$jobs" --target topple_memory_tests
ctest --preset asan -j "$jobs" -L memory

if [[ -x scripts/fuzz.sh ]] && command -v clang++ >/dev/null; then
  phase "fuzzing each reader for ${TOPPLE_FUZZ_SECONDS:-10} s"
  scripts/fuzz.sh "${TOPPLE_FUZZ_SECONDS:-10}"
fi
phase "Python package: build topple._core into .venv-py (scripts/python-venv.sh), pytest against the release CLI"
scripts/python-venv.sh
# The suite holds tests that need neither ../shared nor the CLI, so pytest never ends with "no tests ran" (exit 5);
# any non-zero status fails this script.
TOPPLE_CLI="$PWD/build/release/cli/topple" .venv-py/bin/python -m pytest -q -p no:cacheprovider python/tests
phase "all tests passed"
