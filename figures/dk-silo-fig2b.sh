#!/usr/bin/env bash
# [DK-silo] Fig. 2(b): the NGF chute phase diagram from a sweep over 6 angles
# x 6 thicknesses (scripts/sweep-hstop, about 2 minutes on one core).
#   figures/dk-silo-fig2b.sh OUTDIR     (FIG2B_JOBS: parallel runs, default
#   GRANMPM_FIGURE_JOBS or 1; finished runs are not run again)
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
export GRANMPM=${GRANMPM:-$src/src/app/granmpm}
out=${1:?usage: dk-silo-fig2b.sh OUTDIR}
work=$out/dk-silo-fig2b.d
mkdir -p "$work"
"$src/scripts/sweep-hstop" --out "$work/sweep" --jobs "${FIG2B_JOBS:-${GRANMPM_FIGURE_JOBS:-1}}" \
  --angles "22 24 27 30 35 40" --ratios "0.5 0.7 0.9 1.1 1.4 2" --t-end 1 --t-min 0.5
gnuplot -e "data='$work/sweep/hstop.csv'; out='$out/dk-silo-fig2b.png'" "$src/figures/dk-silo-fig2b.gp"
