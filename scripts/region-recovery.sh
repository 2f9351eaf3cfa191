#!/usr/bin/env bash
# The full regional recovery test (issue 17; tests/region/test_region.cpp, RegionRecovery): N trials (default 20) of a
# synthetic regional earthquake simulated by the solvers, each site inverted alone and jointly. Prints each trial's
# relation and the coverage and width figures; fails if a threshold is missed. About 5 s of wall time a trial on the
# shared 2-core machine. Usage: scripts/region-recovery.sh [TRIALS [INTENSITY_TRIALS]] (after building test_region in
# build/release).
set -euo pipefail
cd "$(dirname "$0")/.."
TOPPLE_REGION_TRIALS="${1:-20}" build/release/tests/test_region --gtest_filter='RegionRecovery.*'
# With 24 intensity-only sites added (issue 30; tests/region/test_intensity.cpp): about 30 s a trial; default 10.
TOPPLE_INTENSITY_TRIALS="${2:-10}" build/release/tests/test_region --gtest_filter='IntensityRecovery.*'
