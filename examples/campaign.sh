#!/usr/bin/env bash
# An example shake-table campaign scored in one command (docs/campaign.md): the table motions are made by
# `topple synth` (this project has no shake-table campaign; its outcomes "observed" are illustrative), then
#   topple campaign OUTDIR/campaign.toml --csv OUTDIR/rows.csv --json OUTDIR/summary.json
# Usage: examples/campaign.sh [OUTDIR]   (default: out/campaign)
set -euo pipefail
cd "$(dirname "$0")/.."
topple=${TOPPLE:-build/release/cli/topple}
out=${1:-out/campaign}
mkdir -p "$out/records"
cp examples/campaign/campaign.toml examples/mesh/balanced_rock.obj "$out/"
echo "== table motions: three components each (x, y, vertical), 10 s, predominant frequency 2 Hz"
for level in weak:0.1 medium:0.3 strong:0.8; do
  "$topple" synth --pga "${level#*:}g" --freq 2Hz --duration 10 --seed 7 --components 3 \
    --out "$out/records/${level%%:*}.csv" --quiet >/dev/null
done
echo "== the campaign, blind: every test under the planar and the 3-D models"
"$topple" campaign "$out/campaign.toml" --csv "$out/rows.csv" --json "$out/summary.json"
