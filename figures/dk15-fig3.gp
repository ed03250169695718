# dk15-fig3.gp: [DK15] Fig. 3 redrawn from two column-collapse sweeps
# (scripts/sweep-collapse, 4 x 4 and 2 x 2 points per unit): run-out
# (x_front - w)/w against aspect ratio a = H/w on log-log axes, with our two
# power fits per sweep (a <= 2 and a >= 4, as verification/V4-collapse/check
# computes them) and the fits of [DK15] Table 3 (2.28 a for a <~ 2.83,
# 3.24 a^0.66 above) and of Staron & Hinch (2005, 2D DEM: 2.5 a,
# 3.25 a^0.71) for comparison.
#
# Inputs (override with gnuplot -e "results4='...'; ..."):
#   results4, results2  sweep-collapse results.csv (a,height,t_end,t,front,runout,...)
#   c1_4, e1_4, c2_4, e2_4, c1_2, ...: the fit coefficients and exponents
#   out      PNG written

if (!exists("results4")) results4 = 'results4.csv'
if (!exists("results2")) results2 = 'results2.csv'
if (!exists("out"))     out = 'dk15-fig3.png'

set terminal pngcairo size 950,720 font ",11"
set output out
set datafile separator comma
set grid lc rgb "#dddddd"
set logscale xy
set xrange [0.3:16]
set yrange [0.3:30]
set xlabel "aspect ratio a = H / w"
set ylabel "run-out (x_f - w) / w"
set title "[DK15] Fig. 3 redrawn: column collapse run-out, half-width w = 0.2 m, E = 100 MPa"
set key top left box opaque font ",10"
set samples 200
dk(x) = x < 2.83 ? 2.28 * x : 3.24 * x**0.66
sh(x) = x < 2.0 ? 2.5 * x : 3.25 * x**0.71
f(x, c, e, lo, hi) = (x >= lo && x <= hi) ? c * x**e : 1/0
plot dk(x) w l lw 2.5 dt 2 lc rgb "#1f77b4" t "[DK15] Table 3: 2.28 a, 3.24 a^{0.66}", \
     sh(x) w l lw 1 dt 3 lc rgb "#7f7f7f" t "Staron \\& Hinch (2005): 2.5 a, 3.25 a^{0.71}", \
     f(x, c1_4, e1_4, 0.3, 2.83) w l lw 2 lc rgb "#d62728" t sprintf("4 x 4 points, a <= 2: %.2f a^{%.2f}", c1_4, e1_4), \
     f(x, c2_4, e2_4, 2.0, 16) w l lw 2 lc rgb "#ff7f0e" t sprintf("4 x 4 points, a >= 4: %.2f a^{%.2f}", c2_4, e2_4), \
     results4 u 1:6 every ::1 w p pt 7 ps 1.6 lc rgb "#d62728" t "runs, 4 x 4 points per unit ([DK15]'s)", \
     f(x, c1_2, e1_2, 0.3, 2.83) w l lw 1.5 dt 4 lc rgb "#2ca02c" t sprintf("2 x 2 points, a <= 2: %.2f a^{%.2f}", c1_2, e1_2), \
     f(x, c2_2, e2_2, 2.0, 16) w l lw 1.5 dt 4 lc rgb "#17becf" t sprintf("2 x 2 points, a >= 4: %.2f a^{%.2f}", c2_2, e2_2), \
     results2 u 1:6 every ::1 w p pt 6 ps 1.4 lc rgb "#2ca02c" t "runs, 2 x 2 points per unit (V4 check)"
