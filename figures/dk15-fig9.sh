#!/usr/bin/env bash
# [DK15] Fig. 9: mean mu, depth-averaged speed and acceleration against time
# on the inclined plane, one line per angle.   figures/dk15-fig9.sh OUTDIR
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
export GRANMPM=${GRANMPM:-$src/src/app/granmpm}
out=${1:?usage: dk15-fig9.sh OUTDIR}
mkdir -p "$out"
source "$src/figures/incline-sweep.inc"
present=""
for a in $angles; do [ -s "$sweep/a$a/series.csv" ] && present="$present $a"; done
gnuplot -e "dir='$sweep'; angles='${present# }'; out='$out/dk15-fig9.png'" "$src/figures/dk15-fig9.gp"
