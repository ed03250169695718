# dk-silo-fig2b.gp: [DK-silo] Fig. 2(b), the flow/no-flow phase diagram of
# the NGF inclined chute, redrawn from our runs: each run of the sweep
# (scripts/sweep-hstop) is a point, blue dot if it flows, grey square if it
# stopped (kinetic energy per unit mass below 1e-10 J/kg), with the analytic
# boundary H = Hstop(theta) of [DK-silo] eq. 3.1 (black line).
#
# Inputs (override with gnuplot -e "data='...'; out='...'"):
#   data   the sweep's CSV: scripts/sweep-hstop --out DIR -> DIR/hstop.csv
#          (angle_deg,H_m,Hstop_m,H_over_Hstop,t_final_s,ke_final,state,predicted)
#   out    PNG written
#   A, mu_s, mu_2, d   material of the sweep (defaults: [DK-silo] Fig. 2(b))
# verification/V7-ngf-chute/check (full mode) produces the CSV and calls this.

if (!exists("data")) data = 'hstop.csv'
if (!exists("out"))  out  = 'dk-silo-fig2b.png'
if (!exists("A"))    A    = 0.25
if (!exists("mu_s")) mu_s = 0.3819
if (!exists("mu_2")) mu_2 = 1.5
if (!exists("d"))    d    = 0.005

set terminal pngcairo size 800,600 font ",11"
set output out
set datafile separator comma
set title "[DK-silo] Fig. 2(b) redrawn: NGF chute, A = 0.25, mu_s = 0.3819, mu_2 = 1.5"
set xlabel "incline angle theta [deg]"
set ylabel "H / d"
set grid lc rgb "#dddddd"
set key top right box opaque
set samples 500

th_s = atan(mu_s) * 180 / pi
th_2 = atan(mu_2) * 180 / pi
hstop(t) = (t > th_s && t < th_2) ? pi * A / 2 * sqrt((mu_2 - tan(t * pi / 180)) / ((mu_2 - mu_s) * (tan(t * pi / 180) - mu_s))) : 1/0
set xrange [20:42]
set yrange [0:5]

plot [th_s + 0.01:42] hstop(x) w l lw 2 lc rgb "black" t "eq. 3.1: H_{stop}/d", \
     data u 1:(strcol(7) eq "stopped" ? $2 / d : 1/0) w p pt 5 ps 1.3 lc rgb "#808080" t "stopped (KE < 1e-10 J/kg)", \
     data u 1:(strcol(7) eq "flowing" ? $2 / d : 1/0) w p pt 7 ps 1.2 lc rgb "#1f4fd0" t "flowing"
