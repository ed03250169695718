#!/usr/bin/env bash
# [DK-silo] Fig. 8: the fluidity g of the flowing silo (inputs/silo-jam.conf,
# W/d = 5, d = 0.028 m) for A = 0.1, 0.5 and 1, averaged over frames 280 ...
# 300 (t = 1.167 ... 1.25 s) and over each mesh unit, on a log scale. As the
# paper, disconnected points count with g = 0 (the free fall above the
# orifice comes out darkest); units that held no point are white.
# Prints per A the mass left in the silo (the height of the free surface:
# lower A should drain a little faster), the points leaving per frame, and
# at the slice heights of Fig. 6 the largest unit mean g and the spread of
# g about the centre line, sqrt(sum g (x - L/2)^2 / sum g) over the units of
# that row (smaller A: less spread).
#   figures/dk-silo-fig8.sh OUTDIR
# The runs come from the shared jamming sweep (figures/jam-sweep.inc:
# $GRANMPM_JAM_SWEEP or OUTDIR/jam-sweep).
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
export GRANMPM=${GRANMPM:-$src/src/app/granmpm}
out=${1:?usage: dk-silo-fig8.sh OUTDIR}
work=$out/dk-silo-fig8.d
mkdir -p "$work"
source "$src/figures/jam-sweep.inc"
As="0.1 0.5 1" wd=5
jam_runs "$As" "$wd"
dx=0.0175 nx=34 ny=35           # the mesh of inputs/silo-jam.conf, x0 = y0 = 0
W=0.14
for A in $As; do
  run=$sweep/runs/A$A-wd$wd
  for f in $(seq 280 300); do
    "$GRANMPM" extract "$run" --frame "$f" --fields x,y,g,state | tail -n +2
  done | awk -F, -v dx=$dx -v nx=$nx -v ny=$ny -v units="$work/A$A-units.csv" '
    # mean g per unit over every point sample of the frames (state 1, disconnected: g = 0)
    {
      i = int($1 / dx); j = int($2 / dx)
      if (i < 0) i = 0; if (i >= nx) i = nx - 1
      if (j < 0) j = 0; if (j >= ny) j = ny - 1
      s[i, j] += ($4 == 0 ? $3 : 0); n[i, j]++
    }
    END {
      print "i,j,x,y,g,n" > units
      for (j = 0; j < ny; j++) for (i = 0; i < nx; i++) if ((i, j) in n)
        printf "%d,%d,%.5f,%.5f,%.6g,%d\n", i, j, (i + 0.5) * dx, (j + 0.5) * dx, s[i, j] / n[i, j], n[i, j] > units
    }'
  # mass left (diagnostics column mass) and points leaving per frame over 280 ... 300
  awk -F, -v A="$A" 'NR == 282 { m0 = $6; n0 = $11 } NR == 302 { m1 = $6; n1 = $11 }
    END { printf "A = %s: mass in the silo %.1f -> %.1f kg/m over frames 280-300 (%.2f kg/(m s)), %.1f points leaving a frame\n",
          A, m0, m1, (m0 - m1) / (20 / 240), (n0 - n1) / 20 }' "$run/diagnostics.csv"
  # the spread of g across the slice heights: sqrt(sum g (x - L/2)^2 / sum g)
  awk -F, -v dx=$dx -v W=$W -v L=0.595 'NR > 1 { sg[$2] += $5; sx[$2] += $5 * ($3 - L / 2)^2; if ($5 > mg[$2]) mg[$2] = $5 }
    END { for (h = 1; h <= 3; h++) { j = int((1 + 0.5 * h) * W / dx)
            printf "  y = %.1f W: largest unit g %.3g 1/s, spread of g about the centre line %.3f m\n",
              1 + 0.5 * h, mg[j], sqrt(sx[j] / sg[j]) } }' "$work/A$A-units.csv"
done
gnuplot -e "d1='$work/A0.1'; d2='$work/A0.5'; d3='$work/A1'; out='$out/dk-silo-fig8.png'" \
  "$src/figures/dk-silo-fig8.gp"
