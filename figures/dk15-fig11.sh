#!/usr/bin/env bash
# [DK15] Fig. 11: the granular slug in flight, against the wall and settled,
# points coloured by the nodal density projected back to them (granmpm
# state); rho_c = 1500 kg/m^3 separates disconnected from dense.
#   figures/dk15-fig11.sh OUTDIR
# inputs/slug-reduced.conf (dx = 0.02 m) unless DK15_FULL=1 (dx = 0.0083 m).
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
granmpm=${GRANMPM:-$src/src/app/granmpm}
out=${1:?usage: dk15-fig11.sh OUTDIR}
work=$out/dk15-fig11.d
mkdir -p "$work"
in=$src/inputs/slug-reduced.conf
[ "${DK15_FULL:-0}" = 1 ] && in=$src/inputs/slug.conf
run=${DK15_RUNS:+$DK15_RUNS/slug}
if [ -z "$run" ]; then
  run=$work/slug
  # once per output directory (scripts/run-once: a finished run is kept)
  OMP_NUM_THREADS=${OMP_NUM_THREADS:-1} "$src/scripts/run-once" "$run" "$granmpm" run "$in" --quiet \
    --output "$run" --set output.checkpoint_wall=300
fi
files= titles=
for t in 0 0.3 0.55 0.6 0.7 3; do
  fr=$(awk -v t="$t" 'BEGIN { printf "%d", t / 0.01 + 0.5 }')   # frames every 0.01 s
  f=$work/slug-$t.csv
  "$granmpm" state "$in" "$run" --frame "$fr" | cut -d, -f1-3 > "$f"
  files="$files $f"
  titles="$titles${titles:+|}t = $t s"
done
gnuplot -e "files='$files'; titles='$titles'; layout='2 3'; cblabel='nodal density [kg/m^3]'; \
  cbmin=1100; cbmax=1600; xmin=0; xmax=1; ymin=0; ymax=0.8; width=1500; height=800; psize=0.35; \
  outfile='$out/dk15-fig11.png'; suptitle='granular slug: thrown at (1.2, 3.0) m/s against a frictionless wall (rho_c = 1500 kg/m^3)'" \
  "$src/figures/snapshots.gp"
