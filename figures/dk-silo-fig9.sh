#!/usr/bin/env bash
# [DK-silo] Fig. 9: point speeds of the coarse (top) and refined (bottom)
# silos of [DK-silo] section 7.3, A = 1: W/d = 1 at frame 350 (t = 1.458 s;
# the arch) and W/d = 5 at frame 105 (t = 0.4375 s; flowing). Coarse: the
# runs of the jamming sweep (figures/jam-sweep.inc); refined: units of half
# the size and a quarter of the step (figures/silo-refined.inc; two runs of
# about 15 minutes each on one core). Printed per run: the classifier's
# verdict, the mass drained by 1.5 s and the mean speed of the dense points
# below half the fill height at the frame drawn ([DK-silo]: the refined
# flowing silo runs a little faster, its orifice edge being sharper).
#   figures/dk-silo-fig9.sh OUTDIR
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
export GRANMPM=${GRANMPM:-$src/src/app/granmpm}
out=${1:?usage: dk-silo-fig9.sh OUTDIR}
work=$out/dk-silo-fig9.d
mkdir -p "$work"
source "$src/figures/jam-sweep.inc"
source "$src/figures/silo-refined.inc"
jam_runs 1 "1 5"
refined_runs 1 "1 5"
files= titles=
for res in coarse refined; do
  for c in "1 350" "5 105"; do
    set -- $c
    wd=$1 f=$2
    if [ $res = coarse ]; then run=$sweep/runs/A1-wd$wd; else run=$refined/runs/A1-wd$wd; fi
    "$GRANMPM" extract "$run" --frame "$f" --fields x,y,vx,vy,state |
      awk -F, 'NR == 1 { print "x,y,speed,state"; next }
               { printf "%s,%s,%.6g,%s\n", $1, $2, sqrt($3 * $3 + $4 * $4), $5 }' > "$work/$res-wd$wd.csv"
    cls=$(tail -n 1 "$run/jam.csv" | cut -d, -f1)
    awk -F, -v r="$res" -v wd="$wd" -v f="$f" -v cls="$cls" 'NR == 2 { m0 = $6 } { m1 = $6 }
      END { printf "%-7s W/d = %s: %s, mass %.1f -> %.1f kg/m by t = %.2f s; ", r, wd, cls, m0, m1, $1 }' "$run/diagnostics.csv"
    awk -F, 'NR > 1 && $4 == 1 && $2 < 0.2975 { s += $3; n++ } END { printf "mean speed of the dense points below y = 0.2975 m: %.4g m/s\n", s / n }' \
      "$work/$res-wd$wd.csv"
    files="$files $work/$res-wd$wd.csv"
    titles="$titles${titles:+|}$res, W/d = $wd, frame $f ($cls)"
  done
done
gnuplot -e "files='$files'; titles='$titles'; out='$out/dk-silo-fig9.png'" "$src/figures/dk-silo-fig9.gp"
