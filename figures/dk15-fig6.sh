#!/usr/bin/env bash
# [DK15] Fig. 6: the flat (top row) and the sloped (bottom row) hourglass at
# 0, 1, 2 and 5 s, points coloured by the equivalent plastic shear rate.
#   figures/dk15-fig6.sh OUTDIR
# Runs the reduced inputs (dx = 0.02 m) unless DK15_FULL=1 (dx = 0.01 m, a few
# minutes); DK15_RUNS=DIR reuses runs DIR/hourglass-flat and DIR/hourglass-sloped.
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
granmpm=${GRANMPM:-$src/src/app/granmpm}
out=${1:?usage: dk15-fig6.sh OUTDIR}
work=$out/dk15-fig6.d
mkdir -p "$work"
files= titles=
for c in hourglass-flat hourglass-sloped; do
  run=$("$src/figures/hourglass-runs" "$out" "$c")           # shared with Fig. 7
  for t in 0 1 2 5; do
    f=$work/$c-$t.csv
    "$granmpm" extract "$run" --frame $((t * 20)) --fields x,y,gdot_p > "$f"   # frames every 0.05 s
    files="$files $f"
    titles="$titles${titles:+|}$c, t = $t s"
  done
done
gnuplot -e "files='$files'; titles='$titles'; layout='2 4'; cblabel='plastic shear rate [1/s]'; \
  cbmin=0; cbmax=5; xmin=0; xmax=0.76; ymin=0; ymax=0.8; width=1600; height=900; \
  outfile='$out/dk15-fig6.png'; suptitle='hourglasses (half, symmetry line at x = 0): flat divider (top), 45 deg funnel (bottom)'" \
  "$src/figures/snapshots.gp"
