# dthesis-figA.gp: [D-thesis] App. A, Figs. A-1 to A-3 redrawn: steady
# downward velocity across the vertical chute (rough walls at x = 0 and
# 1 m) from the reference solutions, one line per parameter value: the local
# closed form of App. A.1 or the steady nonlocal equation of App. A.2
# (verification/ngf1d vchute).
#
# Inputs (gnuplot -e "files='...'; titles='...'; ..."):
#   files   space-separated CSVs x,v (x from wall to wall, a header row),
#           written by figures/dthesis-figA-*.sh
#   titles  their legend entries, '|'-separated
#   local   optional: a local profile (x,v) drawn dashed for comparison
#   ltitle  its legend entry
#   ttl     the figure title
#   out     PNG written
if (!exists("files"))  files = ''
if (!exists("titles")) titles = ''
if (!exists("local"))  local = ''
if (!exists("ltitle")) ltitle = 'local'
if (!exists("ttl"))    ttl = '[D-thesis] App. A redrawn'
if (!exists("out"))    out = 'dthesis-figA.png'
ttl_i(i) = system(sprintf("echo '%s' | cut -d'|' -f%d", titles, i))
set terminal pngcairo size 950,620 font ",11"
set output out
set datafile separator comma
set title ttl
set xlabel "x [m]"
set ylabel "downward velocity [m/s]"
set grid lc rgb "#dddddd"
set key outside right top box opaque spacing 1.1
set xrange [0:1]
set yrange [0:*]
colours = "#1f77b4 #ff7f0e #2ca02c #d62728 #9467bd #8c564b #e377c2 #17becf"
if (local ne '') {
  plot for [i = 1:words(files)] word(files, i) u 1:2 skip 1 w l lw 2 lc rgb word(colours, i) t ttl_i(i), \
       local u 1:2 skip 1 w l lw 2 dt 2 lc rgb "black" t ltitle
} else {
  plot for [i = 1:words(files)] word(files, i) u 1:2 skip 1 w l lw 2 lc rgb word(colours, i) t ttl_i(i)
}
