# dk-silo-fig5.gp: [DK-silo] Fig. 5 redrawn: pressure in the silo for A = 1
# and W/d = 1, 2, 5, averaged over frames 350 ... 360 (t = 1.458 ... 1.5 s)
# and over each mesh unit. (a), top row: the unit averages, white where no
# point was in the unit in any of those frames; (b), bottom: the pressure
# along the vertical centre line against height, one line per run.
#
# Inputs (override with gnuplot -e "d1='...'; ..."):
#   d1, d2, d3  data prefixes, one per run: PREFIX-units.csv (columns
#               i,j,x,y,p,n: unit indices, unit centre [m], mean smoothed
#               pressure [Pa], number of point samples) and PREFIX-centre.csv
#               (y,p,n: the two unit columns either side of the centre line
#               x = L/2 pooled, one row per unit row with points)
#   r1, r2, r3  their W/d (default 1, 2, 5); A (default 1)
#   classes     '|'-separated classifier verdicts for the titles (optional)
#   dx, dy      unit size [m] (default 0.0175); L, H silo width and height
#   pmax        top of the colour scale [Pa] (default: automatic)
#   out         PNG written

if (!exists("d1")) d1 = 'wd1'
if (!exists("d2")) d2 = 'wd2'
if (!exists("d3")) d3 = 'wd5'
if (!exists("r1")) r1 = '1'
if (!exists("r2")) r2 = '2'
if (!exists("r3")) r3 = '5'
if (!exists("A")) A = '1'
if (!exists("classes")) classes = '||'
if (!exists("dx")) dx = 0.0175
if (!exists("dy")) dy = 0.0175
if (!exists("L")) L = 0.595
if (!exists("H")) H = 0.6125
if (!exists("out")) out = 'dk-silo-fig5.png'

set terminal pngcairo size 1500,1000 font ",10"
set output out
set datafile separator comma
dirs = d1." ".d2." ".d3
rs = r1." ".r2." ".r3
cls(i) = system(sprintf("echo '%s' | cut -d'|' -f%d", classes, i))
colors = "#e0409a #2ca02c #1f4fd0"     # pink, green, blue as the paper

set multiplot title "[DK-silo] Fig. 5 redrawn: pressure for A = ".A.", W/d = ".r1.", ".r2.", ".r3.", averaged over frames 350-360 (t = 1.458-1.5 s) and over each mesh unit"

# (a) unit averages
# one colour scale for the three panels
if (!exists("pmax")) {
  pmax = 0
  do for [i = 1:3] {
    stats word(dirs, i)."-units.csv" u 5 every ::1 nooutput
    if (STATS_max > pmax) { pmax = STATS_max }
  }
}
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
set xlabel "x [m]" font ",9"
set ylabel "y [m]" font ",9"
# fixed margins: three panels of the same size, one colour box at the right
set colorbox user origin 0.935, 0.49 size 0.012, 0.36
set cblabel "p [Pa]" font ",9"
do for [i = 1:3] {
  set lmargin at screen 0.045 + (i - 1) * 0.3
  set rmargin at screen 0.045 + (i - 1) * 0.3 + 0.26
  set tmargin at screen 0.86
  set bmargin at screen 0.47
  if (i > 1) { unset ylabel }
  c = cls(i)
  set title sprintf("(a) W/d = %s%s", word(rs, i), c eq "" ? "" : " (".c.")") font ",10"
  set arrow 1 from L / 2 - 4 * dx, 0 to L / 2 + 4 * dx, 0 nohead lw 3 lc rgb "#ffaa00" front
  plot word(dirs, i)."-units.csv" u 3:4:(dx / 2):(dy / 2):5 every ::1 w boxxyerror lc palette
}
unset arrow 1

# (b) centre line
set size noratio
set lmargin at screen 0.1
set rmargin at screen 0.9
set tmargin at screen 0.38
set bmargin at screen 0.06
unset colorbox
set xtics auto
set ytics auto
set title "(b) pressure along the vertical centre line (units either side of x = L/2)" font ",10"
set xlabel "height y [m]" font ",9"
set ylabel "p [Pa]" font ",9"
set xrange [0:H]
set yrange [0:*]
set key top right box opaque
set grid lc rgb "#dddddd"
plot for [i = 1:3] word(dirs, i)."-centre.csv" u 1:2 every ::1 w lp lw 2 pt 7 ps 0.6 lc rgb word(colors, i) t "W/d = ".word(rs, i)
unset multiplot
