#!/usr/bin/env bash
# The whole SLAMMER flexible suite (2,520 analyses x 2 polarities) against topple: pass counts per analysis kind,
# the distribution of differences and every case outside pySLAMMER's criterion (docs/verification.md quotes it).
# Needs a release build with tests: cmake --preset release -DTOPPLE_BUILD_TESTS=ON && cmake --build --preset release
set -euo pipefail
cd "$(dirname "$0")/.."
exe=build/release/tests/test_slammer_flexible
[[ -x $exe ]] || { echo "build $exe first (release preset, TOPPLE_BUILD_TESTS=ON)" >&2; exit 2; }
exec "$exe" --gtest_also_run_disabled_tests --gtest_filter='SlammerFlexible.DISABLED_FullSuite'
