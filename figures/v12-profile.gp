# v12-profile.gp: steady annular shear (verification/V12-annular-shear), the
# azimuthal velocity v_theta / (Omega R_i) against the distance from the
# turning inner cylinder in grain diameters, (r - R_i)/d, linear (left) and
# on a log axis (right; the [HS21] Fig. 9 right panel and its inset): the
# NGF run (points, rings of half a unit averaged over the last quarter),
# the steady radial NGF of verification/ngf1d (line), the local model's run
# (open points) and its closed form (dashed), whose motion stops at the band
# edge R_c where the nonlocal creep decays exponentially.
#
# Inputs (override with gnuplot -e "dir='...'; out='...'"):
#   dir   directory holding compare.csv (r, v of the run, v of the reference),
#         local-profile.csv (r, v, n) and ref-profile.csv (ngf1d annulus),
#         written by verification/V12-annular-shear/check
#   out   PNG written

if (!exists("dir")) dir = '.'
if (!exists("out")) out = 'v12-profile.png'
Ri = 0.06; d = 0.001; W = 0.01 * 0.06    # R_i [m], grain [m], wall speed [m/s]

set terminal pngcairo size 1200,520 font ",11"
set output out
set datafile separator comma
set multiplot layout 1,2 title "Annular shear, R_i = 60 mm, R_o = 80 mm, P = 100 Pa, {/Symbol W} = 0.01 rad/s, d = 1 mm, A = 0.48"
set grid lc rgb "#dddddd"
set xlabel "(r - R_i) / d"
set ylabel "v_{/Symbol q} / ({/Symbol W} R_i)"
set xrange [0:20]
set key top right box opaque

set yrange [-0.05:1.05]
plot dir.'/ref-profile.csv' every ::1 u (($1 - Ri) / d):($6 / W) w l lw 2 lc rgb "#1f77b4" t "NGF, steady 1D (ngf1d)", \
     dir.'/compare.csv' u (($1 - Ri) / d):2 w p pt 7 ps 0.6 lc rgb "#1f77b4" t "NGF, granmpm", \
     dir.'/ref-profile.csv' every ::1 u (($1 - Ri) / d):($7 / W) w l lw 2 dt 2 lc rgb "#d62728" t "local, closed form", \
     dir.'/local-profile.csv' every ::1 u (($1 - Ri) / d):2 w p pt 6 ps 0.6 lc rgb "#d62728" t "local, granmpm"

set logscale y
set yrange [1e-4:1.5]
set format y "10^{%T}"
set key bottom left box opaque
plot dir.'/ref-profile.csv' every ::1 u (($1 - Ri) / d):($6 / W) w l lw 2 lc rgb "#1f77b4" t "NGF, steady 1D (ngf1d)", \
     dir.'/compare.csv' u (($1 - Ri) / d):($2 > 0 ? $2 : 1/0) w p pt 7 ps 0.6 lc rgb "#1f77b4" t "NGF, granmpm", \
     dir.'/ref-profile.csv' every ::1 u (($1 - Ri) / d):($7 > 0 ? $7 / W : 1/0) w l lw 2 dt 2 lc rgb "#d62728" t "local, closed form", \
     dir.'/local-profile.csv' every ::1 u (($1 - Ri) / d):($2 > 0 ? $2 : 1/0) w p pt 6 ps 0.6 lc rgb "#d62728" t "local, granmpm"
unset multiplot
