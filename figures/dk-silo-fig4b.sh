#!/usr/bin/env bash
# [DK-silo] Fig. 4(b): an arch forming in the jamming silo (inputs/silo-jam.conf,
# A = 1, W/d = 1): the lower 0.3 m of the silo at t = 0, 0.05, 0.1, 0.2, 0.4
# and 1.5 s, points coloured by speed (top row) and by state (bottom row).
#   figures/dk-silo-fig4b.sh OUTDIR
# The run comes from the shared jamming sweep (figures/jam-sweep.inc:
# $GRANMPM_JAM_SWEEP or OUTDIR/jam-sweep).
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
export GRANMPM=${GRANMPM:-$src/src/app/granmpm}
out=${1:?usage: dk-silo-fig4b.sh OUTDIR}
work=$out/dk-silo-fig4b.d
mkdir -p "$work"
source "$src/figures/jam-sweep.inc"
A=1 wd=1
jam_runs "$A" "$wd"
run=$sweep/runs/A$A-wd$wd
files= titles=
# frames every 1/240 s
for f in 0 12 24 48 96 360; do
  "$GRANMPM" extract "$run" --frame "$f" --fields x,y,vx,vy,state |
    awk -F, 'NR == 1 { print "x,y,speed,state"; next }
             { printf "%s,%s,%.6g,%s\n", $1, $2, sqrt($3 * $3 + $4 * $4), $5 }' > "$work/f$f.csv"
  files="$files $work/f$f.csv"
  titles="$titles${titles:+|}frame $f, t = $(awk -v f=$f 'BEGIN { printf "%.3g", f / 240 }') s"
done
class=$(tail -n 1 "$run/jam.csv" | cut -d, -f1)
gnuplot -e "files='$files'; titles='$titles'; label='A = $A, W/d = $wd, classified $class'; \
  out='$out/dk-silo-fig4b.png'" "$src/figures/dk-silo-fig4b.gp"
