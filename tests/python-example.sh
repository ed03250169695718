#!/bin/sh
# python-example.sh: examples/python/plot_frame.py (docs/output.md) on a
# small plane run (its last frame and frame 1) and a small 3D run (a z
# slab): it writes a PNG that is not blank, and the frame, time, point count
# and pressure range it prints are those of diagnostics.csv and of `granmpm
# extract` (--frame, --z-range) summed here with awk. Skipped (77) without
# a python3 that has h5py, numpy and matplotlib.
set -u
: "${GRANMPM:?set GRANMPM to the granmpm program (make check does)}"
srcdir=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
export OMP_NUM_THREADS=1
py=
for c in ${PYTHON:-} python3 /usr/bin/python3; do # Debian's modules are /usr/bin/python3's
  if command -v "$c" >/dev/null 2>&1 && "$c" -c 'import h5py, numpy, matplotlib' 2>/dev/null; then
    py=$c
    break
  fi
done
[ -n "$py" ] || {
  echo "SKIP: no python3 with h5py, numpy and matplotlib" \
    "(Debian: python3-h5py python3-numpy python3-matplotlib)"
  exit 77
}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/python-example.XXXXXX") || exit 99
trap 'rm -rf "$tmp"' EXIT INT TERM
fails=0
fail() { echo "FAIL $1"; fails=$((fails + 1)); }

. "$srcdir/tests/small-runs.sh"

# LABEL RUN FRAME EXTRACT-ARGS -- PLOT-ARGS: the plot of RUN and its summary
check() {
  label=$1 run=$2 frame=$3
  shift 3
  ex=
  while [ "$1" != "--" ]; do ex="$ex $1"; shift; done
  shift
  png="$tmp/$label.png"
  "$py" "$srcdir/examples/python/plot_frame.py" "$tmp/$run" "$png" "$@" >"$tmp/out" 2>"$tmp/err" ||
    { fail "$label: exit status $?: $(cat "$tmp/err")"; return; }
  [ "$(head -c 8 "$png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] ||
    { fail "$label: $png is not a PNG"; return; }
  # a picture, not a blank page: many colours, a tenth of the pixels or more not white
  "$py" -c 'import sys, numpy as np, matplotlib.pyplot as plt
img = plt.imread(sys.argv[1])
rgb = img[:, :, :3].reshape(-1, 3)
colours, ink = len(np.unique(rgb, axis=0)), np.mean(rgb.sum(axis=1) < 2.9)
print("%d x %d pixels, %d colours, %.0f %% not white"
      % (img.shape[1], img.shape[0], colours, 100 * ink))
sys.exit(0 if colours >= 50 and ink >= 0.10 else 1)' "$png" >"$tmp/img" ||
    { fail "$label: $png looks blank: $(cat "$tmp/img")"; return; }
  echo "$label: $(cat "$tmp/out"); $(cat "$tmp/img")"
  # frame and time: diagnostics.csv has one row per frame
  if [ "$frame" = last ]; then
    want_frame=$(($(wc -l <"$tmp/$run/diagnostics.csv") - 2))
  else
    want_frame=$frame
  fi
  want_t=$(awk -F, -v k="$want_frame" 'NR == k + 2 {print $1}' "$tmp/$run/diagnostics.csv")
  # shellcheck disable=SC2086 # ex: extract's own options, split on purpose
  "$GRANMPM" extract "$tmp/$run" --frame "$frame" --fields p $ex >"$tmp/p" ||
    { fail "$label: extract failed"; return; }
  awk -v frame="$want_frame" -v t="$want_t" -v label="$label" '
    function abs(a) { return a < 0 ? -a : a }
    function near(a, b, tol) { return abs(a - b) <= tol * (abs(a) + abs(b)) }
    FNR == NR && FNR > 1 {     # extract: a header, then p of each point
      if (n == 0 || $1 < lo) lo = $1
      if (n == 0 || $1 > hi) hi = $1
      n++
      next
    }
    FNR != NR {                # "frame K t T s: N points, p LO to HI Pa"
      if (!($1 == "frame" && $2 == frame && $3 == "t" && near($4, t, 1e-9) && $6 == n &&
            near($9, lo, 1e-15) && near($11, hi, 1e-15) && $12 == "Pa")) {
        printf "FAIL %s: printed \"%s\", want frame %d, t %s, %d points, p %.17g to %.17g\n",
               label, $0, frame, t, n, lo, hi
        exit 1
      }
    }' FS=, "$tmp/p" FS=' ' "$tmp/out" || fails=$((fails + 1))
}
check last r2 last -- # the default frame
check frame1 r2 1 -- --frame 1
check slab r3 last --z-range 0:0.04 -- --z-range 0:0.04
check all3d r3 last -- --frame last

[ "$fails" -eq 0 ] || { echo "python-example: $fails failed"; exit 1; }
echo "python-example: all passed"
