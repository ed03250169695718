# dthesis-fig4-4.gp: [D-thesis] Fig. 4-4 redrawn: steady downward velocity
# across the vertical chute for the runs of the resolution study (g read
# linearly in the unit), the points' own (FLIP) velocities, with the 1D
# reference (ngf1d vchute --equation kk, black).
# Inputs (gnuplot -e "files='...'; ..."):
#   files   space-separated CSVs x,v_disp,v_flip,v_ref
#           (verification/V8-vertical-chute/case NAME-profile.csv)
#   titles  '|'-separated legend entries
#   ref     the reference (ngf1d output: comment lines, then x,g,gdot,v with
#           x from -L/2)
#   out     PNG written
if (!exists("files")) files = ''
if (!exists("titles")) titles = ''
if (!exists("out")) out = 'dthesis-fig4-4.png'
ttl_i(i) = system(sprintf("echo '%s' | cut -d'|' -f%d", titles, i))
set terminal pngcairo size 1000,640 font ",11"
set output out
set datafile separator comma
set datafile commentschars "#x"
set title "[D-thesis] Fig. 4-4 redrawn: vertical chute, nonlocal, g read linearly: point velocities"
set xlabel "x [m]"
set ylabel "downward velocity [m/s]"
set grid lc rgb "#dddddd"
set key outside right top box opaque spacing 1.1
set xrange [0:1]
set yrange [0:0.024]
colours = "#1f77b4 #ff7f0e #2ca02c #d62728 #9467bd"
points = "9 7 5 13 11"
plot ref u ($1 + 0.5):4 w l lw 2 lc rgb "black" t "1D reference (ngf1d)", \
     for [i = 1:words(files)] word(files, i) u 1:3 every ::1 w p pt (word(points, i) + 0) ps 0.6 lc rgb word(colours, i) t ttl_i(i)
