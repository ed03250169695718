#!/usr/bin/env bash
# [D-thesis] Fig. 4-3: the steady velocity across the vertical chute, local
# and nonlocal (the steady fluidity solve), 80 units across with one point
# per unit, against the closed form and the 1D reference
# (verification/V8-vertical-chute/case; a few minutes on one core). The
# runs go to OUTDIR/vertical-chute (or V8_OUTDIR), where dthesis-fig4-5.sh
# finds them.
#   figures/dthesis-fig4-3.sh OUTDIR
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
export GRANMPM=${GRANMPM:-$src/src/app/granmpm}
out=${1:?usage: dthesis-fig4-3.sh OUTDIR}
source "$src/figures/vchute-runs.inc"      # $runs, shared with the other chapter 4 drivers
work=$out/dthesis-fig4-3.d
mkdir -p "$work"
mesh=(--set mesh.nx=80 --set mesh.ny=4 --set mesh.dx=0.0125 --set mesh.dy=0.0125 --set fill.ymax=0.05
      --set fill.ppu=1)                   # a strip 4 units high, as V8 runs it
v8_case local-80x1 "${mesh[@]}" --set material.A=0
v8_case linear-80x1 "${mesh[@]}" --set material.g_sample=linear
for c in local-80x1 linear-80x1; do
  cp "$runs/$c-profile.csv" "$runs/$c-ref.csv" "$work/"
done
gnuplot -e "dir='$work'; out='$out/dthesis-fig4-3.png'" "$src/figures/dthesis-fig4-3.gp"
