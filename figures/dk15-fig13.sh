#!/usr/bin/env bash
# [DK15] Fig. 13: the mu(I) update against the rkf45 reference on the App. B
# history, with the convergence plot.   figures/dk15-fig13.sh OUTDIR
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
granmpm=${GRANMPM:-$src/src/app/granmpm}
out=${1:?usage: dk15-fig13.sh OUTDIR}
work=$out/dk15-fig13.d
mkdir -p "$work"
"$granmpm" constitutive --dt 1e-3 --output "$work/data.csv"
"$granmpm" constitutive --converge 1e-3,1e-4,1e-5 --table "$work/convergence.csv" > /dev/null
gnuplot -e "data='$work/data.csv'; conv='$work/convergence.csv'; out='$out/dk15-fig13.png'" \
  "$src/figures/dk15-fig13.gp"
