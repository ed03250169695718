#!/usr/bin/env bash
# [DK-silo] Fig. 10: pressure in the coarse (top) and refined (bottom)
# silos of [DK-silo] section 7.3, A = 1, W/d = 1 (left) and 5 (right): the
# nodally smoothed point pressure ([DK15] eqs. 4.1-4.3, `granmpm extract
# --smooth`) averaged over frames 349 ... 351 and over each unit of the
# run's own mesh. Runs as dk-silo-fig9.sh (shared). Printed per run: the
# mean pressure of the points just above the orifice (|x - L/2| < W/2,
# y < W: small but not zero over an arch, zero in free fall), also over
# the lithostatic rho_c g (h - y) at the same points, and the
# pressure on the floor beside the side walls against rho_c g h, h the mean
# fill height of the frame (lithostatic away from the orifice).
#   figures/dk-silo-fig10.sh OUTDIR
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
export GRANMPM=${GRANMPM:-$src/src/app/granmpm}
out=${1:?usage: dk-silo-fig10.sh OUTDIR}
work=$out/dk-silo-fig10.d
mkdir -p "$work"
source "$src/figures/jam-sweep.inc"
source "$src/figures/silo-refined.inc"
jam_runs 1 "1 5"
refined_runs 1 "1 5"
L=0.595 W=0.14
args=
k=0
for res in coarse refined; do
  for wd in 1 5; do
    if [ $res = coarse ]; then run=$sweep/runs/A1-wd$wd; else run=$refined/runs/A1-wd$wd; fi
    read -r dx nx ny <<< "$("$GRANMPM" info "$run" | awk '$1 == "dx" && !d { d = $3 } $1 == "nx" && !n { n = $3 } $1 == "ny" && !m { m = $3 }
                                                 END { print d, n, m }')"
    # mean fill height of frame 350: the mass in the silo over rho_c L
    h=$(awk -F, -v L=$L 'NR == 352 { printf "%.4f", $6 / (1500 * L) }' "$run/diagnostics.csv")
    for f in 349 350 351; do
      "$GRANMPM" extract "$run" --smooth --frame "$f" | tail -n +2
    done | awk -F, -v dx="$dx" -v nx="$nx" -v ny="$ny" -v L=$L -v W=$W -v h="$h" -v units="$work/$res-wd$wd-units.csv" '
      # columns x,y,p,p_smooth,gdot_p,state
      { i = int($1 / dx); j = int($2 / dx)
        if (i < 0) i = 0; if (i >= nx) i = nx - 1
        if (j < 0) j = 0; if (j >= ny) j = ny - 1
        s[i, j] += $4; n[i, j]++
        if ($1 > L / 2 - W / 2 && $1 < L / 2 + W / 2 && $2 < W) { so += $4; sl += 1500 * 9.81 * (h - $2); no++ }
        if (($1 < 2 * dx || $1 > L - 2 * dx) && $2 < 2 * dx) { sw += $4; nw++ }
        np++; vol += 1 }
      END {
        print "i,j,x,y,p,n" > units
        for (j = 0; j < ny; j++) for (i = 0; i < nx; i++) if ((i, j) in n)
          printf "%d,%d,%.6f,%.6f,%.6g,%d\n", i, j, (i + 0.5) * dx, (j + 0.5) * dx, s[i, j] / n[i, j], n[i, j] > units
        printf "%.6g %.6g %.6g\n", (no ? so / no : 0), (no ? so / sl : 0), (nw ? sw / nw : 0) }' > "$work/$res-wd$wd.txt"
    read -r po pr pw < "$work/$res-wd$wd.txt"
    cls=$(tail -n 1 "$run/jam.csv" | cut -d, -f1)
    awk -v r=$res -v wd=$wd -v po="$po" -v pr="$pr" -v pw="$pw" -v h="$h" -v c="$cls" 'BEGIN {
      printf "%-7s W/d = %s (%s): above the orifice %.0f Pa = %.2f of rho_c g (h - y); floor at the side walls %.0f Pa = %.2f rho_c g h (h = %.3f m)\n",
        r, wd, c, po, pr, pw, pw / (1500 * 9.81 * h), h }'
    k=$((k + 1))
    args+="d$k='$work/$res-wd$wd-units.csv'; dx$k=$dx; t$k='$res, W/d = $wd ($cls)'; "
  done
done
gnuplot -e "$args out='$out/dk-silo-fig10.png'" "$src/figures/dk-silo-fig10.gp"
