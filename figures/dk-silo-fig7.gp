# dk-silo-fig7.gp: [DK-silo] Fig. 7 redrawn: vertical velocity across the
# slices 1.5 W, 2 W, 2.5 W above the orifice (pink, green, blue) of the
# flowing silo in steady flow, points of every frame of the window (dots),
# with the diffusing Gaussian v_y = C exp(-(x - L/2)^2 / (4 B y)) + v_0
# fitted at each height in every frame of the window: the points of the
# middle frame (dots) and its fits (lines); the legend gives B / d as the
# mean and standard deviation of the frames' fits. One fit over all the
# frames together is made too; all fits go to a table.
#
# Inputs (gnuplot -e "data='...'; ..."):
#   data    CSV f,h,x,vy: frame, height index (1, 2, 3 for 1.5 W, 2 W,
#           2.5 W), x [m], vy [m/s] of the points within half a unit of it
#   frames  directory with the same rows one file per frame, F.csv
#   f0, f1  the frames of the window
#   W, L, d orifice, silo width, grain size [m] (0.14, 0.595, 0.028)
#   table   CSV written: frame (or "all"),h,C,v0,B,B_err,rms
#   ttl     title; out: PNG written
if (!exists("data")) data = 'slices.csv'
if (!exists("W")) W = 0.14
if (!exists("L")) L = 0.595
if (!exists("d")) d = 0.028
if (!exists("frames")) frames = 'frames'
if (!exists("table")) table = 'fits.csv'
if (!exists("ttl")) ttl = ''
if (!exists("out")) out = 'dk-silo-fig7.png'
set datafile separator comma
set fit quiet errorvariables
set fit maxiter 200
xc = L / 2
g(x) = v0 + C * exp(-(x - xc)**2 / (4 * B * yh))   # yh: the slice height
hcol = "#e0409a #2ca02c #1f4fd0"
hname = "1.5W 2W 2.5W"
array Ball[3]
array Eall[3]
array Call[3]
array Vall[3]
array Bm[3]
array Bs[3]
array Cf[3]
array Vf[3]
array Bf[3]
fm = int((f0 + f1) / 2)
set print table
print "frame,h,C,v0,B,B_err,rms"
do for [h = 1:3] {
  yh = (1 + 0.5 * h) * W
  C = -0.5; v0 = -0.01; B = 0.6 * d      # v0 not 0: gnuplot scales steps by the start values
  fit g(x) data u 3:($2 == h ? $4 : 1/0) every ::1 via C, v0, B
  Ball[h] = B; Eall[h] = B_err; Call[h] = C; Vall[h] = v0
  print sprintf("all,%d,%.6g,%.6g,%.6g,%.6g,%.6g", h, C, v0, B, B_err, FIT_STDFIT)
  s1 = 0; s2 = 0
  do for [f = f0:f1] {
    C = Call[h]; v0 = Vall[h]; B = Ball[h]
    fit g(x) sprintf("%s/%d.csv", frames, f) u 3:($2 == h ? $4 : 1/0) every ::1 via C, v0, B
    print sprintf("%d,%d,%.6g,%.6g,%.6g,%.6g,%.6g", f, h, C, v0, B, B_err, FIT_STDFIT)
    s1 = s1 + B; s2 = s2 + B * B
    if (f == fm) { Cf[h] = C; Vf[h] = v0; Bf[h] = B }
  }
  nf = f1 - f0 + 1
  Bm[h] = s1 / nf; Bs[h] = sqrt((s2 - nf * Bm[h]**2) / (nf - 1))
}
unset print

set terminal pngcairo size 900,620 font ",11"
set output out
set title "[DK-silo] Fig. 7 redrawn: v_y across slices, ".ttl."\nlines: v_0 + C exp(-(x - L/2)^2 / (4 B y)) fitted per height ([DK-silo]: B = 0.6 d)\n".\
  sprintf("dots and lines: frame %d and its fit; legend: B over the %d frames' fits (mean and standard deviation)", fm, f1 - f0 + 1) font ",10"
set xlabel "x [m]"
set ylabel "v_y [m/s]"
set grid lc rgb "#dddddd"
set key bottom right box opaque font ",10" width 1
set xrange [0:L]
set samples 400
plot for [h = 1:3] sprintf("%s/%d.csv", frames, fm) u 3:($2 == h ? $4 : 1/0) every ::1 w p pt 7 ps 0.35 lc rgb word(hcol, h) notitle, \
     for [h = 1:3] Vf[h] + Cf[h] * exp(-(x - xc)**2 / (4 * Bf[h] * (1 + 0.5 * h) * W)) w l lw 2.5 lc rgb word(hcol, h) \
       t sprintf("y = %s: B = (%.2f +- %.2f) d", word(hname, h), Bm[h] / d, Bs[h] / d)
