#!/usr/bin/env bash
# [DK-silo] Fig. 5: pressure in the jamming silo (inputs/silo-jam.conf) for
# A = 1 and W/d = 1, 2, 5: (a) the smoothed point pressure averaged over
# frames 350 ... 360 and over each mesh unit, (b) the same along the vertical
# centre line against height. One PNG with both parts.
#   figures/dk-silo-fig5.sh OUTDIR
# The runs come from the shared jamming sweep (figures/jam-sweep.inc:
# $GRANMPM_JAM_SWEEP or OUTDIR/jam-sweep; three runs, a few minutes on 2 cores
# when it has not been made yet).
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
export GRANMPM=${GRANMPM:-$src/src/app/granmpm}
out=${1:?usage: dk-silo-fig5.sh OUTDIR}
work=$out/dk-silo-fig5.d
mkdir -p "$work"
source "$src/figures/jam-sweep.inc"
A=1 wds="1 2 5"
jam_runs "$A" "$wds"
dx=0.0175 nx=34 ny=35           # the mesh of inputs/silo-jam.conf, x0 = y0 = 0
classes=
for wd in $wds; do
  run=$sweep/runs/A$A-wd$wd
  # frames every 1/240 s: 350 ... 360 are t = 1.458 ... 1.5 s
  for f in $(seq 350 360); do
    "$GRANMPM" extract "$run" --smooth --frame "$f" | tail -n +2
  done | awk -F, -v dx=$dx -v nx=$nx -v ny=$ny -v units="$work/wd$wd-units.csv" -v centre="$work/wd$wd-centre.csv" '
    # columns x,y,p,p_smooth,gdot_p,state: mean p_smooth per unit over all samples
    {
      i = int($1 / dx); j = int($2 / dx)
      if (i < 0) i = 0; if (i >= nx) i = nx - 1
      if (j < 0) j = 0; if (j >= ny) j = ny - 1
      s[i, j] += $4; n[i, j]++
    }
    END {
      print "i,j,x,y,p,n" > units
      for (j = 0; j < ny; j++) for (i = 0; i < nx; i++) if ((i, j) in n)
        printf "%d,%d,%.5f,%.5f,%.6g,%d\n", i, j, (i + 0.5) * dx, (j + 0.5) * dx, s[i, j] / n[i, j], n[i, j] > units
      # the centre line x = nx dx / 2 is a unit edge: pool the two columns
      print "y,p,n" > centre
      a = nx / 2 - 1; b = nx / 2
      for (j = 0; j < ny; j++) {
        ss = 0; nn = 0
        if ((a, j) in n) { ss += s[a, j]; nn += n[a, j] }
        if ((b, j) in n) { ss += s[b, j]; nn += n[b, j] }
        if (nn > 0) printf "%.5f,%.6g,%d\n", (j + 0.5) * dx, ss / nn, nn > centre
      }
    }'
  classes="$classes${classes:+|}$(tail -n 1 "$run/jam.csv" | cut -d, -f1)"
done
set -- $wds
gnuplot -e "d1='$work/wd$1'; d2='$work/wd$2'; d3='$work/wd$3'; r1='$1'; r2='$2'; r3='$3'; A='$A'; \
  classes='$classes'; out='$out/dk-silo-fig5.png'" "$src/figures/dk-silo-fig5.gp"
