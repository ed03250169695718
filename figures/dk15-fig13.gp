# dk15-fig13.gp: [DK15] Fig. 13, the constitutive verification of App. B,
# redrawn from `granmpm constitutive` output: our stress update (points)
# against the rkf45 reference ODE (lines).
#
# Top row: the imposed velocity gradient L, the stress components and the
# plastic strain-rate tensor Dp. Bottom row: observed convergence (relative
# time-integrated L2 error against dt), and the differences ours - reference
# of stress and Dp.
#
# Inputs (override with gnuplot -e "data='...'; conv='...'; out='...'"):
#   data  time series:  granmpm constitutive --dt 1e-3 --output data.csv
#   conv  error table:  granmpm constitutive --converge 1e-3,1e-4,1e-5 --table conv.csv
#   out   PNG written
# verification/V2-constitutive/check (full mode) produces both and calls this.

if (!exists("data")) data = 'dk15-fig13.csv'
if (!exists("conv")) conv = 'dk15-fig13-conv.csv'
if (!exists("out"))  out  = 'dk15-fig13.png'
if (!exists("step")) step = 10   # plot every step-th row of ours as a point

set terminal pngcairo size 1500,900 font ",10"
set output out
set datafile separator comma
set key top left spacing 1.1 samplen 2 box opaque
set grid lc rgb "#dddddd"
set multiplot layout 2,3 title "[DK15] Fig. 13 redrawn: mu(I) stress update (points) against the rkf45 reference ODE (lines)"

c1 = "#1f77b4"; c2 = "#d62728"; c3 = "#2ca02c"; c4 = "#9467bd"
set xlabel "t [s]"
set xrange [0:1.25]

# (a) imposed velocity gradient
set title "(a) velocity gradient L"
set ylabel "L [1/s]"
plot data u "t":"Lxx" w l lw 2 lc rgb c1 t "L_{xx} = L_{yy}", \
     ''   u "t":"Lxy" w l lw 2 lc rgb c2 t "L_{xy}", \
     ''   u "t":"Lyx" w l lw 1 dt 2 lc rgb c3 t "L_{yx}"

# (b) stress components
set title "(b) stress"
set ylabel "{/Symbol s} [Pa]"
set key bottom left
plot data u "t":"ref_sxx" w l lw 1.5 lc rgb c1 t "{/Symbol s}_{xx} rkf45", \
     ''   u "t":"sxx" every step w p pt 6 ps 0.6 lc rgb c1 t "{/Symbol s}_{xx} ours", \
     ''   u "t":"ref_syy" w l lw 1.5 lc rgb c2 t "{/Symbol s}_{yy}", \
     ''   u "t":"syy" every step w p pt 4 ps 0.6 lc rgb c2 notitle, \
     ''   u "t":"ref_szz" w l lw 1.5 lc rgb c3 t "{/Symbol s}_{zz}", \
     ''   u "t":"szz" every step w p pt 8 ps 0.6 lc rgb c3 notitle, \
     ''   u "t":"ref_sxy" w l lw 1.5 lc rgb c4 t "{/Symbol s}_{xy}", \
     ''   u "t":"sxy" every step w p pt 12 ps 0.6 lc rgb c4 notitle

# (c) plastic strain rate
set title "(c) plastic strain rate D^p"
set ylabel "D^p [1/s]"
set key top left
plot data u "t":"ref_dp_xx" w l lw 1.5 lc rgb c1 t "D^p_{xx} rkf45", \
     ''   u "t":"dp_xx" every step w p pt 6 ps 0.6 lc rgb c1 t "D^p_{xx} ours", \
     ''   u "t":"ref_dp_yy" w l lw 1.5 lc rgb c2 t "D^p_{yy}", \
     ''   u "t":"dp_yy" every step w p pt 4 ps 0.6 lc rgb c2 notitle, \
     ''   u "t":"ref_dp_zz" w l lw 1.5 lc rgb c3 t "D^p_{zz}", \
     ''   u "t":"dp_zz" every step w p pt 8 ps 0.6 lc rgb c3 notitle, \
     ''   u "t":"ref_dp_xy" w l lw 1.5 lc rgb c4 t "D^p_{xy}", \
     ''   u "t":"dp_xy" every step w p pt 12 ps 0.6 lc rgb c4 notitle

# (d) convergence
set title "(d) relative time-integrated L2 error"
set xlabel "dt [s]"
set ylabel "error"
set logscale xy
set xrange [*:*]
set format x "10^{%L}"
set format y "10^{%L}"
set key bottom right
plot conv u "dt":"sxx" w lp pt 6 lc rgb c1 t "{/Symbol s}_{xx}", \
     ''   u "dt":"syy" w lp pt 4 lc rgb c2 t "{/Symbol s}_{yy}", \
     ''   u "dt":"szz" w lp pt 8 lc rgb c3 t "{/Symbol s}_{zz}", \
     ''   u "dt":"sxy" w lp pt 12 lc rgb c4 t "{/Symbol s}_{xy}", \
     ''   u "dt":"gdot_p" w lp pt 2 lc rgb "black" t "gdot_p", \
     ''   u "dt":(3*$1) w l dt 2 lw 2 lc rgb "gray" t "slope 1"
unset logscale
set format x "% h"
set format y "% h"

# (e) stress difference
set title "(e) stress: ours - rkf45"
set xlabel "t [s]"
set ylabel "{/Symbol Ds} [Pa]"
set xrange [0:1.25]
set key top left
plot data u "t":(column("sxx") - column("ref_sxx")) w l lw 1.5 lc rgb c1 t "{/Symbol s}_{xx}", \
     ''   u "t":(column("syy") - column("ref_syy")) w l lw 1.5 lc rgb c2 t "{/Symbol s}_{yy}", \
     ''   u "t":(column("szz") - column("ref_szz")) w l lw 1.5 lc rgb c3 t "{/Symbol s}_{zz}", \
     ''   u "t":(column("sxy") - column("ref_sxy")) w l lw 1.5 lc rgb c4 t "{/Symbol s}_{xy}"

# (f) plastic strain-rate difference
set title "(f) D^p: ours - rkf45"
set ylabel "{/Symbol D}D^p [1/s]"
plot data u "t":(column("dp_xx") - column("ref_dp_xx")) w l lw 1.5 lc rgb c1 t "D^p_{xx}", \
     ''   u "t":(column("dp_yy") - column("ref_dp_yy")) w l lw 1.5 lc rgb c2 t "D^p_{yy}", \
     ''   u "t":(column("dp_zz") - column("ref_dp_zz")) w l lw 1.5 lc rgb c3 t "D^p_{zz}", \
     ''   u "t":(column("dp_xy") - column("ref_dp_xy")) w l lw 1.5 lc rgb c4 t "D^p_{xy}"

unset multiplot
