# dk-silo-fig2c.gp: [DK-silo] Fig. 2(c), steady velocity profiles of the NGF
# chute at theta = 27 deg for H/Hstop = 1.9, 2.9, 4.8, 6.8, 19 (H = 10, 15,
# 25, 35, 98 mm), normalised by the surface speed of the 1D reference:
# our runs (points, one per row of material points) and the steady 1D
# reference verification/ngf1d (lines of the same colour), with the two
# limits of [DK-silo] section 6: 1 - cos(pi z / 2H) near Hstop (black dashed)
# and Bagnold 1 - (1 - z/H)^(3/2) for H >> Hstop (black dotted).
#
# Inputs (override with gnuplot -e "dir='...'; out='...'"):
#   dir   directory holding H<mm>-profile.csv (y,vx,vx_ref: binned run and
#         reference at the bin centres), written by verification/V7-ngf-chute/check
#   out   PNG written
#   Hs    the layer thicknesses in mm (default "10 15 25 35 98")

if (!exists("dir")) dir = '.'
if (!exists("out")) out = 'dk-silo-fig2c.png'
if (!exists("Hs"))  Hs  = "10 15 25 35 98"
hstop = 5.17300126   # mm, eq. 3.1 at 27 deg

set terminal pngcairo size 800,650 font ",11"
set output out
set datafile separator comma
set title "[DK-silo] Fig. 2(c) redrawn: NGF chute at 27 deg, v / v_{ref}(H)"
set xlabel "v / v_{ref}(H)"
set ylabel "z / H"
set grid lc rgb "#dddddd"
set key bottom right box opaque spacing 1.1
set xrange [0:1.1]
set yrange [0:1]
file(h) = sprintf("%s/H%s-profile.csv", dir, h)
colours = "#1f77b4 #ff7f0e #2ca02c #d62728 #9467bd"

# surface speed of the reference of each file (its last row)
array vtop[words(Hs)]
do for [i = 1:words(Hs)] {
  stats file(word(Hs, i)) u 3 nooutput
  vtop[i] = STATS_max
}

set parametric
set trange [0:1]

plot 1 - cos(pi * t / 2), t w l lw 2 dt 2 lc rgb "black" t "1 - cos(pi z / 2H)", \
     1 - (1 - t)**1.5, t w l lw 2 dt 3 lc rgb "black" t "Bagnold 1 - (1 - z/H)^{3/2}", \
     for [i = 1:words(Hs)] file(word(Hs, i)) u ($3 / vtop[i]):($1 / (word(Hs, i) / 1000.0)) \
         w l lw 1.5 lc rgb word(colours, i) notitle, \
     for [i = 1:words(Hs)] file(word(Hs, i)) u ($2 / vtop[i]):($1 / (word(Hs, i) / 1000.0)) \
         every 2 w p pt 7 ps 0.6 lc rgb word(colours, i) \
         t sprintf("H/H_{stop} = %.1f", word(Hs, i) / hstop)
