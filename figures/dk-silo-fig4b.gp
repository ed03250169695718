# dk-silo-fig4b.gp: [DK-silo] Fig. 4(b) redrawn: an arch forming above the
# orifice of the silo (A = 1, W/d = 1), a row of frames of the lower part of
# the silo. Top row: material points coloured by speed (log scale); bottom
# row: the same points coloured by state (dense blue, disconnected red).
#
# Inputs (override with gnuplot -e "files='...'; ..."):
#   files    space-separated CSVs, one per frame, with a header row and the
#            columns x,y,speed,state (from granmpm extract RUN --frame N
#            --fields x,y,vx,vy,state, speed = |v|)
#   titles   '|'-separated panel titles, one per file
#   out      PNG written
#   ymax     top of the region drawn [m] (default 0.3); x spans the silo
#   vmin, vmax  speed colour range [m/s] (log scale; default 1e-4 ... 1)
#   label    the case, for the title (default 'A = 1, W/d = 1')
#   wx0, wx1 the orifice [m] (default 0.2275 ... 0.3675), marked on the floor

if (!exists("files")) files = 'f0.csv f1.csv f2.csv f3.csv f4.csv'
if (!exists("titles")) titles = 't = 0|t = 0.1 s|t = 0.2 s|t = 0.4 s|t = 1.5 s'
if (!exists("out")) out = 'dk-silo-fig4b.png'
if (!exists("ymax")) ymax = 0.3
if (!exists("vmin")) vmin = 1e-4
if (!exists("vmax")) vmax = 1
if (!exists("label")) label = 'A = 1, W/d = 1'
if (!exists("wx0")) wx0 = 0.2275
if (!exists("wx1")) wx1 = 0.3675
if (!exists("L")) L = 0.595

n = words(files)
pw = 380                       # panel width in pixels
set terminal pngcairo size n * pw + 90, 2 * pw * ymax / L + 170 font ",10"
set output out
set datafile separator comma
set multiplot title "[DK-silo] Fig. 4(b) redrawn: arch formation, ".label." (lower part of the silo; top: speed, bottom: dense / disconnected state)"
set size ratio -1
set xrange [0:L]
set yrange [0:ymax]
set xtics 0.1 font ",8"
set ytics 0.1 font ",8"
set cbtics font ",8"
unset key
# the orifice: a thick black line on the floor where the floor is open
set arrow 1 from wx0, 0 to wx1, 0 nohead lw 4 lc rgb "#ffaa00" front
left = 0.035; gap = 0.004
pwf = (1.0 - left - 0.055) / n
title(i) = system(sprintf("echo '%s' | cut -d'|' -f%d", titles, i))
do for [i = 1:n] {
  # row 1: speed
  set origin left + (i - 1) * pwf, 0.47
  set size pwf - gap, 0.44
  set title title(i) font ",10"
  set logscale cb
  set cbrange [vmin:vmax]
  set format cb "10^{%T}"
  set palette rgbformulae 33,13,10
  if (i == n) { set colorbox user origin left + n * pwf - gap * 0.5, 0.56 size 0.008, 0.27; set cblabel "speed [m/s]" font ",9" } else { unset colorbox }
  plot word(files, i) u 1:2:($3 > vmin ? $3 : vmin) every ::1 w p pt 7 ps 0.45 lc palette
  # row 2: state
  set origin left + (i - 1) * pwf, 0.02
  set size pwf - gap, 0.44
  set title ""
  unset logscale cb
  set cbrange [0:1]
  set palette defined (0 '#4060c0', 1 '#e03020')
  unset colorbox
  unset cblabel
  plot word(files, i) u 1:2:4 every ::1 w p pt 7 ps 0.45 lc palette
}
unset multiplot
