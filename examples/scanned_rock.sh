#!/usr/bin/env bash
# A scanned rock from its mesh to its fragility, in four commands (README, "Spectra and fragility"; docs/method.md,
# "Resting pose" and "Records as recorded"):
#   1. the stable faces of its convex hull and their static overturning accelerations (b/h);
#   2. its body at rest on the stable face nearest the scanned pose, written as JSON;
#   3. a set of records (here made by `topple synth`; in a study, the shake-table or field records as recorded:
#      plain text files take --columns and --baseline);
#   4. the records run as recorded (no rescaling) and a fragility surface fitted in PGA and PGV/PGA, with its figure.
# The mesh is examples/mesh/balanced_rock.obj (a synthetic "rock" made by examples/mesh/make_rock.py). For a
# scan as a scanner writes it: `--unit mm` for millimetres; `--up x,y,z` or `--rotation w,x,y,z` when its z is not up.
# Usage: examples/scanned_rock.sh [OUTDIR]   (default: out/scanned_rock)
set -euo pipefail
cd "$(dirname "$0")/.."
topple=${TOPPLE:-build/release/cli/topple}
out=${1:-out/scanned_rock}
mesh=examples/mesh/balanced_rock.obj
mkdir -p "$out"

echo "== 1. the stable faces of the rock's convex hull (the first 8 of the list)"
"$topple" body "$mesh" --azimuth 0 --list-faces | awk '/^ *face/ || ($3 == "yes" && n++ < 8)'
echo "== 2. the rock at rest on the stable face nearest the scan, rocking toward azimuth 30 deg"
"$topple" body "$mesh" --azimuth 30 --json >"$out/rock.json"
"$topple" body "$mesh" --azimuth 30 | grep -E "^(pose|static a/g|h |b1, b2)"
echo "== 3. 40 records: 4 predominant frequencies x 5 PGAs x 2 seeds"
i=0
for freq in 0.7 1.5 3 6; do
  for pga in 0.1 0.2 0.3 0.45 0.6; do
    for seed in 1 2; do
      i=$((i + 1))
      "$topple" synth --pga "${pga}g" --freq "${freq}Hz" --duration 15 --seed "$seed" --out "$out/record_$i.csv" \
        --quiet >/dev/null
    done
  done
done
echo "== 4. the rock under each record as recorded, and its fragility surface in PGA and PGV/PGA"
"$topple" fragility "$out"/record_*.csv --body "$out/rock.json" --as-recorded --quiet --out "$out/fragility.csv" \
  --plot "$out/fragility.png" | head -4
