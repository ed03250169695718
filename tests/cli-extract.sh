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
rows "jam series" "t,vbar,points,left,dense" 3 "$tmp/run" --jam-series
# its frame-1 row against the points of frames 0 and 1: the mass-weighted mean
# of (y1 - y0) / (t1 - t0) over the points dense in both, matched by id; no
# outlet, so every point stays
"$GRANMPM" extract "$tmp/run" --frame 0 --fields id,y,mass,state >"$tmp/f0"
"$GRANMPM" extract "$tmp/run" --frame 1 --fields id,y,mass,state >"$tmp/f1"
"$GRANMPM" extract "$tmp/run" --jam-series >"$tmp/js"
awk -F, 'FNR == 1 { f++; next }
  f == 1 { y0[$1] = $2; s0[$1] = $4 }
  f == 2 && $4 == 0 && ($1 in s0) && s0[$1] == 0 { m += $3; my += $3 * ($2 - y0[$1]) }
  f == 2 && $4 == 0 { d1++ }
  f == 3 && FNR == 2 { t0 = $1 }
  f == 3 && FNR == 3 { t1 = $1; v = $2; n = $3; left = $4; dense = $5 }
  END { want = my / (m * (t1 - t0))
        ok = (v - want) ^ 2 <= (1e-5 * want) ^ 2 && n == 1600 && left == 0 && dense == d1
        if (!ok) printf "vbar %s (want %.8g), points %s, left %s, dense %s (want %d)\n", v, want, n, left, dense, d1
        exit !ok }' "$tmp/f0" "$tmp/f1" "$tmp/js" >"$tmp/jsmsg" || fail "jam series: $(cat "$tmp/jsmsg")"
# the initial front is the right edge of the column less half a point spacing
front=$("$GRANMPM" extract "$tmp/run" --series | awk -F, 'NR == 2 { print $7 }')
[ "$front" = "0.1975" ] || fail "initial front $front (want 0.1975)"
[ $fails -eq 0 ] && echo "cli-extract: all passed"
exit $((fails > 0))
