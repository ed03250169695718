# dthesis-fig4-3.gp: [D-thesis] Fig. 4-3 redrawn: the steady downward velocity
# across the vertical chute (80 units, one point per unit), local model
# against its closed form (App. A.1) and steady nonlocal fluidity against the
# 1D reference (verification/ngf1d vchute --equation kk). Points: the velocity
# that carries each material point over the last 0.25 s (its displacement);
# small grey points: the points' own (FLIP) velocities.
#
# Inputs (gnuplot -e "dir='...'; out='...'"):
#   dir  directory with local-80x1-profile.csv and linear-80x1-profile.csv
#        (x, v_disp, v_flip, v_ref) and the references local-80x1-ref.csv,
#        linear-80x1-ref.csv (ngf1d output, x from -L/2) from
#        verification/V8-vertical-chute/case
#   out  PNG written
if (!exists("dir")) dir = '.'
if (!exists("out")) out = 'dthesis-fig4-3.png'
set terminal pngcairo size 900,620 font ",11"
set output out
set datafile separator comma
set title "[D-thesis] Fig. 4-3 redrawn: vertical chute, 80 units, 1 point per unit"
set xlabel "x [m]"
set ylabel "downward velocity [m/s]"
set grid lc rgb "#dddddd"
set key bottom center box opaque spacing 1.1
set xrange [0:1]
set yrange [0:0.024]
loc = dir.'/local-80x1-profile.csv'
nl = dir.'/linear-80x1-profile.csv'
plot loc u 1:3 every 7 w p pt 7 ps 0.25 lc rgb "#bbbbbb" t "FLIP point velocities", \
     nl  u 1:3 every 7 w p pt 7 ps 0.25 lc rgb "#bbbbbb" notitle, \
     dir.'/local-80x1-ref.csv' u ($1 + 0.5):2 w l lw 2.5 lc rgb "#1f77b4" t "local, closed form (App. A.1)", \
     loc u 1:2 every 5 w p pt 6 ps 0.7 lc rgb "#1f77b4" t "local, granmpm", \
     dir.'/linear-80x1-ref.csv' u ($1 + 0.5):4 w l lw 2.5 lc rgb "#d62728" t "nonlocal, 1D reference (ngf1d)", \
     nl  u 1:2 every 5 w p pt 4 ps 0.7 lc rgb "#d62728" t "nonlocal (steady solve), granmpm"
