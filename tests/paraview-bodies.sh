#!/bin/sh
# paraview-bodies.sh: the bodies' outlines in bodies.xdmf, as ParaView
# reads them with each of its XDMF readers (XDMF, Xdmf3 S and T), for the
# wheel and the plate of tests/inputs/bodies.conf in the plane and in a 3D
# slab of it (periodic in z, the bodies through the mesh). A time per
# frame; in the plane two closed polylines (64 + 1 and 4 + 1 vertices), in
# 3D 68 side faces between the two ends;
# every vertex of the last frame lies on its body's outline about the
# centre bodies.csv gives (the wheel's radius, the plate's half-diagonal),
# to 1e-10 m (the CSV rounds the centre to 10 digits). Skipped (77)
# without pvpython; no display is needed.
set -u
: "${GRANMPM:?set GRANMPM to the granmpm program (make check does)}"
command -v pvpython >/dev/null 2>&1 || { echo "SKIP: pvpython not installed"; exit 77; }
srcdir=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/paraview-bodies.XXXXXX") || exit 99
trap 'rm -rf "$tmp"' EXIT INT TERM
export OMP_NUM_THREADS=1
in=$srcdir/tests/inputs/bodies.conf
"$GRANMPM" run "$in" --quiet --output "$tmp/r2" --set time.t_end=0.02 ||
  { echo "FAIL: plane run"; exit 1; }
"$GRANMPM" run "$in" --quiet --output "$tmp/r3" --set time.t_end=0.02 --set mesh.nz=2 \
  --set mesh.dz=0.005 --set boundary.front=periodic --set boundary.back=periodic \
  --set fill.layer.zmin=0 --set fill.layer.zmax=0.01 || { echo "FAIL: 3D run"; exit 1; }

cat >"$tmp/check.py" <<'PY'
import csv, math, sys
from paraview import servermanager
from paraview.simple import XDMFReader, Xdmf3ReaderS, Xdmf3ReaderT
run, dim = sys.argv[1], int(sys.argv[2])
rows = list(csv.DictReader(open(run + "/bodies.csv")))
last = max(int(r["frame"]) for r in rows)
centre = {r["body"]: (float(r["x"]), float(r["y"])) for r in rows if int(r["frame"]) == last}
frames = last + 1
reach = {0: 0.02, 1: math.hypot(0.004, 0.025)}          # wheel radius, plate half-diagonal
names = ["wheel", "plate"]
want_pts, want_cells = (68, 2) if dim == 2 else (136, 68)
bad = 0
for name, make, key in (("XDMF", XDMFReader, "FileNames"),
                        ("Xdmf3ReaderS", Xdmf3ReaderS, "FileName"),
                        ("Xdmf3ReaderT", Xdmf3ReaderT, "FileName")):
    r = make(**{key: [run + "/bodies.xdmf"]})
    times = list(r.TimestepValues)
    r.UpdatePipeline(times[-1])
    b = servermanager.Fetch(r)
    if b.IsA("vtkMultiBlockDataSet"):      # the legacy reader: one block
        b = b.GetBlock(0)
    ok = len(times) == frames and b is not None
    worst = float("inf")
    if ok:
        ids = b.GetCellData().GetArray("body")
        ok = (b.GetNumberOfPoints() == want_pts and b.GetNumberOfCells() == want_cells
              and ids is not None)
        worst = 0.0
        for c in range(b.GetNumberOfCells() if ok else 0):
            k = int(ids.GetValue(c))
            cx, cy = centre[names[k]]
            cell = b.GetCell(c)
            for j in range(cell.GetNumberOfPoints()):
                x, y, z = b.GetPoint(cell.GetPointId(j))
                worst = max(worst, abs(math.hypot(x - cx, y - cy) - reach[k]))
        ok = ok and worst <= 1e-10   # the CSV rounds the centre to 10 digits (5e-12 m)
    print("%s %dD: %d times, %s points %s cells, worst |r - R| %.3g m%s"
          % (name, dim, len(times), b.GetNumberOfPoints() if b else "-",
             b.GetNumberOfCells() if b else "-", worst, "" if ok else "  WRONG"))
    bad += not ok
sys.exit(1 if bad else 0)
PY
fails=0
for dim in 2 3; do
  pvpython "$tmp/check.py" "$tmp/r$dim" "$dim" >"$tmp/out" 2>"$tmp/err"
  st=$?
  grep -v '^$' "$tmp/out"
  [ $st -eq 0 ] || { echo "FAIL: ${dim}D: pvpython exit status $st"; tail -n 5 "$tmp/err"; fails=$((fails + 1)); }
done
[ "$fails" -eq 0 ] || exit 1
echo "paraview-bodies: all passed"
