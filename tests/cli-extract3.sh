#!/bin/sh
# cli-extract3.sh: `granmpm extract` of a 3D run (the run of test_output3
# --write3: frames of 300, 300 and 240 points in three layers at
# z = 0.05, 0.15, 0.25 m, moved up 1 mm a frame). z is among the columns;
# --z-range keeps the points of a slab, in plain extraction and in the
# measurements; --z-range of a 2D run, --smooth of a 3D run, a bad range and
# a damaged 3D frame give exit status 2 and one line on stderr.
set -u
: "${GRANMPM:?set GRANMPM to the granmpm program (make check does)}"
srcdir=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
builddir=${GRANMPM_BUILDDIR:-$srcdir}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/cli-extract3.XXXXXX") || exit 99
trap 'rm -rf "$tmp"' EXIT INT TERM
fails=0
fail() { echo "FAIL $1"; fails=$((fails + 1)); }

"$builddir/tests/test_output3" --write3 "$tmp/run3" || { echo "FAIL: writing the 3D run"; exit 1; }

# every column, z among them; the last frame has 240 points
"$GRANMPM" extract "$tmp/run3" >"$tmp/all" 2>"$tmp/err" || fail "extract: $(cat "$tmp/err")"
case "$(head -n 1 "$tmp/all")" in
  x,y,z,vx,vy,vz,sxx,syy,szz,sxy,syz,szx,p,*r3x,r3y,r3z) ;;
  *) fail "header '$(head -n 1 "$tmp/all")'" ;;
esac
[ "$(($(wc -l <"$tmp/all") - 1))" -eq 240 ] || fail "last frame: $(($(wc -l <"$tmp/all") - 1)) rows"

# --z-range: exactly the rows of the whole frame with ZMIN <= z <= ZMAX
slab() { # LABEL FRAME ZMIN ZMAX NROWS
  "$GRANMPM" extract "$tmp/run3" --frame "$2" >"$tmp/whole" 2>"$tmp/err" || fail "$1: $(cat "$tmp/err")"
  "$GRANMPM" extract "$tmp/run3" --frame "$2" --z-range "$3:$4" >"$tmp/slab" 2>"$tmp/err" ||
    fail "$1: $(cat "$tmp/err")"
  awk -F, -v a="$3" -v b="$4" 'NR == 1 || ($3 >= a + 0 && $3 <= b + 0)' "$tmp/whole" >"$tmp/want"
  cmp -s "$tmp/slab" "$tmp/want" || fail "$1: not the rows of the slab"
  [ "$(($(wc -l <"$tmp/slab") - 1))" -eq "$5" ] || fail "$1: $(($(wc -l <"$tmp/slab") - 1)) rows (want $5)"
}
slab "middle layer" 1 0.1 0.2 100
slab "two layers" 0 0 0.2 200
slab "all" last -1 1 240
slab "none" 2 0.3 0.4 0
"$GRANMPM" extract "$tmp/run3" --frame 0 --fields id --z-range 0.2:0.3 >"$tmp/ids" ||
  fail "--fields with --z-range"
[ "$(sed -n 2p "$tmp/ids")" = 2147480200 ] || fail "first id of the top layer: $(sed -n 2p "$tmp/ids")"

# measurements of a slab, on x and y
"$GRANMPM" extract "$tmp/run3" --profile 5 --frame 0 --range 0:1 --z-range 0.2:0.3 >"$tmp/prof" ||
  fail "profile with --z-range"
[ "$(awk -F, 'NR > 1 { n += $5 } END { print n }' "$tmp/prof")" = 100 ] ||
  fail "profile of the top layer: $(awk -F, 'NR > 1 { n += $5 } END { print n }' "$tmp/prof") points"
"$GRANMPM" extract "$tmp/run3" --profile 5 --frame 0 --range 0:1 >"$tmp/prof" || fail "profile"
[ "$(awk -F, 'NR > 1 { n += $5 } END { print n }' "$tmp/prof")" = 300 ] || fail "profile of all"
"$GRANMPM" extract "$tmp/run3" --series --z-range 0:0.1 >"$tmp/series" || fail "series with --z-range"
[ "$(($(wc -l <"$tmp/series") - 1))" -eq 3 ] || fail "series: $(($(wc -l <"$tmp/series") - 1)) rows"
"$GRANMPM" extract "$tmp/run3" --surface --frame 0 --z-range 0:0.1 >"$tmp/surf" || fail "surface"
[ "$(($(wc -l <"$tmp/surf") - 1))" -eq 10 ] || fail "surface: $(($(wc -l <"$tmp/surf") - 1)) columns"

bad() { # LABEL WORD ARGS...: exit 2, one stderr line containing WORD
  label=$1 word=$2
  shift 2
  "$GRANMPM" extract "$@" >"$tmp/out" 2>"$tmp/err"
  st=$?
  [ "$st" -eq 2 ] || { fail "$label: exit status $st (want 2)"; return; }
  [ "$(wc -l <"$tmp/err")" -eq 1 ] || fail "$label: $(wc -l <"$tmp/err") lines on stderr"
  grep -q -- "$word" "$tmp/err" || fail "$label: stderr lacks '$word': $(cat "$tmp/err")"
}
bad "empty z range" "--z-range" "$tmp/run3" --z-range 1:0
bad "z range not a pair" "--z-range" "$tmp/run3" --profile 4 --z-range 1
bad "smooth of a 3D run" "3D" "$tmp/run3" --smooth

# a 2D run has no z
"$GRANMPM" run "$srcdir/inputs/example.conf" --quiet --output "$tmp/run2" \
  --set time.t_end=0.002 --set time.frame_dt=0.002 || { echo "FAIL: example run"; exit 1; }
bad "z range of a 2D run" "2D" "$tmp/run2" --z-range 0:1
bad "z range of a 2D run, profile" "2D" "$tmp/run2" --profile 4 --z-range 0:1
"$GRANMPM" extract "$tmp/run2" | head -n 1 | grep -q '^x,y,vx,vy,' || fail "2D header"

# a damaged 3D frame: its z removed
"$builddir/tests/test_output3" --damage3 "$tmp/run3" || fail "damaging the run"
bad "damaged, extract" "no field 'z'" "$tmp/run3"
bad "damaged, profile" "no field 'z'" "$tmp/run3" --profile 4
bad "damaged, series" "no field 'z'" "$tmp/run3" --series
[ $fails -eq 0 ] && echo "cli-extract3: all passed"
exit $((fails > 0))
