# dthesis-fig4-5.gp: [D-thesis] Figs. 4-5, 4-9 (errors against points per
# unit, 20 units across, g read linearly / as the element mean) and 4-6
# (errors against units across, one point per unit) redrawn from the V8
# runs, beside the thesis' Table 4.2 (open symbols; exponents as read in
# verification/V8-vertical-chute/README.md). Relative and absolute L2 errors
# of the velocity that carries the points (closed symbols, solid) and of the
# FLIP point velocities (crosses, dashed).
#
# Inputs (gnuplot -e "dir='...'; out='...'"): dir holds linear.dat and
# element.dat, rows "ppe units rel_disp abs_disp rel_flip abs_flip
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
lin = dir.'/linear.dat'
ele = dir.'/element.dat'

set title "20 units, g read linearly (Fig. 4-5)"
set xlabel "points per unit (one direction)"
set ylabel "L2 error"
set xrange [0.8:10]
plot lin u ($2 == 20 ? $1 : NaN):3 w lp pt 7 lc rgb "#d62728" t "relative", \
     lin u ($2 == 20 ? $1 : NaN):4 w lp pt 5 lc rgb "#1f77b4" t "absolute", \
     lin u ($2 == 20 ? $1 : NaN):5 w lp dt 2 pt 2 lc rgb "#d62728" t "relative, FLIP velocity", \
     lin u ($2 == 20 ? $1 : NaN):6 w lp dt 2 pt 2 lc rgb "#1f77b4" t "absolute, FLIP velocity", \
     lin u ($2 == 20 ? $1 : NaN):7 w p pt 6 ps 1.5 lc rgb "#d62728" t "relative, [D-thesis]", \
     lin u ($2 == 20 ? $1 : NaN):8 w p pt 4 ps 1.5 lc rgb "#1f77b4" t "absolute, [D-thesis]"

set title "20 units, g the element mean (Fig. 4-9)"
plot ele u ($2 == 20 ? $1 : NaN):3 w lp pt 7 lc rgb "#d62728" t "relative", \
     ele u ($2 == 20 ? $1 : NaN):4 w lp pt 5 lc rgb "#1f77b4" t "absolute", \
     ele u ($2 == 20 ? $1 : NaN):5 w lp dt 2 pt 2 lc rgb "#d62728" t "relative, FLIP velocity", \
     ele u ($2 == 20 ? $1 : NaN):6 w lp dt 2 pt 2 lc rgb "#1f77b4" t "absolute, FLIP velocity", \
     ele u ($2 == 20 ? $1 : NaN):7 w p pt 6 ps 1.5 lc rgb "#d62728" t "relative, [D-thesis]", \
     ele u ($2 == 20 ? $1 : NaN):8 w p pt 4 ps 1.5 lc rgb "#1f77b4" t "absolute, [D-thesis]"

set title "one point per unit, g read linearly (Fig. 4-6)"
set xlabel "units across"
set xrange [15:100]
plot lin u ($1 == 1 ? $2 : NaN):3 w lp pt 7 lc rgb "#d62728" t "relative", \
     lin u ($1 == 1 ? $2 : NaN):4 w lp pt 5 lc rgb "#1f77b4" t "absolute", \
     lin u ($1 == 1 ? $2 : NaN):5 w lp dt 2 pt 2 lc rgb "#d62728" t "relative, FLIP velocity", \
     lin u ($1 == 1 ? $2 : NaN):6 w lp dt 2 pt 2 lc rgb "#1f77b4" t "absolute, FLIP velocity", \
     lin u ($1 == 1 ? $2 : NaN):7 w p pt 6 ps 1.5 lc rgb "#d62728" t "relative, [D-thesis]", \
     lin u ($1 == 1 ? $2 : NaN):8 w p pt 4 ps 1.5 lc rgb "#1f77b4" t "absolute, [D-thesis]"
unset multiplot
