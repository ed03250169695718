#!/usr/bin/env bash
# [D-thesis] Fig. 4-2: the material points of the vertical chute coloured
# by their (FLIP) vertical velocity at 1.25 s, the nonlocal run of Fig. 4-3
# (steady fluidity, g read linearly, 80 x 80 units, one point per unit) on
# the whole square the thesis simulates rather than V8's strip of 4 units
# (about 15 minutes of one core): the chute is periodic along y, so every
# column of points should move alike. Printed: the largest spread of the
# point velocities along y within a column of points, relative to the
# centre speed, and the square's errors beside the strip's (V8, same
# units and points).
#   figures/dthesis-fig4-2.sh OUTDIR
# The runs go to OUTDIR/vertical-chute (or V8_OUTDIR), shared with the
# other [D-thesis] chapter 4 drivers.
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
export GRANMPM=${GRANMPM:-$src/src/app/granmpm}
out=${1:?usage: dthesis-fig4-2.sh OUTDIR}
source "$src/figures/vchute-runs.inc"
work=$out/dthesis-fig4-2.d
mkdir -p "$work"
sq=$(v8_case square-linear-80x1 --set mesh.nx=80 --set mesh.ny=80 --set mesh.dx=0.0125 --set mesh.dy=0.0125 \
       --set fill.ppu=1 --set material.g_sample=linear)
strip=$(v8_case linear-80x1 --set mesh.nx=80 --set mesh.ny=4 --set mesh.dx=0.0125 --set mesh.dy=0.0125 \
          --set fill.ymax=0.05 --set fill.ppu=1 --set material.g_sample=linear)
"$GRANMPM" extract "$runs/square-linear-80x1" --frame last --fields x,y,vy > "$work/points.csv"
awk -F, 'NR > 1 { q = int($1 / 0.0125); v = -$3; if (!(q in lo) || v < lo[q]) lo[q] = v
                  if (!(q in hi) || v > hi[q]) hi[q] = v; if (v > vc) vc = v }
  END { for (q in lo) if (hi[q] - lo[q] > m) { m = hi[q] - lo[q]; qm = q }
        printf "largest spread of the point velocities along y in a column: %.3g m/s = %.2g of the centre speed %.4f m/s (column at x = %.4f m)\n",
          m, m / vc, vc, (qm + 0.5) * 0.0125 }' "$work/points.csv"
read -r _ rd _ rf _ <<< "$sq"
read -r _ rd2 _ rf2 _ <<< "$strip"
echo "relative L2 errors, grid / point velocity: square $rd / $rf, strip of 4 units $rd2 / $rf2 ([D-thesis] Table 4.2, point: 5.198e-4)"
gnuplot -e "data='$work/points.csv'; out='$out/dthesis-fig4-2.png'" "$src/figures/dthesis-fig4-2.gp"
