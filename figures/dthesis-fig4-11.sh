#!/usr/bin/env bash
# [D-thesis] Fig. 4-11: the stress ratio mu at the material points across the
# vertical chute for every V8 run that reads the unit mean of g, against the exact
# steady value (figures/dthesis-stress; the runs of
# verification/V8-vertical-chute, shared: OUTDIR/vertical-chute or V8_OUTDIR).
#   figures/dthesis-fig4-11.sh OUTDIR
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
exec "$src/figures/dthesis-stress" "${1:?usage: dthesis-fig4-11.sh OUTDIR}" dthesis-fig4-11 element mu
