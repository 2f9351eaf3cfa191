#!/usr/bin/env bash
# The regional survey's scale figure (issue 17; docs/performance.md, "Regional surveys over MPI ranks"): a synthetic
# survey of N sites (default 48: the example's dozen and 36 more with three objects each) inverted by `topple invert`
# on 1 rank and on 2 ranks (mpirun), one thread per rank, REPEATS times each, interleaved; prints the wall times, the
# sum of the sites' own inversion times (the part the ranks split) and checks that the JSON is the same.
# Usage: scripts/region-mpi-speedup.sh [N] [REPEATS] (after building topple_cli and make_regional_example).
set -euo pipefail
cd "$(dirname "$0")/.."
n="${1:-48}"
repeats="${2:-3}"
dir="$(mktemp -d)"
trap 'rm -rf "$dir"' EXIT
build/release/tests/make_regional_example "$n" > "$dir/survey.toml"
topple="$PWD/build/release/cli/topple"
for r in $(seq "$repeats"); do
  for ranks in 1 2; do
    start=$(date +%s.%N)
    if [ "$ranks" = 1 ]; then
      "$topple" invert "$dir/survey.toml" --json --quiet --threads 1 > "$dir/out$ranks.json"
    else
      mpirun -n "$ranks" --oversubscribe --bind-to none --allow-run-as-root --mca btl self,vader \
        "$topple" invert "$dir/survey.toml" --json --quiet --threads 1 > "$dir/out$ranks.json"
    fi
    end=$(date +%s.%N)
    python3 - "$dir/out$ranks.json" "$ranks" "$(echo "$end - $start" | bc)" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
print(f"ranks {sys.argv[2]}: wall {float(sys.argv[3]):.1f} s, sites' own inversions {sum(s['seconds'] for s in j['sites']):.1f} s "
      f"(summed over ranks), {len(j['sites'])} sites")
PY
  done
  python3 - "$dir/out1.json" "$dir/out2.json" <<'PY'
import json, sys
def strip(o):
    if isinstance(o, dict): return {k: strip(v) for k, v in o.items() if k not in ("seconds", "provenance")}
    if isinstance(o, list): return [strip(v) for v in o]
    return o
a, b = (strip(json.load(open(p))) for p in sys.argv[1:3])
print("same JSON on 1 and 2 ranks:", a == b)
sys.exit(0 if a == b else 1)
PY
done
