#!/usr/bin/env bash
# An object on the ground, on an upper floor and on a shelf of that floor: the same record, three supports.
# The floor (3 Hz, 5 %) and the shelf (8 Hz, 3 %) filter the ground motion by their own frequency; a heavy object
# (a filled cabinet, 10 % of the floor's modal mass) loads the floor when it slides (--coupled --mass-ratio).
# Usage: examples/upper_floor.sh [RECORD]   (default: Imperial Valley 1940 El Centro from ../shared/records)
set -euo pipefail
cd "$(dirname "$0")/.."
topple=${TOPPLE:-build/release/cli/topple}
record=${1:-../shared/records/RSN6_IMPVALL.I_I-ELC180.AT2}
common=("$record" --scale-pga 0.3g --mu 0.25)

echo "== on the ground (rigid support)"
"$topple" slide "${common[@]}" | grep -E "residual|slip episodes"
echo "== on a 3 Hz upper floor, 5 % damping (decoupled: the floor ignores the object)"
"$topple" slide "${common[@]}" --support-freq 3Hz --support-damping 5% | grep -E "analysis|residual|slip episodes"
echo "== a heavy cabinet on that floor (coupled, mass ratio 0.1)"
"$topple" slide "${common[@]}" --support-freq 3Hz --support-damping 5% --mass-ratio 0.1 --coupled \
  | grep -E "analysis|residual|slip episodes"
echo "== on an 8 Hz shelf, 3 % damping, standing on the ground floor"
"$topple" slide "${common[@]}" --support-freq 8Hz --support-damping 3% | grep -E "analysis|residual|slip episodes"
