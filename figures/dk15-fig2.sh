#!/usr/bin/env bash
# [DK15] Fig. 2: collapse of columns a = 2, 1, 0.5, coloured by gdot_p at
# 0, 0.5 and 2 s and by smoothed pressure at 2 s, with [DK15]'s 4 x 4
# points per unit (the 4 x 4 collapse sweep, figures/collapse-sweep.inc).
# Prints each heap's run-out and final slope.   figures/dk15-fig2.sh OUTDIR
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
export GRANMPM=${GRANMPM:-$src/src/app/granmpm}
out=${1:?usage: dk15-fig2.sh OUTDIR}
work=$out/dk15-fig2.d
mkdir -p "$work"
source "$src/figures/collapse-sweep.inc"
collapse_sweep 4
awk -F, 'NR > 1 && ($1 == 0.5 || $1 == 1 || $1 == 2) {
  printf "a = %s: run-out %.3f, final slope %.2f deg (atan(mu_s) = 20.9 deg)\n", $1, $6, $7 }' "$sweep/results.csv"
for a in 2 1 0.5; do
  run=$sweep/a$a
  # frames every 0.05 s: 0, 0.5 and 2 s are frames 0, 10 and 40
  for k in 0 1 2; do
    f=$(echo "0 10 40" | cut -d' ' -f$((k + 1)))
    "$GRANMPM" extract "$run" --frame "$f" --fields x,y,gdot_p > "$work/a$a-f$k.csv"
  done
  "$GRANMPM" extract "$run" --frame 40 --smooth > "$work/a$a-p.csv"
done
gnuplot -e "d1='$work/a2'; d2='$work/a1'; d3='$work/a0.5'; out='$out/dk15-fig2.png'" \
  "$src/figures/dk15-fig2.gp"
