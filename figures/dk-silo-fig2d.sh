#!/usr/bin/env bash
# [DK-silo] Fig. 2(d): the NGF stopping height Hstop(theta) of glass beads
# (A = 0.48, mu_s = 0.3819) with the common limit mu_2 = 0.6435 and with no
# limit (mu_2 = infinity, the linear local law: ngf1d's `hs21` form), each
# the threshold the steady 1D solver verification/ngf1d finds (bisection of
# H between decay to g = 0 and flow, 400 intervals) beside eq. 3.1 of
# [DK-silo]. No simulation: a few seconds. The paper's figure also shows
# Pouliquen's (1999) measurements on glass beads; their values are not in
# the paper's text, so they are not drawn.
#   figures/dk-silo-fig2d.sh OUTDIR
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
export GRANMPM=${GRANMPM:-$src/src/app/granmpm}
export GRANMPM_BUILDDIR=${GRANMPM_BUILDDIR:-$(cd "$(dirname "$GRANMPM")/../.." && pwd)}
out=${1:?usage: dk-silo-fig2d.sh OUTDIR}
ngf1d=$GRANMPM_BUILDDIR/verification/ngf1d/ngf1d
[ -x "$ngf1d" ] ||
  { echo "dk-silo-fig2d.sh: $ngf1d not found (make builds it)" >&2; exit 1; }
work=$out/dk-silo-fig2d.d
mkdir -p "$work"
A=0.48 mu_s=0.3819 mu_2=0.6435
# angles from just above atan(mu_s) = 20.9 deg, denser where Hstop is steep
thetas=$(awk 'BEGIN { for (t = 21.0; t < 22; t += 0.1) printf "%.1f ", t
                      for (t = 22; t <= 40.001; t += 0.25) printf "%.2f ", t }')
# one row per angle: theta, then Hstop/d from eq. 3.1 and from the solver,
# for mu_2 = 0.6435 (0 above atan(mu_2): every layer flows) and mu_2 = inf
echo "theta_deg,dk_eq31,dk_solver,inf_eq31,inf_solver" > "$work/hstop.csv"
for t in $thetas; do
  a=$("$ngf1d" hstop --theta "$t" --A $A --mu_s $mu_s --mu_2 $mu_2 | head -n 1)
  b=$("$ngf1d" hstop --theta "$t" --A $A --mu_s $mu_s --mu_2 $mu_2 --form hs21 | head -n 1)
  # "Hstop H m, discrete (n = 400) HD m, Hstop/d R": d = H / R (R = 0 above atan(mu_2))
  awk -v t="$t" -v a="$a" -v b="$b" 'BEGIN {
    na = split(a, x, " "); nb = split(b, y, " ")
    d = (x[na] > 0) ? x[2] / x[na] : y[2] / y[nb]
    da = (x[8] == "inf") ? 0 : x[8] / d
    printf "%s,%.8g,%.8g,%.8g,%.8g\n", t, x[2] / d, da, y[2] / d, y[8] / d }' >> "$work/hstop.csv"
done
# the solver's threshold against eq. 3.1 (largest relative difference)
awk -F, 'NR > 1 { for (k = 2; k <= 4; k += 2) if ($k > 0) {
    e = ($(k + 1) - $k) / $k; if (e < 0) e = -e; if (e > m) m = e } }
  END { printf "solver threshold against eq. 3.1: largest relative difference %.2g\n", m }' "$work/hstop.csv"
awk -F, -v t0=25 -v t1=30 'NR > 1 && ($1 == t0 || $1 == t1) {
  printf "theta = %s deg: Hstop/d = %.3f (mu_2 = 0.6435), %.3f (mu_2 = inf)\n", $1, $3, $5 }' "$work/hstop.csv"
gnuplot -e "data='$work/hstop.csv'; A=$A; mu_s=$mu_s; mu_2=$mu_2; out='$out/dk-silo-fig2d.png'" \
  "$src/figures/dk-silo-fig2d.gp"
