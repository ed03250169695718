#!/bin/sh
# paraview-example.sh: examples/paraview/pressure.py (docs/output.md) under
# pvpython on a small plane run and a small 3D run: it writes a PNG with
# points in it, and the time, point count and pressure range it prints are
# those of the last row of diagnostics.csv and of `granmpm extract --frame
# last` summed here with awk. Skipped (77) without pvpython, or without a
# display and xvfb-run.
set -u
: "${GRANMPM:?set GRANMPM to the granmpm program (make check does)}"
srcdir=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
export OMP_NUM_THREADS=1
command -v pvpython >/dev/null 2>&1 || { echo "SKIP: pvpython not installed"; exit 77; }
. "$srcdir/tests/display.sh"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/paraview-example.XXXXXX") || exit 99
trap 'rm -rf "$tmp"' EXIT INT TERM
fails=0
fail() { echo "FAIL $1"; fails=$((fails + 1)); }

. "$srcdir/tests/small-runs.sh"

# The picture: its size, its colours, and the share of pixels not white
# between the title and the colour bar, where only points are drawn.
cat >"$tmp/image.py" <<'PY'
import sys
from vtkmodules.vtkIOImage import vtkPNGReader
r = vtkPNGReader()
r.SetFileName(sys.argv[1])
r.Update()
w, h, _ = r.GetOutput().GetDimensions()
try:
    import numpy as np
    from vtkmodules.util.numpy_support import vtk_to_numpy
except ImportError:
    print("%d x %d pixels (no numpy: not looked into)" % (w, h))
    sys.exit(0 if w > 0 and h > 0 else 1)
a = vtk_to_numpy(r.GetOutput().GetPointData().GetScalars())[:, :3].astype(int).reshape(h, w, 3)
colours = len(np.unique(a.reshape(-1, 3), axis=0))
ink = np.mean(a[int(0.4 * h):int(0.93 * h)].sum(axis=2) < 750)   # rows from the bottom up
print("%d x %d pixels, %d colours, %.1f %% of the middle not white" % (w, h, colours, 100 * ink))
sys.exit(0 if colours >= 50 and ink >= 0.01 else 1)
PY

# Both runs drawn under one X server. xvfb-run -a started right after
# another one (paraview3.sh) can pick the display that one's server still
# holds while it goes away, and pvpython then aborts: "bad X server
# connection"; then once more, a moment later.
cat >"$tmp/draw.sh" <<SH
for r in r2 r3; do
  pvpython "$srcdir/examples/paraview/pressure.py" "$tmp/\$r" "$tmp/\$r.png" \
    >"$tmp/\$r.out" 2>"$tmp/\$r.err"
  echo \$? >"$tmp/\$r.st"
  pvpython "$tmp/image.py" "$tmp/\$r.png" >"$tmp/\$r.img" 2>>"$tmp/\$r.err"
  echo \$? >"$tmp/\$r.ist"
done
SH
$run sh "$tmp/draw.sh"
for again in 1 2; do
  [ -n "$run" ] && grep -qs "bad X server connection" "$tmp/r2.err" "$tmp/r3.err" || break
  echo "paraview-example: the X server went away; once more"
  sleep 2
  $run sh "$tmp/draw.sh"
done
if [ -n "$run" ] && grep -qs "bad X server connection" "$tmp/r2.err" "$tmp/r3.err"; then
  echo "SKIP: pvpython found no usable X server three times (the display, not the script)"
  exit 77
fi

for r in r2 r3; do
  [ "$(cat "$tmp/$r.st" 2>/dev/null)" = 0 ] ||
    { fail "$r: pvpython exit status $(cat "$tmp/$r.st" 2>/dev/null):
$(tail -n 20 "$tmp/$r.err")"; continue; }
  [ "$(head -c 8 "$tmp/$r.png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] ||
    { fail "$r: $r.png is not a PNG"; continue; }
  [ "$(cat "$tmp/$r.ist")" = 0 ] ||
    { fail "$r: $r.png looks blank: $(cat "$tmp/$r.img")"; continue; }
  echo "$r: $(grep -v '^$' "$tmp/$r.out"); $(cat "$tmp/$r.img")"
  want_t=$(tail -n 1 "$tmp/$r/diagnostics.csv" | cut -d, -f1)
  "$GRANMPM" extract "$tmp/$r" --frame last --fields p >"$tmp/p" ||
    { fail "$r: extract failed"; continue; }
  awk -v t="$want_t" -v label="$r" '
    function abs(a) { return a < 0 ? -a : a }
    function near(a, b, tol) { return abs(a - b) <= tol * (abs(a) + abs(b)) }
    FNR == NR && FNR > 1 {     # extract: a header, then p of each point
      if (n == 0 || $1 < lo) lo = $1
      if (n == 0 || $1 > hi) hi = $1
      n++
      next
    }
    FNR != NR && $1 == "t" {   # "t T s: N points, p LO to HI Pa"
      seen = 1
      if (!(near($2, t, 1e-9) && $4 == n && near($7, lo, 1e-15) && near($9, hi, 1e-15) &&
            $10 == "Pa")) {
        printf "FAIL %s: printed \"%s\", want t %s, %d points, p %.17g to %.17g\n",
               label, $0, t, n, lo, hi
        exit 1
      }
    }
    END { if (!seen) { printf "FAIL %s: no summary line\n", label; exit 1 } }
  ' FS=, "$tmp/p" FS=' ' "$tmp/$r.out" || fails=$((fails + 1))
done

[ "$fails" -eq 0 ] || { echo "paraview-example: $fails failed"; exit 1; }
echo "paraview-example: all passed"
