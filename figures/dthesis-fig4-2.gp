# dthesis-fig4-2.gp: [D-thesis] Fig. 4-2 redrawn: the material points of the
# vertical chute (80 x 80 units, one point per unit, steady fluidity with g
# read linearly) at 1.25 s, coloured by their vertical velocity.
# Inputs (gnuplot -e "data='...'; out='...'"):
#   data  CSV x,y,vy with a header (granmpm extract RUN --fields x,y,vy)
#   out   PNG written
if (!exists("data")) data = 'points.csv'
if (!exists("out")) out = 'dthesis-fig4-2.png'
set terminal pngcairo size 760,680 font ",11"
set output out
set datafile separator comma
set title "[D-thesis] Fig. 4-2 redrawn: vertical chute, points coloured by v_y at 1.25 s\n(80 x 80 units, 1 point per unit, steady fluidity, g read linearly)"
set size ratio -1
set xrange [0:1]
set yrange [0:1]
set xlabel "x [m]"
set ylabel "y [m]"
set cblabel "v_y [m/s]"
set palette rgbformulae 33,13,10
unset key
plot data u 1:2:3 every ::1 w p pt 5 ps 0.45 lc palette
