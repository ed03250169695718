#!/usr/bin/env bash
# [D-thesis] Fig. 4-7: the shear stress sigma_xy at the material points across the
# vertical chute for every V8 run that reads g linearly in the unit, against the exact
# steady value (figures/dthesis-stress; the runs of
# verification/V8-vertical-chute, shared: OUTDIR/vertical-chute or V8_OUTDIR).
#   figures/dthesis-fig4-7.sh OUTDIR
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
exec "$src/figures/dthesis-stress" "${1:?usage: dthesis-fig4-7.sh OUTDIR}" dthesis-fig4-7 linear sxy
