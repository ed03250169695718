#!/usr/bin/env bash
# [D-thesis] Figs. 4-5, 4-6 and 4-9: absolute and relative L2 errors of the
# vertical-chute velocity against points per unit (20 units, g read linearly
# and as the element mean) and against the units across (one point per
# unit), ours beside the thesis' Table 4.2. Runs the full V8 check
# (verification/V8-vertical-chute; hours of CPU) in OUTDIR/vertical-chute
# (or V8_OUTDIR), reusing the runs already there (dthesis-fig4-3.sh makes two).
#   figures/dthesis-fig4-5.sh OUTDIR
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
export GRANMPM=${GRANMPM:-$src/src/app/granmpm}
out=${1:?usage: dthesis-fig4-5.sh OUTDIR}
source "$src/figures/vchute-runs.inc"      # $runs, shared with the other chapter 4 drivers
work=$out/dthesis-fig4-5.d
mkdir -p "$work"
v8_runs                                   # the figure shows the misses too
cat "$runs/check.log"
cp "$runs/v8.csv" "$work/"
# v8.csv -> rows "ppe elements rel_disp abs_disp rel_flip abs_flip thesis_rel thesis_abs" per rule
awk -F, 'NR > 1 { split($1, a, "-"); split(a[2], r, "x")
  # [D-thesis] Table 4.2: absolute errors, same exponents as the relative ones
  ta["local-80x1"] = 9.183e-4; ta["linear-80x1"] = 7.486e-4; ta["linear-40x1"] = 1.298e-3
  ta["linear-20x4"] = 3.139e-2; ta["linear-20x2"] = 1.264e-2; ta["linear-20x1"] = 1.891e-3
  ta["element-20x8"] = 9.203e-3; ta["element-20x4"] = 4.479e-3; ta["element-20x2"] = 2.140e-3
  ta["element-20x1"] = 1.891e-3
  t = ($9 == "-" ? "NaN" : $9); tab = ($1 in ta ? ta[$1] : "NaN")
  printf "%s %s %s %s %s %s %s %s\n", r[2], r[1], $2, $3, $4, $5, t, tab > (dir "/" a[1] ".dat") }' \
  dir="$work" "$work/v8.csv"
# one file per panel: 20 units by points per unit (linear, element), one point by units
awk '$2 == 20' "$work/linear.dat" | sort -k1,1n > "$work/linear-20.dat"
awk '$2 == 20' "$work/element.dat" | sort -k1,1n > "$work/element-20.dat"
awk '$1 == 1' "$work/linear.dat" | sort -k2,2n > "$work/linear-1.dat"
gnuplot -e "dir='$work'; out='$out/dthesis-fig4-5.png'" "$src/figures/dthesis-fig4-5.gp"
