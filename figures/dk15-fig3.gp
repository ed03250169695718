# dk15-fig3.gp: [DK15] Fig. 3 redrawn from a column-collapse sweep
# (scripts/sweep-collapse): run-out (x_front - w)/w against aspect ratio
# a = H/w on log-log axes, with our two power fits (a <= 2 and a >= 4, as
# verification/V4-collapse/check computes them) and the fits of [DK15]
# Table 3 (2.28 a for a <~ 2.83, 3.24 a^0.66 above) and of Staron & Hinch
# (2005, 2D DEM: 2.5 a, 3.25 a^0.71) for comparison.
#
# Inputs (override with gnuplot -e "results='...'; out='...'"):
#   results  sweep-collapse results.csv (a,height,t_end,t,front,runout,...)
#   c1, e1, c2, e2: our fit coefficients and exponents (from the V4 check)
#   out      PNG written

if (!exists("results")) results = 'results.csv'
if (!exists("out"))     out = 'dk15-fig3.png'
if (!exists("c1"))      c1 = 1/0
if (!exists("e1"))      e1 = 1/0
if (!exists("c2"))      c2 = 1/0
if (!exists("e2"))      e2 = 1/0

set terminal pngcairo size 900,700 font ",11"
set output out
set datafile separator comma
set grid lc rgb "#dddddd"
set logscale xy
set xrange [0.3:16]
set yrange [0.3:30]
set xlabel "aspect ratio a = H / w"
set ylabel "run-out (x_f - w) / w"
set title "[DK15] Fig. 3 redrawn: column collapse run-out, half-width w = 0.2 m"
set key top left box opaque
set samples 200
dk(x) = x < 2.83 ? 2.28 * x : 3.24 * x**0.66
sh(x) = x < 2.0 ? 2.5 * x : 3.25 * x**0.71
f1(x) = x <= 2.83 ? c1 * x**e1 : 1/0
f2(x) = x >= 2.0 ? c2 * x**e2 : 1/0
plot dk(x) w l lw 2 dt 2 lc rgb "#1f77b4" t "[DK15] Table 3: 2.28 a, 3.24 a^{0.66}", \
     sh(x) w l lw 1 dt 3 lc rgb "#7f7f7f" t "Staron \\& Hinch (2005): 2.5 a, 3.25 a^{0.71}", \
     f1(x) w l lw 2 lc rgb "#d62728" t sprintf("ours, a <= 2: %.2f a^{%.2f}", c1, e1), \
     f2(x) w l lw 2 lc rgb "#ff7f0e" t sprintf("ours, a >= 4: %.2f a^{%.2f}", c2, e2), \
     results u 1:6 every ::1 w p pt 7 ps 1.6 lc rgb "#d62728" t "MPM runs"
