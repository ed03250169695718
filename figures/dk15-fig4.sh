#!/usr/bin/env bash
# [DK15] Fig. 4: silo discharge through orifices of 10, 14 and 18 cm (columns)
# at 0, 2 and 5 s (rows), points coloured by the equivalent plastic shear
# rate; half silo, symmetry line at x = 0.
#   figures/dk15-fig4.sh OUTDIR
# dx = 0.02 m unless DK15_FULL=1 (inputs/silo.conf as it is, dx = 0.01 m:
# several minutes). The runs go to 5 s without the stop.mass test.
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
granmpm=${GRANMPM:-$src/src/app/granmpm}
out=${1:?usage: dk15-fig4.sh OUTDIR}
work=$out/dk15-fig4.d
mkdir -p "$work"
res=(--set mesh.dx=0.02 --set mesh.dy=0.02 --set mesh.nx=25 --set mesh.ny=53)
[ "${DK15_FULL:-0}" = 1 ] && res=()
files= titles=
for t in 0 2 5; do
  for D in 10 14 18; do
    run=$work/D$D
    half=$(awk -v d="$D" 'BEGIN { printf "%.10g", d / 200 }')
    # once per output directory (scripts/run-once: a finished run is kept)
    OMP_NUM_THREADS=${OMP_NUM_THREADS:-1} "$src/scripts/run-once" "$run" "$granmpm" run \
      "$src/inputs/silo.conf" --quiet --output "$run" --set outlet.to="$half" --set stop.mass=0 \
      --set time.t_end=5 --set time.frame_dt=0.05 --set output.checkpoint_wall=300 "${res[@]}" \
      2> "$work/D$D.log"
    f=$work/D$D-$t.csv
    "$granmpm" extract "$run" --frame $((t * 20)) --fields x,y,gdot_p > "$f"
    files="$files $f"
    titles="$titles${titles:+|}D = $D cm, t = $t s"
  done
done
gnuplot -e "files='$files'; titles='$titles'; layout='3 3'; cblabel='plastic shear rate [1/s]'; \
  cbmin=0; cbmax=10; xmin=0; xmax=0.5; ymin=0; ymax=1.05; width=1300; height=1500; psize=0.25; \
  outfile='$out/dk15-fig4.png'; suptitle='silo discharge (half silo, symmetry line at x = 0)'" \
  "$src/figures/snapshots.gp"
