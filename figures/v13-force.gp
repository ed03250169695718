# v13-force.gp: earth pressure on a moving smooth wall
# (verification/V13-earth-pressure): the coefficient K = 2 F/(gamma H^2) of
# the horizontal force on the wall against its travel over the layer's
# depth H, moved away from the layer (active) and into it (passive), on the
# 2.5 mm mesh (thick) and the 5 mm one (thin), with Rankine's K_a and K_p
# for sin(phi) = mu_s, the at-rest k0 of the fill and, for the rough wall
# (tan(delta) = tan(phi/2), grey), Coulomb's wedge (dotted); the shaded
# band is the plateau the check measures. Below: the points at the end of
# the two fine runs (5 mm of travel) coloured by the plastic shear rate,
# the active wedge sliding down along a band from the wall's heel, the
# passive one pushed up.
#
# Inputs (override with gnuplot -e "dir='...'; out='...'"):
#   dir   directory holding act-K.csv, pas-K.csv, act-q-K.csv, pas-q-K.csv,
#         rough-act-K.csv, rough-pas-K.csv (t, travel, travel/H, F, K, |fy|/F)
#         and act-last.csv, pas-last.csv (x, y, gdot_p), written by
#         verification/V13-earth-pressure/check
#   out   PNG written

if (!exists("dir")) dir = '.'
if (!exists("out")) out = 'v13-force.png'
Ka = 0.4473; Kp = 2.236; K0 = 0.618     # Rankine, sin(phi) = mu_s; Jaky's k0 of the fill
Kac = 0.3982; Kpc = 2.980               # Coulomb, delta = phi/2

set terminal pngcairo size 1200,820 font ",11"
set output out
set datafile separator comma
set multiplot title "Earth pressure on a moving wall, H = 0.1 m, mu(I) with mu_s = 0.3819 ({/Symbol f} = 22.45 deg), 5 mm/s"

set origin 0, 0.4
set size 1, 0.56
set grid lc rgb "#dddddd"
set xlabel "wall travel / H (%)"
set ylabel "K = 2F / ({/Symbol g} H^2)"
set logscale y
set yrange [0.3:3.5]
set ytics (0.3, 0.4, 0.5, 0.6, 0.8, 1, 1.5, 2, 3)
set xrange [0:5.2]
set key outside right top box opaque
set object 1 rect from 0.4, graph 0 to 1.2, graph 1 fc rgb "#eeeeee" fs solid noborder behind
plot Ka w l lw 1.5 dt 2 lc rgb "#1f77b4" t "K_a = 0.447", \
     Kp w l lw 1.5 dt 2 lc rgb "#d62728" t "K_p = 2.236", \
     K0 w l lw 1.5 dt 2 lc rgb "#2ca02c" t "k_0 = 0.618", \
     Kac w l lw 1 dt 3 lc rgb "#555555" t "Coulomb, {/Symbol d} = {/Symbol f}/2", \
     Kpc w l lw 1 dt 3 lc rgb "#555555" notitle, \
     dir.'/act-K.csv' every ::1 u ($3 * 100):5 w l lw 2.5 lc rgb "#1f77b4" t "active, 2.5 mm mesh", \
     dir.'/pas-K.csv' every ::1 u ($3 * 100):5 w l lw 2.5 lc rgb "#d62728" t "passive, 2.5 mm mesh", \
     dir.'/act-q-K.csv' every ::1 u ($3 * 100):5 w l lw 1 lc rgb "#1f77b4" t "active, 5 mm mesh", \
     dir.'/pas-q-K.csv' every ::1 u ($3 * 100):5 w l lw 1 lc rgb "#d62728" t "passive, 5 mm mesh", \
     dir.'/rough-act-K.csv' every ::1 u ($3 * 100):5 w l lw 1.5 lc rgb "#777777" t "rough wall, 2.5 mm", \
     dir.'/rough-pas-K.csv' every ::1 u ($3 * 100):5 w l lw 1.5 lc rgb "#777777" notitle
unset object 1
unset logscale y
unset grid

set size ratio -1
set xrange [-0.012:0.24]
set yrange [0:0.115]
set xtics 0.05
set ytics 0.05
set xlabel "x (m)"
set ylabel "y (m)"
set cblabel "plastic shear rate (1/s)"
set cbrange [0:1]
set palette rgbformulae 33,13,10
unset key
set origin 0, 0.0
set size 0.5, 0.42
set title "active, after 5 mm"
plot dir.'/act-last.csv' every ::1 u 1:2:3 w p pt 5 ps 0.3 lc palette
set origin 0.5, 0.0
set size 0.5, 0.42
set title "passive, after 5 mm"
plot dir.'/pas-last.csv' every ::1 u 1:2:3 w p pt 5 ps 0.3 lc palette
unset multiplot
