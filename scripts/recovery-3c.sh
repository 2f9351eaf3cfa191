#!/usr/bin/env bash
# The full recovery test in three components (issue 14; tests/inversion/test_inversion_3c.cpp, Recovery3c): N trials (default
# 30) of a known three-component motion with a random direction of strongest shaking, objects at random bearings,
# observed by the solvers, each inverted. Prints each trial and the coverage of the 95 % and 68 % regions and of the
# direction's 95 % arc; fails if a threshold is missed. About 7 s of CPU a trial (4-7 min on the shared 2-core
# machine for 30). Usage: scripts/recovery-3c.sh [TRIALS] (after building test_inversion_3c in build/release).
set -euo pipefail
cd "$(dirname "$0")/.."
TOPPLE_3C_TRIALS="${1:-30}" build/release/tests/test_inversion_3c --gtest_filter='Recovery3c.RecoversPgaFrequencyAndDirection'
