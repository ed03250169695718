# dk-silo-fig4a.gp: [DK-silo] Fig. 4(a) redrawn: the silo jamming phase
# diagram, nonlocal amplitude A against opening W/d (inputs/silo-jam.conf,
# W fixed, d = W / (W/d)). Each run of the sweep (scripts/sweep-jam) is a
# point classified by `granmpm extract RUN --jam` as in [DK-silo] 7.2: blue
# circle flowing, grey square static, orange triangle unsure. Runs off the
# paper's lattice (A in 0.1 ... 3, W/d in 1 ... 5) are drawn smaller. The
# black line W/d = c A through the origin separates static from flowing
# runs; with a traced boundary (sweep-jam --trace) its brackets and their
# least-squares line through the origin are drawn too.
#
# Inputs (override with gnuplot -e "data='...'; ..."):
#   data     the sweep's CSV: sweep-jam --out DIR -> DIR/jam.csv
#            (A,W_over_d,d_m,class,t_zero_s,velocity_vote,leaving_per_frame,
#            outflow_vote,wall_s)
#   c        slope of the boundary line (no line if absent); clo, chi the
#            range of slopes with the fewest runs on the wrong side and
#            nwrong the number of those runs (for the legend, optional)
#   trace    DIR/trace.csv (A,wd_static,class_lo,wd_hi,class_hi,runs), and
#   ctrace   the slope of its least-squares line (both optional)
#   out      PNG written

if (!exists("data")) data = 'jam.csv'
if (!exists("out")) out = 'dk-silo-fig4a.png'
if (!exists("clo")) clo = ''
if (!exists("chi")) chi = ''
if (!exists("nwrong")) nwrong = ''
if (!exists("c")) c = NaN
havetrace = exists("trace") && exists("ctrace")
if (!havetrace) { trace = data; ctrace = NaN }

set terminal pngcairo size 1050,650 font ",11"
set output out
set datafile separator comma
set title "[DK-silo] Fig. 4(a) redrawn: silo jamming phase diagram (inputs/silo-jam.conf)"
set xlabel "nonlocal amplitude A"
set ylabel "W / d"
set rmargin at screen 0.72
set key at screen 0.74, 0.92 left top Left reverse box opaque font ",10" spacing 1.3 width 1
set grid xtics ytics back lw 1 lc rgb "#c8c8c8"
set xrange [0:3.3]
set yrange [0:5.6]
set xtics 0.5
set ytics 1

# the paper's lattice: symbol sizes
onlattice(a, w) = (w == int(w) && w >= 1 && w <= 5 && (abs(a - 0.1) < 1e-9 || (abs(2 * a - int(2 * a + 0.5)) < 1e-9 && a >= 0.5 && a <= 3)))
ps(a, w) = onlattice(a, w) ? 2.0 : 1.2

ctitle = c == c ? sprintf("W/d = %.3g A", c) : ""
if (c == c && clo ne '') {
  set label 1 sprintf("the lines W/d = c A with the fewest\nruns on the wrong side (static above,\nflowing below; unsure never count):\nc in (%s, %s), %s run%s wrong;\ndrawn: the middle of that range%s", \
    clo, chi, nwrong, nwrong eq "1" ? "" : "s", havetrace ? "\n\ntraced brackets: W/d static (bottom)\n... not static (top), and the least-\nsquares line through the origin" : "") \
    at screen 0.74, 0.62 left font ",9"
}
set label 3 "small symbols: runs off the\npaper's lattice" at screen 0.74, 0.12 left font ",9"

set samples 200
plot \
  c * x w l lw 2 lc rgb "black" t ctitle, \
  ctrace * x w l lw 2 dt 2 lc rgb "#c02020" t (havetrace ? sprintf("traced, fit: W/d = %.3g A", ctrace) : ""), \
  trace u 1:(havetrace && strcol(3) eq "static" && strcol(5) ne "static" ? ($2 + $4) / 2 : 1/0):2:4 every ::1 \
     w yerrorbars pt 1 ps 1.5 lw 1.5 lc rgb "#c02020" t (havetrace ? "traced brackets" : ""), \
  data u 1:(strcol(4) eq "flowing" ? $2 : 1/0):(ps($1, $2)) every ::1 w p pt 7 ps variable lc rgb "#1f4fd0" t "flowing", \
  data u 1:(strcol(4) eq "static" ? $2 : 1/0):(ps($1, $2)) every ::1 w p pt 5 ps variable lc rgb "#808080" t "static", \
  data u 1:(strcol(4) eq "unsure" ? $2 : 1/0):(ps($1, $2)) every ::1 w p pt 9 ps variable lc rgb "#ff8c00" t "unsure"
