# dk-silo-fig2d.gp: [DK-silo] Fig. 2(d) redrawn: the NGF stopping height of
# glass beads against the incline angle, with the common limit mu_2 of the
# local law (solid blue) and with no limit, mu_2 = infinity (dotted red):
# the threshold found by the steady 1D solver verification/ngf1d (lines),
# eq. 3.1 of [DK-silo] (thin grey, under them). Pouliquen's (1999)
# glass-bead data of the paper's figure are not in its text and not drawn.
#
# Inputs (override with gnuplot -e "data='...'; out='...'"):
#   data   CSV theta_deg,dk_eq31,dk_solver,inf_eq31,inf_solver (Hstop/d),
#          written by figures/dk-silo-fig2d.sh
#   A, mu_s, mu_2   the material (defaults: glass beads, [DK-silo] Fig. 2(d))
#   out    PNG written

if (!exists("data")) data = 'hstop.csv'
if (!exists("out"))  out  = 'dk-silo-fig2d.png'
if (!exists("A"))    A    = 0.48
if (!exists("mu_s")) mu_s = 0.3819
if (!exists("mu_2")) mu_2 = 0.6435

set terminal pngcairo size 800,600 font ",11"
set output out
set datafile separator comma
set title sprintf("[DK-silo] Fig. 2(d) redrawn: NGF H_{stop} of glass beads, A = %g, mu_s = %g", A, mu_s)
set xlabel "incline angle theta [deg]"
set ylabel "H_{stop} / d"
set grid lc rgb "#dddddd"
set key top right box opaque
set xrange [20:40]
set yrange [0:12]
th_s = atan(mu_s) * 180 / pi
th_2 = atan(mu_2) * 180 / pi
set arrow 1 from th_s, graph 0 to th_s, graph 1 nohead dt 3 lc rgb "#808080"
set label 1 sprintf("atan(mu_s) = %.1f deg", th_s) at th_s + 0.3, graph 0.95 font ",9"
set arrow 2 from th_2, graph 0 to th_2, graph 1 nohead dt 3 lc rgb "#808080"
set label 2 sprintf("atan(mu_2) = %.1f deg", th_2) at th_2 + 0.3, graph 0.6 font ",9"
set label 3 "not drawn: Pouliquen's (1999) glass-bead data\nof the paper's figure (not in its text)" \
  at graph 0.2, graph 0.75 font ",9"
plot data u 1:($1 < th_2 ? $2 : 1/0) skip 1 w l lw 5 lc rgb "#c8c8c8" notitle, \
     data u 1:4 skip 1 w l lw 5 lc rgb "#c8c8c8" t "eq. 3.1 (both)", \
     data u 1:($1 < th_2 ? $3 : 1/0) skip 1 w l lw 2 lc rgb "#1f4fd0" t sprintf("mu_2 = %g (solver)", mu_2), \
     data u 1:5 skip 1 w l lw 2 dt 3 lc rgb "#d62728" t "mu_2 = infinity (solver)"
