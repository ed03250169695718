#!/usr/bin/env bash
# The evidence of the [DK-silo] section 7.2 classifier over time, for three
# runs of the jamming sweep (inputs/silo-jam.conf): A = 1, W/d = 1 (an arch),
# A = 1, W/d = 5 (a drain) and A = 0.1, W/d = 5 (a drain that pulses). Per
# run: the mean vertical velocity of the dense material between frames
# (`granmpm extract RUN --jam-series`), the part of the run where its last
# zero crossing votes flowing (first half) or static (last tenth), the
# crossing itself, and the points leaving per frame.
#   figures/dk-silo-votes.sh OUTDIR
# The runs come from the shared jamming sweep (figures/jam-sweep.inc:
# $GRANMPM_JAM_SWEEP or OUTDIR/jam-sweep).
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
export GRANMPM=${GRANMPM:-$src/src/app/granmpm}
out=${1:?usage: dk-silo-votes.sh OUTDIR}
work=$out/dk-silo-votes.d
mkdir -p "$work"
source "$src/figures/jam-sweep.inc"
jam_runs "1" "1 5"
jam_runs "0.1" "5"
args=
k=0
for r in "1 1" "1 5" "0.1 5"; do
  set -- $r
  k=$((k + 1))
  run=$sweep/runs/A$1-wd$2
  "$GRANMPM" extract "$run" --jam-series > "$work/A$1-wd$2.csv"
  # class,t_zero,t_end,velocity_vote,leaving_per_frame,outflow_vote,frames
  IFS=, read -r cls tz te vv lv ov _ <<< "$("$GRANMPM" extract "$run" --jam | sed -n 2p)"
  echo "A = $1, W/d = $2: $cls (velocity $vv, last crossing $tz s; outflow $ov, $lv points a frame)"
  args+="f$k='$work/A$1-wd$2.csv'; tz$k='$tz'; te$k=$te; "
  args+="t$k='A = $1, W/d = $2: $cls (velocity: $vv, outflow: $ov, $(printf %.3g "$lv") a frame)'; "
done
gnuplot -e "$args out='$out/dk-silo-votes.png'" "$src/figures/dk-silo-votes.gp"
