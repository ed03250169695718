#!/usr/bin/env bash
# Final state of the default example (inputs/example.conf), points coloured
# by pressure.   figures/final-state.sh OUTDIR
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
granmpm=${GRANMPM:-$src/src/app/granmpm}
out=${1:?usage: final-state.sh OUTDIR}
work=$out/final-state.d
mkdir -p "$out"
"$src/scripts/run-once" "$work" "$granmpm" run "$src/inputs/example.conf" --quiet --output "$work"
"$granmpm" extract "$work" --frame last --fields x,y,p,state > "$work/final-state.csv"
gnuplot -e "datafile='$work/final-state.csv'; outfile='$out/final-state.png'" \
  "$src/figures/final-state.gp"
