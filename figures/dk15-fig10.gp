# dk15-fig10.gp: [DK15] Fig. 10 redrawn from an incline sweep
# (scripts/sweep-incline). Left: depth-averaged speed against tilt angle,
# our runs (points) against eq. 4.7 (line). Right: the 25 deg velocity
# profile (points) against eq. 4.6 (line).
#
# Inputs (override with gnuplot -e "results='...'; profile='...'; out='...'"):
#   results  sweep-incline results.csv (angle,t_end,t,vbar,vbar_ref,...)
#   profile  granmpm extract RUN25 --profile 40 --range 0:0.2 (y,vx,vy,mass,n)
#   xi, K25, h, rho, mu_s, mu_2: the material and layer (defaults: inputs/incline-reduced.conf)
#   out      PNG written

if (!exists("results")) results = 'results.csv'
if (!exists("profile")) profile = 'profile.csv'
if (!exists("out"))     out = 'dk15-fig10.png'
if (!exists("xi"))      xi = 0.279 / (0.005 * sqrt(2450.0))
if (!exists("h"))       h = 0.2
if (!exists("rho"))     rho = 1500.0
if (!exists("mu_s"))    mu_s = 0.3819
if (!exists("mu_2"))    mu_2 = 0.6435
g = 9.8
d2r(a) = a * pi / 180
K(a) = (tan(d2r(a)) - mu_s) / (mu_2 - tan(d2r(a)))
vbar(a) = (tan(d2r(a)) > mu_s && tan(d2r(a)) < mu_2) ? 0.4 * xi * h * K(a) * sqrt(rho * cos(d2r(a))) * sqrt(g * h) : 1/0
v25(y) = (2.0 / 3.0) * xi * K(25) * sqrt(rho * cos(d2r(25))) * (h**1.5 - (h - y)**1.5) / sqrt(h) * sqrt(g * h)

set terminal pngcairo size 1300,560 font ",11"
set output out
set datafile separator comma
set grid lc rgb "#dddddd"
set multiplot layout 1,2 title "[DK15] Fig. 10 redrawn: inclined plane, local mu(I) (h = 0.2 m, dx = 0.005 m)"

set title "depth-averaged speed against tilt angle"
set xlabel "tilt angle [deg]"
set ylabel "depth-averaged speed v_x [m/s]"
set logscale y
set xrange [20.5:32.9]
set yrange [0.01:100]
set key top left box opaque
set arrow 1 from first atan(mu_s) * 180 / pi, graph 0 to first atan(mu_s) * 180 / pi, graph 1 nohead dt 2 lc rgb "#888888"
set arrow 2 from first atan(mu_2) * 180 / pi, graph 0 to first atan(mu_2) * 180 / pi, graph 1 nohead dt 2 lc rgb "#888888"
set samples 400
plot vbar(x) w l lw 2 lc rgb "#1f77b4" t "eq. 4.7", \
     results u 1:(valid(5) ? $4 : 1/0) every ::1 w p pt 7 ps 1.3 lc rgb "#d62728" t "MPM, last frame"

unset logscale y
unset arrow 1
unset arrow 2
set title "velocity profile at 25 deg"
set xlabel "v_x [m/s]"
set ylabel "height above the base y [m]"
set xrange [0:1.2 * v25(h)]
set yrange [0:h]
set key bottom right
plot sample [yy=0:h] '+' u (v25(yy)):(yy) w l lw 2 lc rgb "#1f77b4" t "eq. 4.6", \
     profile u (column(5) > 0 ? column(2) : 1/0):1 every ::1 w p pt 7 ps 1.1 lc rgb "#d62728" t "MPM (40 bins)"
unset multiplot
