#!/usr/bin/env bash
# [DK-silo] Fig. 7 on the refined silo: the same fit as dk-silo-fig7.sh
# (A = 0.5, W/d = 5, frames FIG7_FRAMES, default 60 ... 180) on the run with
# units of half the size and a quarter of the step ([DK-silo] Table 2;
# figures/silo-refined.inc, about 12 minutes of one core), to show how far
# B depends on the mesh.
#   figures/dk-silo-fig7-refined.sh OUTDIR
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
export GRANMPM=${GRANMPM:-$src/src/app/granmpm}
out=${1:?usage: dk-silo-fig7-refined.sh OUTDIR}
source "$src/figures/silo-refined.inc"
refined_runs 0.5 5
FIG7_RUN=$refined/runs/A0.5-wd5 FIG7_NAME=dk-silo-fig7-refined exec "$src/figures/dk-silo-fig7.sh" "$out"
