# dk15-fig12.gp: [DK15] Fig. 12 redrawn: inverse packing fraction 1/Phi =
# rho_s / rho against pressure, split as the model splits it:
#   left:   the flowing part, the step at 1/Phi_c (thick), with the
#           kinetic-theory Phi(I) relation of [DK15] eq. A10 at three shear
#           rates (thin) that it replaces;
#   middle: the elastic part, -p / K in compression, 0 in tension;
#   right:  their sum, 1/Phi_c exp(-p/K) (the hypoelastic update integrated
#           exactly; 1/Phi_c - p/K to first order), and one material point
#           of the trans-phase mu(I) update driven through compression and
#           back (`granmpm constitutive`, points).
# Inputs (gnuplot -e "point='...'; ..."):
#   point   the driver's CSV (columns p 10, rho 18, state 19)
#   E, nu, rho_s, rho_c   the material (App. B: 1e4 Pa, 0.3, 2450, 1500)
#   eps, d  restitution and grain size of eq. A10 (0.9, 0.005 m)
#   out     PNG written
if (!exists("point")) point = 'point.csv'
if (!exists("E")) E = 1e4
if (!exists("nu")) nu = 0.3
if (!exists("rho_s")) rho_s = 2450.
if (!exists("rho_c")) rho_c = 1500.
if (!exists("eps")) eps = 0.9
if (!exists("d")) d = 0.005
if (!exists("out")) out = 'dk15-fig12.png'
K = 1.0 * E / (3 * (1 - 2 * nu))
ic = 1.0 * rho_s / rho_c                # 1/Phi_c (not an integer division)
lam = (1 + eps) / 2
# eq. A10: pressure of the sheared granular gas at packing fraction f, shear rate gd
pkin(f, gd) = rho_s * f**2 / 81 * (2.52 * lam * f / (0.6 - f) + 1)**2 * gd**2 * d**2
pmax = 1200
set terminal pngcairo size 1500,520 font ",10"
set output out
set datafile separator comma
set multiplot layout 1,3 title sprintf("[DK15] Fig. 12 redrawn: volume contributions (App. B material: E = %g Pa, K = %.0f Pa; rho_s = %g, rho_c = %g kg/m^3)", E, K, rho_s, rho_c)
set grid lc rgb "#dddddd"
set xlabel "pressure p [Pa]"
set xrange [-50:pmax]
set key top right box opaque font ",9"
set samples 400

set title "flowing part"
set ylabel "rho_s v_f / m (inverse packing fraction of the flowing part)"
set yrange [1.5:2.1]
set parametric
set trange [0.45:0.5999]
plot pkin(t, 1), 1 / t w l lw 1.5 lc rgb "#9467bd" t "eq. A10, 1/s", \
     pkin(t, 10), 1 / t w l lw 1.5 lc rgb "#2ca02c" t "eq. A10, 10/s", \
     pkin(t, 50), 1 / t w l lw 1.5 lc rgb "#ff7f0e" t "eq. A10, 50/s", \
     0, ic + (t - 0.45) / (0.5999 - 0.45) * (2.1 - ic) w l lw 4 lc rgb "#1f4fd0" t "model: step at 1/Phi_c", \
     (t - 0.45) / (0.5999 - 0.45) * pmax, ic w l lw 4 lc rgb "#1f4fd0" notitle
unset parametric

set title "elastic part"
set ylabel "rho_s v_e / m"
set yrange [-0.15:0.02]
plot [-50:pmax] (x > 0 ? -x / K : 0) w l lw 4 lc rgb "#d62728" t "model: -p/K, 0 in tension"

set title "sum: the equation of state"
set ylabel "1/Phi = rho_s / rho"
set yrange [1.4:1.8]
set parametric
set trange [0:pmax]
plot 0, 1.8 - (1.8 - ic) * t / pmax w l lw 4 lc rgb "#888888" t "step + elastic", \
     t, ic * exp(-t / K) w l lw 4 lc rgb "#888888" notitle, \
     point u 10:(rho_s / $18) every ::1 w p pt 6 ps 0.8 lc rgb "#1f4fd0" t "granmpm constitutive (one point)"
unset parametric
unset multiplot
