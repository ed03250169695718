# dk15-fig9.gp: [DK15] Fig. 9 redrawn from an incline sweep
# (scripts/sweep-incline): against time, for every tilt angle, the mean mu of
# the layer (sum m tau / sum m p), the depth-averaged speed and the
# depth-averaged acceleration (granmpm extract RUN --series).
# Below atan(mu_s) nothing flows; between atan(mu_s) and atan(mu_2) mu tends
# to tan(angle) and the speed to a constant; above atan(mu_2) mu tends to mu_2
# and the acceleration to g (sin - mu_2 cos) > 0.
#
# |v| and |a| are drawn on log scales (the 20 deg line is the elastic
# oscillation left by the loading, ~1e-4 m/s).
#
# Inputs (override with gnuplot -e "dir='...'; angles='...'; out='...'"):
#   dir     sweep directory holding aANGLE/series.csv
#   angles  space-separated list of angles to draw
#   mu_2    for the dashed line (default 0.6435)
#   out     PNG written

if (!exists("dir"))    dir = 'sweep-incline'
if (!exists("angles")) angles = '19 20 21 22 23 24 25 26 27 28 29 30 34'
if (!exists("mu_2"))   mu_2 = 0.6435
if (!exists("out"))    out = 'dk15-fig9.png'
file(a) = sprintf("%s/a%s/series.csv", dir, a)
n = words(angles)
col(i) = hsv2rgb(0.75 * (i - 1) / (n > 1 ? n - 1 : 1), 0.85, 0.85)

set terminal pngcairo size 1600,560 font ",11"
set output out
set datafile separator comma
set grid lc rgb "#dddddd"
set multiplot layout 1,3 title "[DK15] Fig. 9 redrawn: inclined plane, h = 0.2 m, angles ".word(angles,1)." ... ".word(angles,n)." deg (atan mu_s = 20.9, atan mu_2 = 32.8)"
set xlabel "t [s]"
set key outside right top font ",9" spacing 0.9 samplen 1.5

set title "mean mu of the layer"
set ylabel "mu"
set yrange [0.3:0.7]
plot for [i=1:n] file(word(angles,i)) u 1:5 every ::2 w l lw 1.5 lc rgb col(i) t word(angles,i)." deg", \
     mu_2 w l dt 2 lc rgb "#555555" t "mu_2"

set title "depth-averaged speed"
set ylabel "v_x [m/s]"
set logscale y
set yrange [1e-6:200]
set format y "10^{%L}"
plot for [i=1:n] file(word(angles,i)) u 1:(abs($2)) every ::2 w l lw 1.5 lc rgb col(i) t word(angles,i)." deg"
unset logscale y

set title "depth-averaged acceleration"
set ylabel "dv_x/dt [m/s^2]"
set logscale y
set yrange [1e-5:5]
amax = word(angles, n) + 0.0
ainf = 9.8 * (sin(amax * pi / 180) - mu_2 * cos(amax * pi / 180))
plot for [i=1:n] file(word(angles,i)) u 1:(abs($4)) every ::2 w l lw 1.5 lc rgb col(i) t word(angles,i)." deg", \
     (ainf > 0 ? ainf : 1/0) w l dt 2 lc rgb "#555555" t sprintf("a_{inf}, %g deg", amax)
unset multiplot
