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
export GRANMPM_BUILDDIR=${GRANMPM_BUILDDIR:-$(cd "$(dirname "$GRANMPM")/../.." && pwd)}
out=${1:?usage: dthesis-fig4-3.sh OUTDIR}
[ -x "$GRANMPM_BUILDDIR/verification/ngf1d/ngf1d" ] ||
  { echo "dthesis-fig4-3.sh: $GRANMPM_BUILDDIR/verification/ngf1d/ngf1d not built (make check builds it)" >&2; exit 1; }
work=$out/dthesis-fig4-3.d
runs=${V8_OUTDIR:-$out/vertical-chute}   # shared with dthesis-fig4-5.sh (V8's case names)
mkdir -p "$work" "$runs"
export V8_REUSE=1
mesh=(--set mesh.nx=80 --set mesh.ny=4 --set mesh.dx=0.0125 --set mesh.dy=0.0125 --set fill.ymax=0.05
      --set fill.ppu=1)                   # a strip 4 units high, as V8 runs it
"$src/verification/V8-vertical-chute/case" local-80x1 "$runs" "${mesh[@]}" --set material.A=0 &
"$src/verification/V8-vertical-chute/case" linear-80x1 "$runs" "${mesh[@]}" \
  --set material.g_sample=linear
wait
for c in local-80x1 linear-80x1; do
  cp "$runs/$c-profile.csv" "$runs/$c-ref.csv" "$work/"
done
gnuplot -e "dir='$work'; out='$out/dthesis-fig4-3.png'" "$src/figures/dthesis-fig4-3.gp"
