#!/usr/bin/env bash
# The longer recovery test with coupled slide-rock objects among the witnesses (issue 15; tests/
# test_inversion_coupled.cpp, CoupledSurvey.RecoversKnownShakingWithCoupledObjectsAndCalibratedIntervals): N trials
# (default 60; ctest runs 16) of a known motion, every object observed by the solvers, each inverted. Prints each
# trial (with the coupled objects' outcomes) and the coverage of the 95 % and 68 % regions; fails if a threshold
# (>= 85 %, >= 55 %) is missed. About 1 s of CPU a trial. Usage: scripts/recovery-coupled.sh [TRIALS] (after
# building test_inversion_coupled in build/release).
set -euo pipefail
cd "$(dirname "$0")/.."
TOPPLE_RECOVERY_TRIALS="${1:-60}" build/release/tests/test_inversion_coupled \
  --gtest_filter='CoupledSurvey.RecoversKnownShakingWithCoupledObjectsAndCalibratedIntervals'
