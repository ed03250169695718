# dk-silo-fig8.gp: [DK-silo] Fig. 8 redrawn: the fluidity g (log scale) of
# the flowing silo, W/d = 5, for A = 0.1, 0.5 and 1 (left to right),
# averaged over frames 280 ... 300 and over each mesh unit; disconnected
# points count with g = 0, so the free fall above the orifice is darkest;
# units that held no point are white.
#
# Inputs (gnuplot -e "d1='...'; ..."):
#   d1, d2, d3  data prefixes: PREFIX-units.csv (i,j,x,y,g,n: unit indices,
#               centre [m], mean g [1/s], point samples), one per A
#   t1, t2, t3  panel titles (default A = 0.1, 0.5, 1)
#   gmin, gmax  colour range of g [1/s] (default 1e-2 ... 1e1); lower
#               values, zero included, take the bottom colour
#   dx, dy, L, H, W  unit size, silo width, mesh height, orifice [m]
#   out         PNG written
if (!exists("d1")) d1 = 'A0.1'
if (!exists("d2")) d2 = 'A0.5'
if (!exists("d3")) d3 = 'A1'
if (!exists("t1")) t1 = 'A = 0.1'
if (!exists("t2")) t2 = 'A = 0.5'
if (!exists("t3")) t3 = 'A = 1'
if (!exists("gmin")) gmin = 1e-2
if (!exists("gmax")) gmax = 1e1
if (!exists("dx")) dx = 0.0175
if (!exists("dy")) dy = 0.0175
if (!exists("L")) L = 0.595
if (!exists("H")) H = 0.6125
if (!exists("W")) W = 0.14
if (!exists("out")) out = 'dk-silo-fig8.png'

set terminal pngcairo size 1500,560 font ",10"
set output out
set datafile separator comma
dirs = d1." ".d2." ".d3
titles = t1."|".t2."|".t3
ttl(i) = system(sprintf("echo '%s' | cut -d'|' -f%d", titles, i))
lg(g) = log10(g < gmin ? gmin : (g > gmax ? gmax : g))

set multiplot title "[DK-silo] Fig. 8 redrawn: log_{10} g of the flowing silo, W/d = 5 (d = 0.028 m), averaged over frames 280-300 (t = 1.167-1.25 s) and over each mesh unit"
set size ratio -1
set xrange [0:L]
set yrange [0:H]
set xtics 0.1 font ",8"
set ytics 0.1 font ",8"
set cbtics font ",8"
unset key
set palette rgbformulae 7,5,15
set cbrange [log10(gmin):log10(gmax)]
set style fill solid 1.0 noborder
set xlabel "x [m]" font ",9"
set ylabel "y [m]" font ",9"
set colorbox user origin 0.935, 0.12 size 0.012, 0.7
set cblabel "log_{10} g [1/s] (g <= 10^{-2} and disconnected: bottom colour)" font ",9"
do for [i = 1:3] {
  set lmargin at screen 0.045 + (i - 1) * 0.3
  set rmargin at screen 0.045 + (i - 1) * 0.3 + 0.26
  set tmargin at screen 0.88
  set bmargin at screen 0.1
  if (i > 1) { unset ylabel }
  set title ttl(i) font ",10"
  set arrow 1 from L / 2 - W / 2, 0 to L / 2 + W / 2, 0 nohead lw 3 lc rgb "#00b0ff" front
  plot word(dirs, i)."-units.csv" u 3:4:(dx / 2):(dy / 2):(lg($5)) every ::1 w boxxyerror lc palette
}
unset multiplot
