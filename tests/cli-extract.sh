#!/bin/sh
# cli-extract.sh: `granmpm extract` measurements on a small run
# (docs/diagnostics.md). Bad options and a missing run give exit status 2
# and one line on stderr naming the option; good ones give the documented
# columns with one row per bin, column or frame.
set -u
: "${GRANMPM:?set GRANMPM to the granmpm program (make check does)}"
srcdir=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/cli-extract.XXXXXX") || exit 99
trap 'rm -rf "$tmp"' EXIT INT TERM
fails=0
fail() { echo "FAIL $1"; fails=$((fails + 1)); }

# a 0.04 s run of the example column: frames at 0, 0.02, 0.04 s
"$GRANMPM" run "$srcdir/inputs/example.conf" --quiet --output "$tmp/run" \
  --set time.t_end=0.04 || { echo "FAIL: example run"; exit 1; }

bad() { # LABEL WORD ARGS...: exit 2, one stderr line containing WORD
  label=$1 word=$2
  shift 2
  "$GRANMPM" extract "$@" >"$tmp/out" 2>"$tmp/err"
  st=$?
  [ "$st" -eq 2 ] || { fail "$label: exit status $st (want 2)"; return; }
  [ "$(wc -l <"$tmp/err")" -eq 1 ] || fail "$label: $(wc -l <"$tmp/err") lines on stderr"
  grep -q -- "$word" "$tmp/err" || fail "$label: stderr lacks '$word': $(cat "$tmp/err")"
}
bad "zero bins" "--profile" "$tmp/run" --profile 0
bad "fractional bins" "--profile" "$tmp/run" --profile 2.5
bad "empty range" "--range" "$tmp/run" --profile 4 --range 1:0
bad "range not a pair" "--range" "$tmp/run" --profile 4 --range 1
bad "negative width" "--width" "$tmp/run" --surface --width -1
bad "width too small" "--width" "$tmp/run" --surface --width 1e-12
bad "slope width too small" "--width" "$tmp/run" --series --slope auto --width 1e-12
bad "front-min 0" "--front-min" "$tmp/run" --series --front-min 0
bad "front-cell 0" "--front-cell" "$tmp/run" --series --front-cell 0
bad "slope word" "--slope" "$tmp/run" --series --slope steep
bad "gdot-min negative" "--gdot-min" "$tmp/run" --series --gdot-min -1
bad "frame beyond" "frame 9" "$tmp/run" --profile 4 --frame 9
bad "missing run" "cannot open" "$tmp/none" --series

rows() { # LABEL HEADER NROWS ARGS...
  label=$1 header=$2 n=$3
  shift 3
  "$GRANMPM" extract "$@" >"$tmp/out" 2>"$tmp/err" || { fail "$label: exit $?: $(cat "$tmp/err")"; return; }
  [ "$(head -n 1 "$tmp/out")" = "$header" ] || fail "$label: header '$(head -n 1 "$tmp/out")'"
  [ "$(($(wc -l <"$tmp/out") - 1))" -eq "$n" ] || fail "$label: $(($(wc -l <"$tmp/out") - 1)) rows (want $n)"
}
rows "profile" "y,vx,vy,mass,n" 4 "$tmp/run" --profile 4
rows "series" "t,vx,speed,ax,mu,flow_mass,front" 3 "$tmp/run" --series
rows "series slope" "t,vx,speed,ax,mu,flow_mass,front,slope,slope_deg,xa,xb" 3 "$tmp/run" --series --slope 0.05:0.15
# the 0.2 m wide column fills 20 columns of the 0.01 m units
rows "surface" "x,top" 20 "$tmp/run" --surface --frame 0
# 2 x 2 points in each of 20 x 20 units
rows "smooth" "x,y,p,p_smooth,gdot_p,state" 1600 "$tmp/run" --smooth
# the initial front is the right edge of the column less half a point spacing
front=$("$GRANMPM" extract "$tmp/run" --series | awk -F, 'NR == 2 { print $7 }')
[ "$front" = "0.1975" ] || fail "initial front $front (want 0.1975)"
[ $fails -eq 0 ] && echo "cli-extract: all passed"
exit $((fails > 0))
