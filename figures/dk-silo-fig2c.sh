#!/usr/bin/env bash
# [DK-silo] Fig. 2(c): steady NGF chute profiles at 27 deg for H/Hstop = 1.9,
# 2.9, 4.8, 6.8, 19 against the 1D reference (verification/V7-ngf-chute/profile;
# about 6 minutes on one core, most of it the 98 mm layer). A layer whose
# profile was made before (OUTDIR/dk-silo-fig2c.d/H<mm>.result) is not run
# again; one interrupted is run again from the start.
#   figures/dk-silo-fig2c.sh OUTDIR
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
export GRANMPM=${GRANMPM:-$src/src/app/granmpm}
export GRANMPM_BUILDDIR=${GRANMPM_BUILDDIR:-$(cd "$(dirname "$GRANMPM")/../.." && pwd)}
out=${1:?usage: dk-silo-fig2c.sh OUTDIR}
[ -x "$GRANMPM_BUILDDIR/verification/ngf1d/ngf1d" ] ||
  { echo "dk-silo-fig2c.sh: $GRANMPM_BUILDDIR/verification/ngf1d/ngf1d not found (make builds it)" >&2; exit 1; }
work=$out/dk-silo-fig2c.d
mkdir -p "$work"
for h in 10 15 25 35 98; do
  if [ ! -s "$work/H$h.result" ] || [ ! -s "$work/H$h-profile.csv" ]; then
    rm -rf "$work/H$h" "$work/H$h.result"
    "$src/verification/V7-ngf-chute/profile" H$h $h "$work" > "$work/H$h.result.tmp"
    mv "$work/H$h.result.tmp" "$work/H$h.result"
  fi
  echo "H = $h mm: rel. L2, v(top), v_ref(top), KE change: $(cat "$work/H$h.result")"
done
gnuplot -e "dir='$work'; out='$out/dk-silo-fig2c.png'" "$src/figures/dk-silo-fig2c.gp"
