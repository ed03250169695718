# small-runs.sh, sourced by the example tests: a short plane run in
# $tmp/r2 (inputs/example.conf, 0.04 s) and a small 3D one in $tmp/r3
# (inputs/silo3d.conf on a 4 x 6 x 4 mesh, 0.2 s).
"$GRANMPM" run "$srcdir/inputs/example.conf" --quiet --output "$tmp/r2" \
  --set time.t_end=0.04 || { echo "FAIL: plane run"; exit 1; }
"$GRANMPM" run "$srcdir/inputs/silo3d.conf" --quiet --output "$tmp/r3" --set time.t_end=0.2 \
  --set mesh.nx=4 --set mesh.ny=6 --set mesh.nz=4 --set mesh.dx=0.04 --set mesh.dy=0.04 \
  --set mesh.dz=0.04 || { echo "FAIL: 3D run"; exit 1; }
