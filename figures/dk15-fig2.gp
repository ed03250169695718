# dk15-fig2.gp: [DK15] Fig. 2 redrawn: collapse of columns of aspect ratio
# 2, 1 and 0.5 (left to right; half-width 0.2 m, right half simulated).
# Rows 1-3: material points coloured by the equivalent plastic shear rate
# gdot_p at t0, t1, t2; row 4: pressure at t2 smoothed through the grid
# ([DK15] eqs. 4.1-4.3, granmpm extract --smooth).
#
# Inputs (override with gnuplot -e "d1='...'; ..."):
#   d1, d2, d3  run directories' extracted data prefix: for each of them the
#               files PREFIX-f0.csv, -f1.csv, -f2.csv (x,y,gdot_p from
#               granmpm extract --fields x,y,gdot_p) and PREFIX-p.csv
#               (granmpm extract --smooth of the frame at t2)
#   t0, t1, t2  the times of the frames [s]; a1, a2, a3 the aspect ratios
#   out         PNG written

if (!exists("d1")) d1 = 'a2'
if (!exists("d2")) d2 = 'a1'
if (!exists("d3")) d3 = 'a0.5'
if (!exists("a1")) a1 = '2'
if (!exists("a2")) a2 = '1'
if (!exists("a3")) a3 = '0.5'
if (!exists("t0")) t0 = '0'
if (!exists("t1")) t1 = '0.5'
if (!exists("t2")) t2 = '2'
if (!exists("out")) out = 'dk15-fig2.png'

set terminal pngcairo size 1500,1000 font ",10"
set output out
set datafile separator comma
set multiplot layout 4,3 title "[DK15] Fig. 2 redrawn: column collapse, a = ".a1.", ".a2.", ".a3." (rows: gdot_p at t = ".t0.", ".t1.", ".t2." s; pressure smoothed through the grid at ".t2." s)"
set size ratio -1
set xrange [0:1.1]
set yrange [0:0.42]
set xtics 0.2 font ",8"
set ytics 0.1 font ",8"
set cbtics font ",8"
unset key
set lmargin 5
set rmargin 8
set palette defined (0 "#000033", 1 "#2c7bb6", 2 "#abd9e9", 3 "#fdae61", 4 "#d7191c")
dirs = d1." ".d2." ".d3
ars = a1." ".a2." ".a3
times = t0." ".t1." ".t2
do for [k=0:2] {
  do for [i=1:3] {
    set title sprintf("a = %s, t = %s s, gdot_p [1/s]", word(ars,i), word(times,k+1)) font ",9"
    set cbrange [0:20]
    plot sprintf("%s-f%d.csv", word(dirs,i), k) u 1:2:3 every ::1 w p pt 7 ps 0.25 lc palette
  }
}
do for [i=1:3] {
  set title sprintf("a = %s, t = %s s, smoothed p [Pa]", word(ars,i), t2) font ",9"
  set cbrange [0:*]
  plot sprintf("%s-p.csv", word(dirs,i)) u 1:2:4 every ::1 w p pt 7 ps 0.25 lc palette
}
unset multiplot
