#!/usr/bin/env bash
# [D-thesis] App. A, Fig. A-3: the steady nonlocal solution of the vertical
# chute (App. A.2; verification/ngf1d) for several nonlocal amplitudes A,
# mu_s = 0.3819 and the rest of Table 4.1, with the local closed form (no
# simulation, seconds). The thesis: small A comes close to the local model,
# larger A smooths the profile further. We print the largest difference from
# the local profile relative to its centre speed, and the centre speed.
#   figures/dthesis-figA-3.sh OUTDIR
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
export GRANMPM=${GRANMPM:-$src/src/app/granmpm}
out=${1:?usage: dthesis-figA-3.sh OUTDIR}
source "$src/figures/vchute-ref.inc"
work=$out/dthesis-figA-3.d
mkdir -p "$work"
vchute_ref "$work/local.csv" --local --mu_s 0.3819
files= titles=
for A in 0.01 0.05 0.1 0.25 0.48 1 2; do
  f=$work/nonlocal-A$A.csv
  vchute_ref "$f" --A "$A" --mu_s 0.3819
  # the local profile interpolated linearly to the nonlocal one's nodes
  awk -F, -v A="$A" 'FNR == 1 { file++; next }
    file == 1 { n++; xl[n] = $1; vl[n] = $2; if ($2 > c) c = $2; next }
    { while (k < n - 1 && xl[k + 1] < $1) k++
      if (k < 1) k = 1
      v = vl[k] + (vl[k + 1] - vl[k]) * ($1 - xl[k]) / (xl[k + 1] - xl[k])
      d = $2 - v; if (d < 0) d = -d; if (d > m) m = d; if ($2 > cn) cn = $2 }
    END { printf "A = %-5s largest |v - v_local| = %.4f of the local centre speed; centre speed %.5f m/s (local %.5f)\n", A, m / c, cn, c }' \
    "$work/local.csv" "$f"
  files="$files $f"
  titles="$titles${titles:+|}A = $A"
done
gnuplot -e "files='$files'; titles='$titles'; local='$work/local.csv'; ltitle='local (A = 0)'; \
  out='$out/dthesis-figA-3.png'; ttl='[D-thesis] Fig. A-3 redrawn: steady nonlocal solution, A varied (mu_s = 0.3819)'" \
  "$src/figures/dthesis-figA.gp"
