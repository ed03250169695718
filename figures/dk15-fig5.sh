#!/usr/bin/env bash
# [DK15] Fig. 5: mass remaining against time and the Beverloo plot.
#   figures/dk15-fig5.sh OUTDIR
# Draws the full sweep of verification/V5-silo (inputs/silo.conf as it is:
# dx = 0.01 m, E = 1e7 Pa, D = 6 ... 20 cm by 2 cm; about 7 minutes of one
# core), made in OUTDIR/silo-sweep through scripts/sweep-silo (finished runs
# are not run again), with points that leave through the free top removed
# as V5 runs it (verification/V5-silo/README.md); or the scripts/sweep-silo
# output DK15_SWEEP=DIR; or, with DK15_QUICK=1, the coarse sweep of V5's
# quick check (dx = 0.02 m, E = 1e6 Pa, D = 8 ... 24 cm). Prints the flow
# rates and the fits as V5 does. GRANMPM_FIGURE_JOBS: runs side by side.
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
export GRANMPM=${GRANMPM:-$src/src/app/granmpm} GRANMPM_SRCDIR=$src
out=${1:?usage: dk15-fig5.sh OUTDIR}
sweep=${DK15_SWEEP:-}
sizes='D06 D10 D14 D18'
jobs=(--jobs "${GRANMPM_FIGURE_JOBS:-1}")
if [ -z "$sweep" ] && [ "${DK15_QUICK:-0}" = 1 ]; then
  sweep=$out/dk15-fig5.d
  OMP_NUM_THREADS=${OMP_NUM_THREADS:-1} "$src/scripts/sweep-silo" --out "$sweep" "${jobs[@]}" \
    --sizes "0.08 0.12 0.16 0.20 0.24" --set mesh.dx=0.02 --set mesh.dy=0.02 \
    --set mesh.nx=25 --set mesh.ny=53 --set material.E=1e6 > /dev/null ||
    echo "dk15-fig5.sh: some runs of the sweep failed; drawing the others" >&2
  sizes='D08 D12 D16 D24'
elif [ -z "$sweep" ]; then
  sweep=$out/silo-sweep
  OMP_NUM_THREADS=${OMP_NUM_THREADS:-1} "$src/scripts/sweep-silo" --out "$sweep" "${jobs[@]}" \
    --sizes "0.06 0.08 0.10 0.12 0.14 0.16 0.18 0.20" --set remove.free_edges=true > /dev/null ||
    echo "dk15-fig5.sh: some runs of the sweep failed; drawing the others" >&2
fi
[ "$(wc -l < "$sweep/flow-rates.csv")" -gt 2 ] || { echo "dk15-fig5.sh: fewer than two flow rates in $sweep" >&2; exit 1; }
# the flow rates and both fits, as verification/V5-silo/check
awk -F, 'NR == 1 { next }
  { n++; D = $1; Q = $3; c = Q / (1500 * sqrt(9.8) * D^1.5); lc += log(c)
    printf "D = %.2f m: Q = %.1f kg/(m s), C = %.3f\n", D, Q, c
    x = log(D); y = log(Q); sx += x; sy += y; sxx += x * x; sxy += x * y }
  END { C = exp(lc / n); b = (n * sxy - sx * sy) / (n * sxx - sx * sx); a = exp((sy - b * sx) / n)
        printf "Beverloo C = %.3f ([DK15] 1.42, %+.1f %%); free fit: power %.3f, C = %.3f ([DK15] 1.47, 1.31)\n",
          C, 100 * (C / 1.42 - 1), b, a / (1500 * sqrt(9.8)) }' "$sweep/flow-rates.csv"
gnuplot -e "sweep='$sweep'; sizes='$sizes'; outfile='$out/dk15-fig5.png'" "$src/figures/dk15-fig5.gp" 2> "$out/dk15-fig5.fit.log"
