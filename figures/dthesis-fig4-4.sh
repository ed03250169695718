#!/usr/bin/env bash
# [D-thesis] Fig. 4-4: the steady downward velocity across the vertical
# chute of the resolution study with g read linearly in the unit (20 units
# with 1, 2 and 4 points per unit across, 40 and 80 units with one), the
# points' own (FLIP) velocities as the thesis plots them, with the 1D
# reference. Printed: each run's relative L2 error against the reference and
# Table 4.2's (the runs of verification/V8-vertical-chute, shared:
# OUTDIR/vertical-chute or V8_OUTDIR).
#   figures/dthesis-fig4-4.sh OUTDIR
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
export GRANMPM=${GRANMPM:-$src/src/app/granmpm}
out=${1:?usage: dthesis-fig4-4.sh OUTDIR}
source "$src/figures/vchute-runs.inc"
work=$out/dthesis-fig4-4.d
mkdir -p "$work"
v8_runs
files= titles=
for c in linear-20x4 linear-20x2 linear-20x1 linear-40x1 linear-80x1; do
  [ -s "$runs/$c-profile.csv" ] || { echo "dthesis-fig4-4.sh: $runs/$c-profile.csv missing (see $runs/check.log)" >&2; exit 1; }
  cp "$runs/$c-profile.csv" "$work/"
  awk -F, -v c="$c" '$1 == c { printf "%-12s relative L2 error of the point velocities %.3e, [D-thesis] Table 4.2 %s\n", c, $4, $9 }' "$runs/v8.csv"
  n=${c#*-}; n=${n%x*}; ppu=${c#*x}
  files="$files $work/$c-profile.csv"
  titles="$titles${titles:+|}$n units, $ppu x $ppu points"
done
cp "$runs/linear-80x1-ref.csv" "$work/ref.csv"
gnuplot -e "files='$files'; titles='$titles'; ref='$work/ref.csv'; out='$out/dthesis-fig4-4.png'" \
  "$src/figures/dthesis-fig4-4.gp"
