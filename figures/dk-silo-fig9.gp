# dk-silo-fig9.gp: [DK-silo] Fig. 9 redrawn: the speed of every material
# point (log scale) in the coarse (top row) and refined (bottom row) silos,
# A = 1, W/d = 1 (left, static) and W/d = 5 (right, flowing).
# Inputs (gnuplot -e "files='...'; ..."):
#   files   four CSVs x,y,speed,state with a header: coarse W/d = 1, coarse
#           W/d = 5, refined W/d = 1, refined W/d = 5
#   titles  '|'-separated panel titles
#   vmin, vmax  speed colour range [m/s] (log; default 1e-4 ... 1)
#   out     PNG written
if (!exists("files")) files = ''
if (!exists("titles")) titles = ''
if (!exists("vmin")) vmin = 1e-4
if (!exists("vmax")) vmax = 1
if (!exists("L")) L = 0.595
if (!exists("H")) H = 0.6125
if (!exists("out")) out = 'dk-silo-fig9.png'
ttl(i) = system(sprintf("echo '%s' | cut -d'|' -f%d", titles, i))
set terminal pngcairo size 1200,1250 font ",10"
set output out
set datafile separator comma
set multiplot title "[DK-silo] Fig. 9 redrawn: point speeds, A = 1; coarse (top, units of 17.5 mm) and refined (bottom, 8.75 mm)"
set size ratio -1
set xrange [0:L]
set yrange [0:H]
set xtics 0.1 font ",8"
set ytics 0.1 font ",8"
set cbtics font ",8"
unset key
set logscale cb
set cbrange [vmin:vmax]
set format cb "10^{%T}"
set palette rgbformulae 33,13,10
set cblabel "speed [m/s]" font ",9"
set colorbox user origin 0.93, 0.3 size 0.012, 0.4
set arrow 1 from 0.2275, 0 to 0.3675, 0 nohead lw 4 lc rgb "#ffaa00" front
do for [i = 1:4] {
  set lmargin at screen 0.06 + ((i - 1) % 2) * 0.43
  set rmargin at screen 0.06 + ((i - 1) % 2) * 0.43 + 0.38
  set tmargin at screen (i <= 2 ? 0.94 : 0.48)
  set bmargin at screen (i <= 2 ? 0.53 : 0.07)
  set title ttl(i) font ",10"
  plot word(files, i) u 1:2:($3 > vmin ? $3 : vmin) every ::1 w p pt 7 ps (i <= 2 ? 0.3 : 0.15) lc palette
}
unset multiplot
