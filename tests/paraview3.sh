#!/bin/sh
# paraview3.sh: ParaView opens the run.xdmf of a 3D run (test_output3
# --write3) with each of its XDMF readers (XDMF, Xdmf3 S and T) and finds
# the points in 3D: 300 points at the first time, 240 at the last, the
# bounds of the lattice in x, y and z, and the 3D fields as point arrays. Skipped (77) without pvpython, or
# without a display and xvfb-run.
set -u
command -v pvpython >/dev/null 2>&1 || { echo "SKIP: pvpython not installed"; exit 77; }
builddir=${GRANMPM_BUILDDIR:-$(cd "$(dirname "$0")/.." && pwd)}
srcdir=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
. "$srcdir/tests/display.sh"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/paraview3.XXXXXX") || exit 99
trap 'rm -rf "$tmp"' EXIT INT TERM
"$builddir/tests/test_output3" --write3 "$tmp/run3" || { echo "FAIL: writing the 3D run"; exit 1; }

cat >"$tmp/check.py" <<'PY'
import sys
from paraview.simple import XDMFReader, Xdmf3ReaderS, Xdmf3ReaderT
path = sys.argv[1]
# frame 0: 10 x 10 x 3 points at 0.05 + 0.1 k (z to 0.25); frame 2: 60
# points of the top layer fewer, 2 mm up
want = {0.0: (300, (0.05, 0.95, 0.05, 0.95, 0.05, 0.25)),
        0.2: (240, (0.05, 0.95, 0.05, 0.95, 0.052, 0.252))}
bad = 0
for name, make, key in (("XDMF", XDMFReader, "FileNames"),
                        ("Xdmf3ReaderS", Xdmf3ReaderS, "FileName"),
                        ("Xdmf3ReaderT", Xdmf3ReaderT, "FileName")):
    r = make(**{key: [path]})
    times = list(r.TimestepValues)
    for t, (n, b) in sorted(want.items()):
        r.UpdatePipeline(t)
        info = r.GetDataInformation()
        got_n = info.GetNumberOfPoints()
        got_b = info.GetBounds()
        pd = info.GetPointDataInformation()
        arrays = [pd.GetArrayInformation(k).GetName() for k in range(pd.GetNumberOfArrays())]
        ok = (got_n == n and all(abs(g - w) < 1e-9 for g, w in zip(got_b, b)) and
              all(a in arrays for a in ("z", "vz", "syz", "szx", "r3z", "p", "id")))
        print("%s t=%g: %d points, bounds x %.6g..%.6g y %.6g..%.6g z %.6g..%.6g, "
              "%d point arrays (times %s)%s"
              % (name, t, got_n, *got_b, len(arrays), ",".join("%g" % v for v in times),
                 "" if ok else "  WRONG " + ",".join(arrays)))
        bad += not ok
sys.exit(1 if bad else 0)
PY
for try in 1 2 3; do
  $run pvpython "$tmp/check.py" "$tmp/run3/run.xdmf" >"$tmp/out" 2>"$tmp/err"
  st=$?
  [ -n "$run" ] && grep -qs "bad X server connection" "$tmp/err" || break
  sleep 2
done
if [ -n "$run" ] && grep -qs "bad X server connection" "$tmp/err"; then
  echo "SKIP: pvpython found no usable X server three times (the display, not the reader)"
  exit 77
fi
grep -v '^$' "$tmp/out"
if [ $st -ne 0 ]; then
  echo "FAIL: pvpython exit status $st"
  cat "$tmp/err"
  exit 1
fi
echo "paraview3: all passed"
