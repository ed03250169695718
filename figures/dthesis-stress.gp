# dthesis-stress.gp: [D-thesis] Figs. 4-7, 4-8, 4-10 and 4-11 redrawn: the
# shear stress sigma_xy or the stress ratio mu of every material point
# across the vertical chute, one panel per run, with the exact steady value
# (the walls carry the weight: sigma_xy = rho g (x - L/2),
# mu = rho g |x - L/2| / p).
#
# Inputs (gnuplot -e "files='...'; ..."):
#   files   space-separated CSVs x,sxy,mu (the points of the last frame),
#           written by figures/dthesis-stress
#   titles  '|'-separated panel titles
#   field   sxy or mu
#   rule    linear or element (for the title)
#   rho, grav, p0, L   density, gravity, pressure, width (1500, 0.8, 900, 1)
#   ttl, out  title prefix, PNG written
if (!exists("files")) files = ''
if (!exists("titles")) titles = ''
if (!exists("field")) field = 'sxy'
if (!exists("rule")) rule = 'linear'
if (!exists("rho")) rho = 1500
if (!exists("grav")) grav = 0.8
if (!exists("p0")) p0 = 900
if (!exists("L")) L = 1
if (!exists("ttl")) ttl = '[D-thesis]'
if (!exists("out")) out = 'dthesis-stress.png'
ttl_i(i) = system(sprintf("echo '%s' | cut -d'|' -f%d", titles, i))
col = (field eq 'sxy') ? 2 : 3
exact(x) = (field eq 'sxy') ? rho * grav * (x - L / 2.0) : rho * grav * abs(x - L / 2.0) / p0
np = words(files)
ncol = (np > 4) ? 3 : 2
nrow = (np + ncol - 1) / ncol
set terminal pngcairo size 520 * ncol, 400 * nrow + 60 font ",10"
set output out
set datafile separator comma
set multiplot layout nrow, ncol title ttl.": ".(field eq 'sxy' ? "shear stress sigma_{xy}" : "stress ratio mu")." at the points, g ".(rule eq 'linear' ? "read linearly in the unit" : "as the unit mean")."; black: the exact steady value" font ",11"
set xlabel "x [m]"
set ylabel (field eq 'sxy' ? "sigma_{xy} [Pa]" : "mu")
set grid lc rgb "#dddddd"
set key top center box opaque font ",9"
set xrange [0:L]
set samples 401
do for [i = 1:np] {
  set title ttl_i(i)
  plot exact(x) w l lw 1.5 lc rgb "black" notitle, \
       word(files, i) u 1:col every ::1 w p pt 7 ps 0.35 lc rgb "#d62728" t "points"
}
unset multiplot
