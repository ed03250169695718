# dk-silo-fig6.gp: [DK-silo] Fig. 6 redrawn: two flowing silos (W/d = 5)
# differing only in A. Top row: material points coloured by speed, iso-speed
# lines at 0.05 ... 0.35 m/s (of the mesh-unit mean speed) and the slice
# heights 1.5 W, 2 W, 2.5 W (pink, green, blue); bottom row: the vertical
# velocity across those slices, points (small) and their mean per unit
# column (lines).
#
# Inputs (override with gnuplot -e "d1='...'; ..."):
#   d1, d2   data prefixes, one per run, each with
#              PREFIX-points.csv  x,y,vx,vy,speed,state of every point
#              PREFIX-slices.csv  h,x,vy: points within dy/2 of height h
#                                 (h = 1, 2, 3 for 1.5 W, 2 W, 2.5 W)
#              PREFIX-bins.csv    h,x,vy,n: their mean per unit column
#              PREFIX-grid.dat    x y speed: unit-mean speed on the unit
#                                 centres, gnuplot grid format (NaN if empty);
#                                 PREFIX-contours.dat, .csv are written
#                                 from it
#   t1, t2   panel titles
#   W        orifice width [m] (default 0.14); L, H silo width, mesh height
#   vmax     top of the speed colour scale [m/s] (default 0.5)
#   out      PNG written

if (!exists("d1")) d1 = 'A0.1'
if (!exists("d2")) d2 = 'A1'
if (!exists("t1")) t1 = 'A = 0.1, frame 70'
if (!exists("t2")) t2 = 'A = 1, frame 86'
if (!exists("W")) W = 0.14
if (!exists("L")) L = 0.595
if (!exists("H")) H = 0.6125
if (!exists("vmax")) vmax = 0.5
if (!exists("out")) out = 'dk-silo-fig6.png'

hcol = "#e0409a #2ca02c #1f4fd0"     # 1.5 W, 2 W, 2.5 W
hname = "1.5W 2W 2.5W"
dirs = d1." ".d2
titles = t1."|".t2
ttl(i) = system(sprintf("echo '%s' | cut -d'|' -f%d", titles, i))

# the iso-speed lines, as tables of line segments
set contour base
unset surface
set view map
set cntrparam levels discrete 0.05, 0.10, 0.15, 0.20, 0.25, 0.30, 0.35
set cntrparam linear
do for [i = 1:2] {
  set table word(dirs, i)."-contours.dat"
  splot word(dirs, i)."-grid.dat" u 1:2:3 w l
  unset table
  # as CSV (x,y; a blank line between the pieces of line)
  system(sprintf("awk 'NF == 3 && $1 !~ /^#/ { print $1 \",\" $2; next } { print \"\" }' '%s-contours.dat' > '%s-contours.csv'", word(dirs, i), word(dirs, i)))
}
unset contour
reset

set terminal pngcairo size 1400,1250 font ",10"
set output out
set datafile separator comma
hcol = "#e0409a #2ca02c #1f4fd0"
hname = "1.5W 2W 2.5W"
set multiplot title "[DK-silo] Fig. 6 redrawn: flowing silos, W/d = 5 (d = 0.028 m, W = 0.14 m), A = 0.1 (left) and A = 1 (right)"

# top row: speed
set size ratio -1
set xrange [0:L]
set yrange [0:H]
set xtics 0.1 font ",8"
set ytics 0.1 font ",8"
set cbtics font ",8"
set xlabel "x [m]" font ",9"
set ylabel "y [m]" font ",9"
unset key
set palette rgbformulae 33,13,10
set cbrange [0:vmax]
set cblabel "speed [m/s]" font ",9"
do for [i = 1:2] {
  set origin (i - 1) * 0.5, 0.42
  set size 0.5, 0.55
  set title ttl(i) font ",10"
  do for [h = 1:3] {
    set arrow h from 0, (1 + 0.5 * h) * W to L, (1 + 0.5 * h) * W nohead lw 2 dt 2 lc rgb word(hcol, h) front
  }
  plot word(dirs, i)."-points.csv" u 1:2:5 every ::1 w p pt 7 ps 0.3 lc palette, \
       word(dirs, i)."-contours.csv" u 1:2 w l lw 1 lc rgb "black"
}
unset arrow 1; unset arrow 2; unset arrow 3

# bottom row: vertical velocity across the slices
set size noratio
set xtics auto
set ytics auto
set xrange [0:L]
set yrange [*:*]
set xlabel "x [m]"
set ylabel "v_y [m/s]"
set key bottom right box opaque font ",9"
set grid lc rgb "#dddddd"
# one v_y range for both
vmin = 0
do for [i = 1:2] {
  stats word(dirs, i)."-slices.csv" u 3 every ::1 nooutput
  if (STATS_min < vmin) { vmin = STATS_min }
}
set yrange [vmin * 1.05:0.05]
do for [i = 1:2] {
  set origin (i - 1) * 0.5, 0.0
  set size 0.5, 0.42
  set title ttl(i)." : v_y across the slices" font ",10"
  plot for [h = 1:3] word(dirs, i)."-slices.csv" u 2:($1 == h ? $3 : 1/0) every ::1 w p pt 7 ps 0.35 lc rgb word(hcol, h) notitle, \
       for [h = 1:3] word(dirs, i)."-bins.csv" u 2:($1 == h ? $3 : 1/0) every ::1 w l lw 2 lc rgb word(hcol, h) t "y = ".word(hname, h)
}
unset multiplot
