#!/usr/bin/env bash
# The recovery test on real records, full size (issue 18; docs/verification.md "Recovery on real records"): 25 records
# of ../shared/records x 4 PGAs (0.1, 0.2, 0.35, 0.6 g), 12 household objects each with outcomes from the solvers,
# 5 % of the observations misreported, inverted on the survey's default grid (30 x 25 cells, 40 motions), scored.
# Prints a markdown table and the summary; minutes of CPU (about 36 million runs per family).
#   scripts/recovery-real-records.sh                      # today's default family (synthetic, Clough-Penzien)
#   scripts/recovery-real-records.sh rezaeian2010         # the record-like family
#   scripts/recovery-real-records.sh pgv [rezaeian2010]   # the PGV/PGA hypothesis table instead
# Extra arguments after the family go to the program (--threads N, --write DIR, --pga 0.1,0.3, --records N,
# --misreport-rate R). Needs a release build with benchmarks:
#   cmake --preset release -DTOPPLE_BUILD_BENCH=ON && cmake --build --preset release --target recovery_real_records
set -euo pipefail
cd "$(dirname "$0")/.."
exe=build/release/bench/recovery_real_records
[[ -x $exe ]] || { echo "build $exe first (release preset, TOPPLE_BUILD_BENCH=ON)" >&2; exit 2; }
if [[ ${1:-} == pgv ]]; then
  shift
  exec "$exe" --pgv --inversion "family = \"${1:-synthetic}\""
fi
family=${1:-synthetic}
shift || true
exec "$exe" --inversion "family = \"$family\"" "$@"
