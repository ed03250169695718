# Final state of a run: its points coloured by their own pressure (left) and
# by the nodally smoothed pressure of [DK15] eqs. 4.1-4.3 (right, the way
# the paper plots pressure), on one colour scale; stress-free points
# (disconnected, state 1) in grey on both.
# gnuplot -e "datafile='run/final-state.csv'; outfile='final.png'" final-state.gp
# The CSV comes from: granmpm extract RUNDIR --smooth --frame last
# (columns x, y, p, p_smooth, gdot_p, state).
if (!exists("datafile")) datafile = 'final-state.csv'
if (!exists("outfile")) outfile = 'final-state.png'
set terminal pngcairo size 1200,760 noenhanced font ",11"
set output outfile
set datafile separator ","
set xlabel "x [m]"
set ylabel "y [m]"
set cblabel "pressure p [Pa]"
set palette rgbformulae 33,13,10
set key off
# the scale from the smoothed field: a point's own pressure above it takes
# the top colour
stats datafile using 4 skip 1 nooutput
set cbrange [0:STATS_max > 0 ? STATS_max : 1]
set multiplot layout 2,1
set size ratio -1
set title "final state: each point's own pressure"
plot datafile using 1:2:($6 == 0 ? $3 : 1/0) skip 1 with points pt 7 ps 0.9 lc palette, \
     datafile using 1:($6 == 0 ? 1/0 : $2) skip 1 with points pt 7 ps 0.9 lc rgb "gray70"
set title "final state: nodally smoothed pressure ([DK15] eqs. 4.1-4.3)"
plot datafile using 1:2:($6 == 0 ? $4 : 1/0) skip 1 with points pt 7 ps 0.9 lc palette, \
     datafile using 1:($6 == 0 ? 1/0 : $2) skip 1 with points pt 7 ps 0.9 lc rgb "gray70"
unset multiplot
