#!/usr/bin/env bash
# Makes examples/cemetery.toml: a synthetic cemetery survey, a population of gravestones counted after an earthquake.
#
# How (everything from topple itself, reproducible bit for bit):
#  1. the "true" shaking: `topple synth --pga 0.5g --freq 2Hz --duration 20 --seed 2030` (Clough-Penzien filtered
#     noise, docs/method.md);
#  2. 150 gravestones, solid rectangular blocks on their base, width uniform in [0.25, 0.45] m and height uniform in
#     [0.7, 1.3] m, drawn by the Park-Miller minimal-standard generator (x <- 16807 x mod (2^31 - 1), seed 2030; exact
#     in awk's doubles, so every awk draws the same stones), sizes rounded to the centimetre as a surveyor writes them;
#  3. each stone run under that motion by `topple rock` (Housner's rocking model, Housner's restitution): toppled or not;
#  4. the survey: the count, how many toppled, the stated size ranges, and the first 20 stones as the measured sample
#     (mu 0.5-0.7, stone on stone).
# `topple invert examples/cemetery.toml` should then find the PGA near 0.5 g (tests/cli/test_cli_invert.cpp runs this
# script and checks it).
# Usage: examples/make_cemetery.sh [OUT]   (default: examples/cemetery.toml; TOPPLE=path/to/topple)
set -euo pipefail
cd "$(dirname "$0")/.."
topple=${TOPPLE:-build/release/cli/topple}
out=${1:-examples/cemetery.toml}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$topple" synth --pga 0.5g --freq 2Hz --duration 20 --seed 2030 --out "$tmp/motion.csv" --quiet >/dev/null
awk 'BEGIN {
  x = 2030; m = 2147483647;
  for (i = 1; i <= 150; i++) {
    x = (16807 * x) % m; w = 25 + int(20 * x / m + 0.5);
    x = (16807 * x) % m; h = 70 + int(60 * x / m + 0.5);
    print w, h;
  }
}' >"$tmp/stones.txt"
toppled=0
while read -r w h; do
  if "$topple" rock "$tmp/motion.csv" --shape block --width "${w}cm" --height "${h}cm" --json |
    grep -q '"overturned": true'; then
    toppled=$((toppled + 1))
  fi
done <"$tmp/stones.txt"
{
  echo "# A synthetic cemetery survey made by examples/make_cemetery.sh (see its header): 150 gravestones under one"
  echo "# synthetic motion of PGA 0.5 g and predominant frequency 2 Hz (topple synth, seed 2030); $toppled toppled by"
  echo "# topple's own rocking model. The first 20 stones are the measured sample. Do not edit: rerun the script."
  echo "[inversion]"
  echo "pga_g = [0.05, 2.0, 16]"
  echo "freq_hz = [0.5, 10.0, 8]"
  echo "motions_per_cell = 10"
  echo "duration_s = 20"
  echo
  echo "[site]"
  echo "name = \"cemetery\""
  echo
  echo "[[population]]"
  echo "id = \"gravestones\""
  echo "description = \"upright stone slabs on stone plinths\""
  echo "shape = \"block\""
  echo "count = 150"
  echo "overturned = $toppled"
  echo "width = [\"25cm\", \"45cm\"]"
  echo "height = [\"70cm\", \"130cm\"]"
  echo "mu = [0.5, 0.7]"
  echo "members = 20"
  echo "sample = ["
  head -n 20 "$tmp/stones.txt" | awk '{ printf "  {width = \"%dcm\", height = \"%dcm\"},\n", $1, $2 }'
  echo "]"
} >"$out"
echo "wrote $out: $toppled of 150 toppled"
