#!/usr/bin/env bash
# [DK15] Fig. 5: mass remaining against time and the Beverloo plot.
#   figures/dk15-fig5.sh OUTDIR
# Runs the coarse sweep of verification/V5-silo --quick (dx = 0.02 m, E = 1e6 Pa, D = 8
# ... 24 cm) unless DK15_SWEEP=DIR names a scripts/sweep-silo output (the
# full sweep: scripts/sweep-silo --out DIR).
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
export GRANMPM=${GRANMPM:-$src/src/app/granmpm} GRANMPM_SRCDIR=$src
out=${1:?usage: dk15-fig5.sh OUTDIR}
sweep=${DK15_SWEEP:-}
sizes='D06 D10 D14 D18'
if [ -z "$sweep" ]; then
  sweep=$out/dk15-fig5.d
  OMP_NUM_THREADS=${OMP_NUM_THREADS:-1} "$src/scripts/sweep-silo" --out "$sweep" --jobs 1 \
    --sizes "0.08 0.12 0.16 0.20 0.24" --set mesh.dx=0.02 --set mesh.dy=0.02 \
    --set mesh.nx=25 --set mesh.ny=53 --set material.E=1e6 > /dev/null
  sizes='D08 D12 D16 D24'
fi
gnuplot -e "sweep='$sweep'; sizes='$sizes'; outfile='$out/dk15-fig5.png'" "$src/figures/dk15-fig5.gp" 2> "$out/dk15-fig5.fit.log"
