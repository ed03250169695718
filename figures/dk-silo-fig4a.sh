#!/usr/bin/env bash
# [DK-silo] Fig. 4(a): the silo jamming phase diagram, A = 0.1 ... 3 against
# W/d = 1 ... 5 (inputs/silo-jam.conf, 35 runs of scripts/sweep-jam, about
# 16 minutes on 2 cores), with the boundary W/d = c A through the origin
# (c the middle of the range sweep-jam finds) and, if the sweep was also
# traced (sweep-jam --trace), the traced brackets and their fitted line.
#   figures/dk-silo-fig4a.sh OUTDIR
# The sweep is $GRANMPM_JAM_SWEEP or OUTDIR/jam-sweep (figures/jam-sweep.inc),
# shared with the Fig. 4(b), 5 and 6 drivers. Every finished run of it is
# drawn, so runs that failed are left out rather than failing the figure.
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
export GRANMPM=${GRANMPM:-$src/src/app/granmpm}
out=${1:?usage: dk-silo-fig4a.sh OUTDIR}
work=$out/dk-silo-fig4a.d
mkdir -p "$work"
source "$src/figures/jam-sweep.inc"
As="0.1 0.5 1 1.5 2 2.5 3" wds="1 2 3 4 5"
jam_runs "$As" "$wds" ||
  echo "dk-silo-fig4a.sh: sweep-jam failed; drawing the runs that finished" >&2
# collect every finished run of the sweep (runs nothing): DIR/jam.csv and
# DIR/diagram.txt, and DIR/trace.csv, trace.txt if it was traced
trace=()
[ -s "$sweep/trace.csv" ] && trace=(--trace)
"$src/scripts/sweep-jam" --out "$sweep" --collect ${trace[@]+"${trace[@]}"} > "$work/sweep.txt"
cat "$work/sweep.txt"
cp "$sweep/jam.csv" "$work/jam.csv"
[ "$(wc -l < "$work/jam.csv")" -gt 1 ] || { echo "dk-silo-fig4a.sh: no finished run in $sweep" >&2; exit 1; }
missing=$(jam_missing "$As" "$wds" | tr '\n' ' ')
[ -z "$missing" ] || echo "dk-silo-fig4a.sh: not in the diagram (no finished run): $missing" >&2

# "boundary W/d = c A: c in (LO, HI) puts N of M runs on the wrong side"
args=
line=$(grep '^boundary W/d = c A' "$sweep/diagram.txt" 2> /dev/null || true)
if [ -n "$line" ]; then
  cp "$sweep/diagram.txt" "$work/diagram.txt"
  read -r lo hi nw <<< "$(echo "$line" | sed 's/.*c in (\([^,]*\), *\([^)]*\)) puts \([0-9]*\) of.*/\1 \2 \3/')"
  if [ "$hi" != inf ]; then
    c=$(awk -v a="$lo" -v b="$hi" 'BEGIN { printf "%.6g", (a + b) / 2 }')
    args="c=$c; clo='$(printf %.3g "$lo")'; chi='$(printf %.3g "$hi")'; nwrong='$nw'; "
    echo "boundary drawn: W/d = $c A (middle of ($lo, $hi))"
  else
    echo "dk-silo-fig4a.sh: no finite boundary (c in ($lo, inf): no run flows); no line drawn" >&2
  fi
fi
if [ ${#trace[@]} -gt 0 ] && [ -s "$sweep/trace.txt" ]; then
  ct=$(sed -n 's/^traced boundary: W\/d = c A, c = \([^ ]*\) .*/\1/p' "$sweep/trace.txt")
  if [ -n "$ct" ]; then
    cp "$sweep/trace.csv" "$sweep/trace.txt" "$work/"
    args="$args trace='$work/trace.csv'; ctrace=$ct; "
  fi
fi
gnuplot -e "$args data='$work/jam.csv'; out='$out/dk-silo-fig4a.png'" "$src/figures/dk-silo-fig4a.gp"
