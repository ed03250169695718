#!/usr/bin/env bash
# [DK15] Fig. 12 (App. A): the volume contributions behind the model's
# equation of state, against pressure. The model's own pieces: a flowing
# volume that is a step at the critical packing fraction Phi_c = rho_c /
# rho_s (any larger inverse packing fraction at zero pressure, any pressure
# at 1/Phi_c), an elastic volume linear in compression with the bulk
# modulus K and zero in tension, and their sum, which the trans-phase mu(I)
# update follows: one material point of the App. B material (E = 1e4 Pa,
# so that the elastic branch shows; K = E / (3 (1 - 2 nu)) = 8333 Pa)
# driven by `granmpm constitutive` through an isotropic compression from
# rho = 1400 kg/m^3 (disconnected) to 1710 kg/m^3 and back. For the flowing
# part the figure also draws the kinetic-theory Phi(I) relation [DK15]
# App. A derives (eq. A10, with eps = 0.9 and d = 5 mm, at three shear
# rates), which the step replaces. No simulation: a second.
# Printed: the largest departure of the driven point's pressure from
# K ln(rho / rho_c) (the hypoelastic update integrated exactly) and from the
# reference ODE of the driver, and where it disconnects.
#   figures/dk15-fig12.sh OUTDIR
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
granmpm=${GRANMPM:-$src/src/app/granmpm}
out=${1:?usage: dk15-fig12.sh OUTDIR}
work=$out/dk15-fig12.d
mkdir -p "$work"
# isotropic compression at tr D = -0.1 1/s for 2 s, then as much extension
printf 't,Lxx,Lxy,Lyx,Lyy\n0,-0.05,0,0,-0.05\n2,-0.05,0,0,-0.05\n2.000001,0.05,0,0,0.05\n4,0.05,0,0,0.05\n' \
  > "$work/history.csv"
"$granmpm" constitutive --history "$work/history.csv" --rho0 1400 --dt 1e-3 --every 20 \
  --output "$work/point.csv"
# the material of the driver's default (App. B): E, nu, rho_s, rho_c
E=1e4 nu=0.3 rho_s=2450 rho_c=1500
# columns: t 1, p 10, rho 18, state 19, ref_p 24
awk -F, -v E=$E -v nu=$nu -v rc=$rho_c 'NR > 1 {
    K = E / (3 * (1 - 2 * nu)); pe = ($18 >= rc) ? K * log($18 / rc) : 0
    d = $10 - pe; if (d < 0) d = -d; if (d > m) m = d
    r = $10 - $24; if (r < 0) r = -r; if (r > mr) mr = r
    if ($10 > pmax) pmax = $10
    if (prev_state == 0 && $19 == 1) dis = $18
    prev_state = $19 }
  END { printf "largest pressure %.1f Pa; largest departure from K ln(rho/rho_c): %.3g Pa (%.2g of it), from the reference ODE: %.3g Pa; disconnects at rho = %.2f kg/m^3 (rho_c = %s, within a step)\n",
        pmax, m, m / pmax, mr, dis, rc }' "$work/point.csv"
gnuplot -e "point='$work/point.csv'; E=$E; nu=$nu; rho_s=$rho_s; rho_c=$rho_c; out='$out/dk15-fig12.png'" \
  "$src/figures/dk15-fig12.gp"
