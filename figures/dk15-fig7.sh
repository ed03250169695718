#!/usr/bin/env bash
# [DK15] Fig. 7: the hourglasses of Fig. 6, points coloured by their state
# from the nodal density projected back to them (granmpm state): dense
# (rho_nodal >= rho_c) or disconnected.
#   figures/dk15-fig7.sh OUTDIR
# Reduced inputs unless DK15_FULL=1; DK15_RUNS=DIR reuses runs.
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
granmpm=${GRANMPM:-$src/src/app/granmpm}
out=${1:?usage: dk15-fig7.sh OUTDIR}
work=$out/dk15-fig7.d
mkdir -p "$work"
sfx=-reduced; [ "${DK15_FULL:-0}" = 1 ] && sfx=
files= titles=
for c in hourglass-flat hourglass-sloped; do
  run=$("$src/figures/hourglass-runs" "$out" "$c")           # shared with Fig. 6
  for t in 0.5 1 2 5; do
    fr=$(awk -v t="$t" 'BEGIN { printf "%d", t / 0.05 + 0.5 }')
    f=$work/$c-$t.csv
    "$granmpm" state "$src/inputs/$c$sfx.conf" "$run" --frame "$fr" | cut -d, -f1,2,4 > "$f"
    files="$files $f"
    titles="$titles${titles:+|}$c, t = $t s"
  done
done
gnuplot -e "files='$files'; titles='$titles'; layout='2 4'; cblabel='state (nodal density)'; states=1; \
  xmin=0; xmax=0.76; ymin=0; ymax=0.8; width=1600; height=900; \
  outfile='$out/dk15-fig7.png'; suptitle='state from the nodal density: dense (blue) or disconnected (red)'" \
  "$src/figures/snapshots.gp"
