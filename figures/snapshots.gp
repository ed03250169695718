# Panels of point snapshots, coloured by the third column of each file.
# gnuplot -e "files='a.csv b.csv'; titles='t=0|t=1'; layout='1,2'; \
#   cblabel='...'; cbmin=0; cbmax=1; xmin=0; xmax=1; ymin=0; ymax=1; \
#   outfile='x.png'; width=1200; height=600" snapshots.gp
# Each CSV has a header row and x,y,value columns. titles: '|'-separated.
# states=1 draws two colours (value 0 dense: blue, 1 disconnected: red), no colour box.
if (!exists("states")) states = 0
if (!exists("width")) width = 1200
if (!exists("height")) height = 700
if (!exists("psize")) psize = 0.3
if (!exists("suptitle")) suptitle = ''
set terminal pngcairo size width,height noenhanced font ",10"
set output outfile
set datafile separator ","
n = words(files)
rows = int(word(layout, 1)); cols = int(word(layout, 2))
set multiplot layout rows,cols title suptitle
set size ratio -1
set xrange [xmin:xmax]
set yrange [ymin:ymax]
set key off
if (states) {
  set palette defined (0 '#4060c0', 1 '#e03020')
  set cbrange [0:1]
  unset colorbox
} else {
  set palette rgbformulae 33,13,10
  set cbrange [cbmin:cbmax]
}
set cblabel cblabel
do for [i = 1:n] {
  t = system(sprintf("echo '%s' | cut -d'|' -f%d", titles, i))
  set title t
  plot word(files, i) using 1:2:3 skip 1 with points pt 7 ps psize lc palette
}
unset multiplot
