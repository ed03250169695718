# dk-silo-votes.gp: the evidence of the silo classifier ([DK-silo] section
# 7.2; docs/diagnostics.md) over time for three runs, one panel each: the
# mean vertical velocity the dense material moved with between frames
# (left axis, blue), zero (black), the first half of the run (last crossing
# there: a vote for flowing, blue band) and its last tenth (a vote for
# static, grey band), the last zero crossing (orange line), and the points
# leaving per frame (right axis, grey steps).
#
# Inputs (override with gnuplot -e "f1='...'; ..."):
#   f1, f2, f3     CSVs t,vbar,points,left,dense (granmpm extract RUN --jam-series)
#   t1, t2, t3     panel titles
#   tz1, tz2, tz3  last zero crossing [s] ('nan': none)
#   te1, te2, te3  end of the run [s]
#   out            PNG written

if (!exists("f1")) f1 = 'A1-wd1.csv'
if (!exists("f2")) f2 = 'A1-wd5.csv'
if (!exists("f3")) f3 = 'A0.1-wd5.csv'
if (!exists("t1")) t1 = f1
if (!exists("t2")) t2 = f2
if (!exists("t3")) t3 = f3
if (!exists("tz1")) tz1 = 'nan'
if (!exists("tz2")) tz2 = 'nan'
if (!exists("tz3")) tz3 = 'nan'
if (!exists("te1")) te1 = 1.5
if (!exists("te2")) te2 = 1.5
if (!exists("te3")) te3 = 1.5
if (!exists("out")) out = 'dk-silo-votes.png'

set terminal pngcairo size 1000,1050 font ',10'
set output out
set datafile separator ','
set multiplot layout 3,1
set xlabel 't [s]'
set ylabel 'mean v_y of the dense material [m/s]'
set y2label 'points leaving per frame'
set ytics nomirror
set y2tics
set y2range [0:*]
set key top right
set grid

do for [k = 1:3] {
  f = value('f'.k); t = value('t'.k); tz = value('tz'.k); te = value('te'.k)
  set title t
  set xrange [0:te]
  unset object
  unset arrow
  set object 1 rect from 0, graph 0 to 0.5 * te, graph 1 behind fc rgb '#dbe9f6' fs solid noborder
  set object 2 rect from 0.9 * te, graph 0 to te, graph 1 behind fc rgb '#e4e4e4' fs solid noborder
  set label 1 'last crossing here: flowing' at first 0.01 * te, graph 0.06 front
  set label 2 'static' at first 0.91 * te, graph 0.06 front
  if (tz ne 'nan') {
    set arrow 1 from real(tz), graph 0 to real(tz), graph 1 nohead lc rgb '#e07b00' lw 2
  }
  plot f every ::1 using 1:4 axes x1y2 with steps lc rgb '#999999' title 'points leaving', \
       f every ::1 using 1:2 with lines lc rgb '#1f5fa8' lw 1.5 title 'mean v_y (dense)', \
       0 with lines lc rgb 'black' notitle
}
unset multiplot
