#!/usr/bin/env bash
# [D-thesis] App. A, Fig. A-1: the local closed form (App. A.1) of the
# steady vertical chute for several static friction coefficients mu_s, the
# other parameters of Table 4.1 (verification/ngf1d; no simulation, seconds).
# The thesis: a plug persists even for small mu_s, narrower and narrower. We
# print the plug's width against 2 mu_s p / (rho g) of App. A.1 (eq. A.4).
#   figures/dthesis-figA-1.sh OUTDIR
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
export GRANMPM=${GRANMPM:-$src/src/app/granmpm}
out=${1:?usage: dthesis-figA-1.sh OUTDIR}
source "$src/figures/vchute-ref.inc"
work=$out/dthesis-figA-1.d
mkdir -p "$work"
files= titles=
for ms in 0.05 0.1 0.2 0.3 0.3819 0.5 0.6; do
  f=$work/local-mus$ms.csv
  vchute_ref "$f" --local --mu_s "$ms"
  w=$(plug_width "$f")
  awk -v ms="$ms" -v w="$w" -v v="$(awk -F, 'NR > 1 && $2 > m { m = $2 } END { print m }' "$f")" 'BEGIN {
    xc = 2 * ms * 900 / (1500 * 0.8)
    printf "mu_s = %-6s plug width %.4f m (App. A.1: %.4f m), centre speed %.5f m/s\n", ms, w, xc, v }'
  files="$files $f"
  titles="$titles${titles:+|}mu_s = $ms"
done
gnuplot -e "files='$files'; titles='$titles'; out='$out/dthesis-figA-1.png'; \
  ttl='[D-thesis] Fig. A-1 redrawn: local closed form (App. A.1), mu_s varied'" \
  "$src/figures/dthesis-figA.gp"
