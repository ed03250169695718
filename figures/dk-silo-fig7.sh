#!/usr/bin/env bash
# [DK-silo] Fig. 7: vertical velocity across horizontal slices at 1.5 W,
# 2 W and 2.5 W above the orifice of the flowing silo (inputs/silo-jam.conf,
# A = 0.5, W/d = 5: d = 0.028 m, W = 0.14 m) in steady flow, with the
# diffusing Gaussian v_y = C exp(-(x - L/2)^2 / (4 B y)) + v_0 fitted at each
# height (v_0: the walls are frictionless, so material slides down them).
# [DK-silo] finds B = 0.6 d.
# Steady flow: frames FIG7_FRAMES (default "60 180", t = 0.25 ... 0.75 s; the
# driver prints the points leaving per frame over them). The points within
# half a unit of each height are fitted in every frame of the window (B per
# frame and height), and once over all those frames together (the lines
# drawn, with gnuplot's standard errors). B is reported per height as the
# mean and standard deviation over the frames, and over all heights and
# frames, against 0.6 d.
#   figures/dk-silo-fig7.sh OUTDIR
# The run comes from the shared jamming sweep (figures/jam-sweep.inc:
# $GRANMPM_JAM_SWEEP or OUTDIR/jam-sweep); FIG7_RUN=DIR fits another run
# of the same silo instead (a refined one, for instance).
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
export GRANMPM=${GRANMPM:-$src/src/app/granmpm}
out=${1:?usage: dk-silo-fig7.sh OUTDIR}
name=${FIG7_NAME:-dk-silo-fig7}
work=$out/$name.d
mkdir -p "$work"
read -r f0 f1 <<< "${FIG7_FRAMES:-60 180}"
[[ "$f0" =~ ^[0-9]+$ && "$f1" =~ ^[0-9]+$ && "$f0" -lt "$f1" ]] ||
  { echo "dk-silo-fig7.sh: FIG7_FRAMES must be two frame numbers 'FIRST LAST', FIRST < LAST" >&2; exit 2; }
A=0.5 wd=5 d=0.028 W=0.14 L=0.595
if [ -n "${FIG7_RUN:-}" ]; then
  run=$FIG7_RUN
else
  source "$src/figures/jam-sweep.inc"
  jam_runs "$A" "$wd"
  run=$sweep/runs/A$A-wd$wd
fi
nf=$(($(wc -l < "$run/diagnostics.csv") - 1))
[ "$f1" -lt "$nf" ] || { echo "dk-silo-fig7.sh: $run has $nf frames, FIG7_FRAMES needs $f1" >&2; exit 1; }
dy=$("$GRANMPM" info "$run" | awk '$1 == "dy" { print $3; exit }')
# points within half a unit of each height, every frame of the window: f,h,x,vy
# (and one file per frame, frames/F.csv, for the fits of single frames)
mkdir -p "$work/frames"
echo "f,h,x,vy" > "$work/slices.csv"
for f in $(seq "$f0" "$f1"); do
  "$GRANMPM" extract "$run" --frame "$f" --fields x,y,vy,state |
    awk -F, -v f="$f" -v W=$W -v dy="$dy" 'NR == 1 { print "f,h,x,vy" } NR > 1 {
      for (h = 1; h <= 3; h++) { yh = (1 + 0.5 * h) * W
        if ($2 >= yh - dy / 2 && $2 < yh + dy / 2) printf "%d,%d,%s,%s\n", f, h, $1, $3 } }' \
    > "$work/frames/$f.csv"
  tail -n +2 "$work/frames/$f.csv"
done >> "$work/slices.csv"
awk -F, -v f0="$f0" -v f1="$f1" 'NR == f0 + 2 { n0 = $11; t0 = $1 } NR == f1 + 2 { n1 = $11; t1 = $1 }
  END { printf "frames %d-%d (t = %.3f-%.3f s): %.1f points leaving a frame\n", f0, f1, t0, t1, (n0 - n1) / (f1 - f0) }' \
  "$run/diagnostics.csv"
# the frames' points leaving, one value per frame, to see the flow is steady
awk -F, -v f0="$f0" -v f1="$f1" 'NR >= f0 + 2 && NR <= f1 + 2 { if (NR > f0 + 2) { q = p - $11; s += q; ss += q * q; k++ } p = $11 }
  END { m = s / k; printf "points leaving per frame over the window: mean %.1f, standard deviation %.1f\n", m, sqrt(ss / k - m * m) }' \
  "$run/diagnostics.csv"
gnuplot -e "data='$work/slices.csv'; frames='$work/frames'; f0=$f0; f1=$f1; W=$W; L=$L; d=$d; \
  table='$work/fits.csv'; ttl='A = $A, W/d = $wd, units of $(awk -v d="$dy" 'BEGIN { print d * 1000 }') mm, frames $f0-$f1'; out='$out/$name.png'" \
  "$src/figures/dk-silo-fig7.gp" 2> "$work/fit.log"
# B per height: mean and standard deviation over the frames; all heights together
awk -F, -v d=$d 'NR > 1 && $1 != "all" { h = $2; n[h]++; s[h] += $5; ss[h] += $5 * $5; N++; S += $5; SS += $5 * $5 }
  NR > 1 && $1 == "all" { B[$2] = $5; e[$2] = $6 }
  END {
    for (h = 1; h <= 3; h++) {
      m = s[h] / n[h]; sd = sqrt((ss[h] - n[h] * m * m) / (n[h] - 1))
      printf "y = %.1f W: B = %.4f +- %.4f m = (%.2f +- %.2f) d over %d frames; one fit over all: (%.3f +- %.3f) d\n",
        1 + 0.5 * h, m, sd, m / d, sd / d, n[h], B[h] / d, e[h] / d
    }
    m = S / N; sd = sqrt((SS - N * m * m) / (N - 1))
    printf "B = (%.2f +- %.2f) d over all heights and frames ([DK-silo]: 0.6 d); %+.0f %%\n", m / d, sd / d, 100 * (m / d / 0.6 - 1)
  }' "$work/fits.csv"
