#!/usr/bin/env bash
# [DK-silo] Fig. 6: two flowing silos (inputs/silo-jam.conf, W/d = 5, d =
# 0.028 m) differing only in A: A = 0.1 at frame 70 (t = 0.292 s) and A = 1
# at frame 86 (t = 0.358 s). Top row: points coloured by speed, with iso-speed
# lines (0.05 ... 0.35 m/s, from unit averages) and the slice heights 1.5 W,
# 2 W, 2.5 W above the floor; bottom row: vertical velocity across the three
# slices (points within dy/2 of each height, and their mean per unit column).
#   figures/dk-silo-fig6.sh OUTDIR
# The runs come from the shared jamming sweep (figures/jam-sweep.inc:
# $GRANMPM_JAM_SWEEP or OUTDIR/jam-sweep).
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
export GRANMPM=${GRANMPM:-$src/src/app/granmpm}
out=${1:?usage: dk-silo-fig6.sh OUTDIR}
work=$out/dk-silo-fig6.d
mkdir -p "$work"
source "$src/figures/jam-sweep.inc"
wd=5
jam_runs "0.1 1" "$wd"
dx=0.0175 nx=34 ny=35           # the mesh of inputs/silo-jam.conf, x0 = y0 = 0
W=0.14                          # the orifice
for c in "0.1 70" "1 86"; do
  set -- $c
  A=$1 f=$2
  "$GRANMPM" extract "$sweep/runs/A$A-wd$wd" --frame "$f" --fields x,y,vx,vy,state |
    awk -F, -v dx=$dx -v nx=$nx -v ny=$ny -v W=$W -v pre="$work/A$A" '
      NR == 1 { print "x,y,vx,vy,speed,state" > (pre "-points.csv")
                print "h,x,vy" > (pre "-slices.csv"); next }
      {
        x = $1; y = $2; vy = $4; sp = sqrt($3 * $3 + $4 * $4)
        printf "%s,%s,%s,%s,%.6g,%s\n", x, y, $3, vy, sp, $5 > (pre "-points.csv")
        i = int(x / dx); j = int(y / dx)
        if (i < 0) i = 0; if (i >= nx) i = nx - 1
        if (j < 0) j = 0; if (j >= ny) j = ny - 1
        gs[i, j] += sp; gn[i, j]++
        # slices at 1.5 W, 2 W, 2.5 W: points within half a unit
        for (h = 1; h <= 3; h++) {
          yh = (1 + 0.5 * h) * W
          if (y >= yh - dx / 2 && y < yh + dx / 2) {
            printf "%d,%s,%s\n", h, x, vy > (pre "-slices.csv")
            bs[h, i] += vy; bn[h, i]++
          }
        }
      }
      END {
        print "h,x,vy,n" > (pre "-bins.csv")
        for (h = 1; h <= 3; h++) {
          for (i = 0; i < nx; i++) if ((h, i) in bn)
            printf "%d,%.5f,%.6g,%d\n", h, (i + 0.5) * dx, bs[h, i] / bn[h, i], bn[h, i] > (pre "-bins.csv")
        }
        # unit-mean speed on the unit centres for the iso-speed lines (gnuplot
        # grid format: blank line between rows of constant x; empty units NaN)
        for (i = 0; i < nx; i++) {
          for (j = 0; j < ny; j++)
            printf "%.5f %.5f %s\n", (i + 0.5) * dx, (j + 0.5) * dx, ((i, j) in gn) ? sprintf("%.6g", gs[i, j] / gn[i, j]) : "NaN" > (pre "-grid.dat")
          print "" > (pre "-grid.dat")
        }
      }'
done
gnuplot -e "d1='$work/A0.1'; d2='$work/A1'; t1='A = 0.1, frame 70 (t = 0.292 s)'; \
  t2='A = 1, frame 86 (t = 0.358 s)'; W=$W; out='$out/dk-silo-fig6.png'" "$src/figures/dk-silo-fig6.gp"
