# dk-silo-fig10.gp: [DK-silo] Fig. 10 redrawn: the smoothed pressure of the
# coarse (top row) and refined (bottom row) silos, A = 1, W/d = 1 (left)
# and 5 (right), averaged over frames 349 ... 351 and over each unit of
# the run's mesh; white where a unit held no point.
# Inputs (gnuplot -e "d1='...'; ..."):
#   d1 ... d4   CSVs i,j,x,y,p,n (unit indices, centre [m], mean pressure
#               [Pa], samples): coarse W/d = 1, coarse 5, refined 1, refined 5
#   dx1 ... dx4 their unit sizes [m]; t1 ... t4 panel titles
#   pmax        top of the colour scale [Pa] (default: the largest mean)
#   out         PNG written
if (!exists("out")) out = 'dk-silo-fig10.png'
if (!exists("L")) L = 0.595
if (!exists("H")) H = 0.6125
files = d1." ".d2." ".d3." ".d4
array dxs[4] = [dx1, dx2, dx3, dx4]
titles = t1."|".t2."|".t3."|".t4
ttl(i) = system(sprintf("echo '%s' | cut -d'|' -f%d", titles, i))
set datafile separator comma
if (!exists("pmax")) {
  pmax = 0
  do for [i = 1:4] {
    stats word(files, i) u 5 every ::1 nooutput
    if (STATS_max > pmax) { pmax = STATS_max }
  }
}
set terminal pngcairo size 1200,1250 font ",10"
set output out
set multiplot title "[DK-silo] Fig. 10 redrawn: smoothed pressure averaged over frames 349-351 and each unit, A = 1; coarse (top) and refined (bottom)"
set size ratio -1
set xrange [0:L]
set yrange [0:H]
set xtics 0.1 font ",8"
set ytics 0.1 font ",8"
set cbtics font ",8"
unset key
set palette rgbformulae 22,13,-31
set cbrange [0:pmax]
set style fill solid 1.0 noborder
set cblabel "p [Pa]" font ",9"
set colorbox user origin 0.93, 0.3 size 0.012, 0.4
set arrow 1 from 0.2275, 0 to 0.3675, 0 nohead lw 4 lc rgb "#ffaa00" front
do for [i = 1:4] {
  set lmargin at screen 0.06 + ((i - 1) % 2) * 0.43
  set rmargin at screen 0.06 + ((i - 1) % 2) * 0.43 + 0.38
  set tmargin at screen (i <= 2 ? 0.94 : 0.48)
  set bmargin at screen (i <= 2 ? 0.53 : 0.07)
  set title ttl(i) font ",10"
  h = dxs[i] / 2
  plot word(files, i) u 3:4:(h):(h):5 every ::1 w boxxyerror lc palette
}
unset multiplot
