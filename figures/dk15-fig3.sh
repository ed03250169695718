#!/usr/bin/env bash
# [DK15] Fig. 3: run-out against aspect ratio with the fits of Table 3, from
# the collapse sweeps with 4 x 4 points per unit ([DK15]'s) and 2 x 2 (the
# reduced inputs of the V4 check; figures/collapse-sweep.inc). Prints both
# sweeps' run-outs and power fits (a <= 2 and a >= 4, as the V4 check) with
# their departures from Table 3.
#   figures/dk15-fig3.sh OUTDIR
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
export GRANMPM=${GRANMPM:-$src/src/app/granmpm}
out=${1:?usage: dk15-fig3.sh OUTDIR}
mkdir -p "$out"
source "$src/figures/collapse-sweep.inc"
# power fits as in verification/V4-collapse/check: a <= 2 and a >= 4
fits() {
  awk -F, 'NR > 1 && $6 != "" { n++; a[n] = $1; r[n] = $6 }
    function fit(lo, hi,   i, m, sx, sy, sxx, sxy, x, y, b) {
      for (i = 1; i <= n; i++) if (a[i] >= lo && a[i] <= hi) {
        x = log(a[i]); y = log(r[i]); m++; sx += x; sy += y; sxx += x * x; sxy += x * y }
      if (m < 2) return "1/0 1/0"
      b = (m * sxy - sx * sy) / (m * sxx - sx * sx)
      return sprintf("%.6g %.6g", exp((sy - b * sx) / m), b) }
    END { print fit(0, 2), fit(4, 1e9) }' "$1"
}
args=
for ppu in 4 2; do
  collapse_sweep $ppu
  read -r c1 e1 c2 e2 <<< "$(fits "$sweep/results.csv")"
  awk -F, -v p=$ppu 'NR > 1 && $6 != "" { printf "%s %s:%.3f", (n++ ? "" : p " x " p " points per unit, run-out (a:r):"), $1, $6 } END { print "" }' "$sweep/results.csv"
  awk -v p=$ppu -v c1="$c1" -v e1="$e1" -v c2="$c2" -v e2="$e2" 'BEGIN {
    printf "  a <= 2: %.3f a^%.3f ([DK15] 2.28 a: coefficient %+.0f %%); a >= 4: %.3f a^%.3f ([DK15] 3.24 a^0.66: %+.0f %%)\n",
      c1, e1, 100 * (c1 / 2.28 - 1), c2, e2, 100 * (c2 / 3.24 - 1) }'
  args+="results$ppu='$sweep/results.csv'; c1_$ppu=$c1; e1_$ppu=$e1; c2_$ppu=$c2; e2_$ppu=$e2; "
done
gnuplot -e "$args out='$out/dk15-fig3.png'" "$src/figures/dk15-fig3.gp"
