#!/usr/bin/env bash
# [DK15] Fig. 10: depth-averaged speed against angle (eq. 4.7) and the 25 deg
# profile (eq. 4.6).   figures/dk15-fig10.sh OUTDIR
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
export GRANMPM=${GRANMPM:-$src/src/app/granmpm}
out=${1:?usage: dk15-fig10.sh OUTDIR}
mkdir -p "$out"
source "$src/figures/incline-sweep.inc"
gnuplot -e "results='$sweep/results.csv'; profile='$sweep/a25/profile.csv'; out='$out/dk15-fig10.png'" \
  "$src/figures/dk15-fig10.gp"
