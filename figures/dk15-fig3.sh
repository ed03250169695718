#!/usr/bin/env bash
# [DK15] Fig. 3: run-out against aspect ratio with the fits of Table 3.
#   figures/dk15-fig3.sh OUTDIR
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
export GRANMPM=${GRANMPM:-$src/src/app/granmpm}
out=${1:?usage: dk15-fig3.sh OUTDIR}
mkdir -p "$out"
source "$src/figures/collapse-sweep.inc"
# power fits as in verification/V4-collapse/check: a <= 2 and a >= 4
fits=$(awk -F, 'NR > 1 && $6 != "" { n++; a[n] = $1; r[n] = $6 }
  function fit(lo, hi,   i, m, sx, sy, sxx, sxy, x, y, b) {
    for (i = 1; i <= n; i++) if (a[i] >= lo && a[i] <= hi) {
      x = log(a[i]); y = log(r[i]); m++; sx += x; sy += y; sxx += x * x; sxy += x * y }
    if (m < 2) return "1/0 1/0"
    b = (m * sxy - sx * sy) / (m * sxx - sx * sx)
    return sprintf("%.6g %.6g", exp((sy - b * sx) / m), b) }
  END { print fit(0, 2), fit(4, 1e9) }' "$sweep/results.csv")
read -r c1 e1 c2 e2 <<< "$fits"
gnuplot -e "results='$sweep/results.csv'; c1=$c1; e1=$e1; c2=$c2; e2=$e2; out='$out/dk15-fig3.png'" \
  "$src/figures/dk15-fig3.gp"
