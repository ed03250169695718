# dthesis-fig4-5.gp: [D-thesis] Figs. 4-5, 4-9 (errors against points per
# unit, 20 units across, g read linearly / as the element mean) and 4-6
# (errors against units across, one point per unit) redrawn from the V8
# runs, beside the thesis' Table 4.2 (open symbols; exponents as read in
# verification/V8-vertical-chute/README.md). Relative and absolute L2 errors
# (absolute over the points of the thesis' square domain) of the velocity
# that carries the points (closed symbols, solid) and of the points' own FLIP
# velocities (crosses, dashed), which is what the thesis measures.
#
# Inputs (gnuplot -e "dir='...'; out='...'"): dir holds linear-20.dat,
# element-20.dat (20 units, by points per unit) and linear-1.dat (one point
# per unit, by units), rows "ppe units rel_grid abs_grid rel_point abs_point
# thesis_rel thesis_abs", written by figures/dthesis-fig4-5.sh; out the PNG.
if (!exists("dir")) dir = '.'
if (!exists("out")) out = 'dthesis-fig4-5.png'
set terminal pngcairo size 1300,460 font ",10"
set output out
set multiplot layout 1,3 title "[D-thesis] Figs. 4-5, 4-9, 4-6 redrawn: vertical chute velocity errors (rel. and abs. L2)"
set logscale xy
set format y "10^{%L}"
set grid lc rgb "#dddddd"
set key top left box opaque font ",9" spacing 1.0
set yrange [1e-5:1]
lin = dir.'/linear-20.dat'
ele = dir.'/element-20.dat'
one = dir.'/linear-1.dat'

set title "20 units, g read linearly (Fig. 4-5)"
set xlabel "points per unit (one direction)"
set ylabel "L2 error"
set xrange [0.8:10]
plot lin u 1:3 w lp pt 7 lc rgb "#d62728" t "relative, grid velocity", \
     lin u 1:4 w lp pt 5 lc rgb "#1f77b4" t "absolute, grid velocity", \
     lin u 1:5 w lp dt 2 pt 2 lc rgb "#d62728" t "relative, point (FLIP) velocity", \
     lin u 1:6 w lp dt 2 pt 2 lc rgb "#1f77b4" t "absolute, point (FLIP) velocity", \
     lin u 1:7 w p pt 6 ps 1.5 lc rgb "#d62728" t "relative, [D-thesis]", \
     lin u 1:8 w p pt 4 ps 1.5 lc rgb "#1f77b4" t "absolute, [D-thesis]"

set title "20 units, g the element mean (Fig. 4-9)"
plot ele u 1:3 w lp pt 7 lc rgb "#d62728" t "relative, grid velocity", \
     ele u 1:4 w lp pt 5 lc rgb "#1f77b4" t "absolute, grid velocity", \
     ele u 1:5 w lp dt 2 pt 2 lc rgb "#d62728" t "relative, point (FLIP) velocity", \
     ele u 1:6 w lp dt 2 pt 2 lc rgb "#1f77b4" t "absolute, point (FLIP) velocity", \
     ele u 1:7 w p pt 6 ps 1.5 lc rgb "#d62728" t "relative, [D-thesis]", \
     ele u 1:8 w p pt 4 ps 1.5 lc rgb "#1f77b4" t "absolute, [D-thesis]"

set title "one point per unit, g read linearly (Fig. 4-6)"
set xlabel "units across"
set xrange [15:100]
plot one u 2:3 w lp pt 7 lc rgb "#d62728" t "relative, grid velocity", \
     one u 2:4 w lp pt 5 lc rgb "#1f77b4" t "absolute, grid velocity", \
     one u 2:5 w lp dt 2 pt 2 lc rgb "#d62728" t "relative, point (FLIP) velocity", \
     one u 2:6 w lp dt 2 pt 2 lc rgb "#1f77b4" t "absolute, point (FLIP) velocity", \
     one u 2:7 w p pt 6 ps 1.5 lc rgb "#d62728" t "relative, [D-thesis]", \
     one u 2:8 w p pt 4 ps 1.5 lc rgb "#1f77b4" t "absolute, [D-thesis]"
unset multiplot
