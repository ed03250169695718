#!/usr/bin/env bash
# [HS21] Fig. 19 analogue: the slice through the middle of the draining 3D
# silo (inputs/silo3d.conf, a quarter with mirror planes x = 0 and z = 0,
# with [HS21]'s hyperelastic NGF as in its Fig. 19; about 7 minutes on one
# core), at 0.6, 1.2 and 2.4 s: the points with
# z <= 1 cm, mirrored about x = 0 to show the whole width, coloured by speed
# (top row) and by plastic shear rate (bottom row).
#   figures/hs21-fig19.sh OUTDIR
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
granmpm=${GRANMPM:-$src/src/app/granmpm}
out=${1:?usage: hs21-fig19.sh OUTDIR}
work=$out/hs21-fig19.d
mkdir -p "$work"
run=$work/silo3d-ngf
# once per output directory (scripts/run-once: a finished run is kept, an
# interrupted one goes on from its checkpoint)
OMP_NUM_THREADS=${OMP_NUM_THREADS:-1} "$src/scripts/run-once" "$run" "$granmpm" run \
  "$src/inputs/silo3d.conf" --quiet --output "$run" \
  --set time.t_end=2.4 --set time.frame_dt=0.05 --set material.model=ngf_hyper \
  --set material.p_sample=point --set output.checkpoint_wall=300
speed= gdp= titles=
for t in 0.6 1.2 2.4; do
  f=$(awk -v t="$t" 'BEGIN { printf "%d", t / 0.05 + 0.5 }')
  "$granmpm" extract "$run" --frame "$f" --z-range 0:0.01 --fields x,y,vx,vy,vz,gdot_p |
    awk -F, -v a="$work/speed-$t.csv" -v b="$work/gdp-$t.csv" '
      NR == 1 { print "x,y,speed" > a; print "x,y,gdot_p" > b; next }
      { v = sqrt($3 * $3 + $4 * $4 + $5 * $5)
        for (s = -1; s <= 1; s += 2) {            # the point and its mirror image
          printf "%.6g,%s,%.6g\n", s * $1, $2, v > a
          printf "%.6g,%s,%s\n", s * $1, $2, $6 > b } }'
  speed="$speed $work/speed-$t.csv"
  gdp="$gdp $work/gdp-$t.csv"
  titles="$titles${titles:+|}t = $t s"
done
gnuplot -e "files='$speed'; titles='$titles'; layout='1 3'; cblabel='speed [m/s]'; \
  cbmin=0; cbmax=0.6; xmin=-0.16; xmax=0.16; ymin=-0.04; ymax=0.18; width=1500; height=450; \
  psize=0.35; outfile='$work/speed.png'; suptitle='3D silo, mid-plane slice (z <= 1 cm): speed'" \
  "$src/figures/snapshots.gp"
gnuplot -e "files='$gdp'; titles='$titles'; layout='1 3'; cblabel='plastic shear rate [1/s]'; \
  cbmin=0; cbmax=20; xmin=-0.16; xmax=0.16; ymin=-0.04; ymax=0.18; width=1500; height=450; \
  psize=0.35; outfile='$work/gdp.png'; suptitle='3D silo, mid-plane slice (z <= 1 cm): plastic shear rate'" \
  "$src/figures/snapshots.gp"
# the two rows in one picture
gnuplot -e "set terminal pngcairo size 1500,900; set output '$out/hs21-fig19.png'; \
  set multiplot layout 2,1; unset border; unset tics; set xrange [0:1500]; set yrange [0:450]; \
  set size ratio -1; plot '$work/speed.png' binary filetype=png with rgbimage notitle; \
  plot '$work/gdp.png' binary filetype=png with rgbimage notitle; unset multiplot"
