# Final state of a run: points coloured by pressure.
# gnuplot -e "datafile='run/final-state.csv'; outfile='final.png'" final-state.gp
# The CSV comes from: granmpm extract RUNDIR --frame last --fields x,y,p,state
if (!exists("datafile")) datafile = 'final-state.csv'
if (!exists("outfile")) outfile = 'final-state.png'
set terminal pngcairo size 1000,600 noenhanced font ",11"
set output outfile
set datafile separator ","
set size ratio -1
set xlabel "x [m]"
set ylabel "y [m]"
set cblabel "pressure p [Pa]"
set palette rgbformulae 33,13,10
set key off
set title "final state (points coloured by pressure)"
# A few points carry pressure spikes several times the lithostatic value;
# clip the colour scale at the mean + 3 standard deviations so the heap's
# gradient shows (clipped points take the top colour).
stats datafile using 3 skip 1 nooutput
set cbrange [0:STATS_mean + 3 * STATS_stddev]
plot datafile using 1:2:3 skip 1 with points pt 7 ps 0.4 lc palette
