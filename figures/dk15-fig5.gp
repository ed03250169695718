# [DK15] Fig. 5: left, mass remaining in the (full) silo against time for
# several orifices, with the 1200 ... 900 kg band of the fit; right, the
# steady flow rate against the orifice on log-log axes with the Beverloo fit
# Q = C rho sqrt(g) D^1.5 (ours and [DK15]'s C = 1.42) and the free power fit.
# gnuplot -e "sweep='DIR'; sizes='D06 D10 D14 D18'; outfile='x.png'" dk15-fig5.gp
# DIR is a scripts/sweep-silo output (DIR/flow-rates.csv, DIR/D??/diagnostics.csv;
# column 16 of the diagnostics is mass_region, the half silo).
if (!exists("outfile")) outfile = 'dk15-fig5.png'
if (!exists("sizes")) sizes = 'D06 D10 D14 D18'
set terminal pngcairo size 1400,600 noenhanced font ",11"
set output outfile
set datafile separator ","
set multiplot layout 1,2
set title "mass remaining in the silo"
set xlabel "t [s]"
set ylabel "mass [kg] (full silo, 1 m thick)"
set yrange [0:1600]
set key top right
set object 1 rect from graph 0, first 900 to graph 1, first 1200 fc rgb "#e8e8e8" behind
plot for [i = 1:words(sizes)] sprintf("%s/%s/diagnostics.csv", sweep, word(sizes, i)) \
  using 1:(2 * $16) skip 1 with lines lw 2 title sprintf("D = %d cm", int(word(sizes, i)[2:]))
unset object 1
set title "steady flow rate (fit while 1200 ... 900 kg remain)"
set logscale xy
set xlabel "orifice D [m]"
set ylabel "Q [kg/s] (per m of thickness)"
set yrange [*:*]
set xrange [0.04:0.3]
rho = 1500.0; g = 9.8
f(x) = log(a) + b * log(x)
a = 5000; b = 1.5
fit f(x) sprintf("%s/flow-rates.csv", sweep) using 1:(log($3)) skip 1 via a, b
c(x) = log(C) + 1.5 * log(x) + log(rho * sqrt(g))
C = 1.4
fit c(x) sprintf("%s/flow-rates.csv", sweep) using 1:(log($3)) skip 1 via C
set key top left
plot sprintf("%s/flow-rates.csv", sweep) using 1:3 skip 1 with points pt 7 ps 1.5 title "granmpm", \
  C * rho * sqrt(g) * x ** 1.5 with lines lw 2 title sprintf("C rho sqrt(g) D^1.5, C = %.3f", C), \
  1.42 * rho * sqrt(g) * x ** 1.5 with lines lw 2 dt 2 title "[DK15]: C = 1.42", \
  a * x ** b with lines lw 2 dt 3 lc rgb "black" title sprintf("free fit: power %.3f", b)
unset multiplot
