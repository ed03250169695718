#!/bin/sh
# cli-size.sh: `granmpm check`'s estimates of a run's memory and output
# (docs/input-reference.md, "The size of a run") against what the run
# takes: the memory estimate 1.0 to 1.4 times the peak resident memory
# (tests/maxrss), the output estimate 1.0 to 2 times the bytes of the run
# directory, for the example (plane, 1600 points, 26 frames) and the 3D
# silo (32768 points, 6 frames), and the 3D silo with the hyperelastic NGF
# (its store carries F and Fp). The estimates err on the large side by
# design: a run that check passes must fit.
set -u
: "${GRANMPM:?set GRANMPM to the granmpm program (make check does)}"
srcdir=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
builddir=${GRANMPM_BUILDDIR:-$srcdir}
if [ -n "${GRANMPM_SANITIZED:-}" ]; then
  echo "SKIP: a sanitizer build (its shadow memory is part of every peak)"
  exit 77
fi
tmp=$(mktemp -d "${TMPDIR:-/tmp}/cli-size.XXXXXX") || exit 99
trap 'rm -rf "$tmp"' EXIT INT TERM
export OMP_NUM_THREADS=1
fails=0

# MB VALUE UNIT: VALUE (as check prints it: 43.3 MB, 512 kB, 1.2 GB) in bytes
bytes() {
  awk -v v="$1" -v u="$2" 'BEGIN { f = u == "kB" ? 1024 : u == "MB" ? 1048576 : u == "GB" ? 1073741824 : 1; printf "%.0f\n", v * f }'
}

# size LABEL INPUT SETS...
size() {
  label=$1
  input=$2
  shift 2
  line=$("$GRANMPM" check "$input" "$@" | sed -n 's/^# estimated memory \([0-9.e+]*\) \([kMG]*B\) .*, output \([0-9.e+]*\) \([kMG]*B\) .*/\1 \2 \3 \4/p')
  # shellcheck disable=SC2086
  set -- "$@" && set -- $line "$@"
  [ $# -ge 4 ] || { echo "FAIL $label: no estimate from check"; fails=$((fails + 1)); return; }
  mem=$(bytes "$1" "$2")
  out=$(bytes "$3" "$4")
  shift 4
  rss=$("$builddir/tests/maxrss" "$GRANMPM" run "$input" "$@" --quiet --output "$tmp/$label") ||
    { echo "FAIL $label: the run failed"; fails=$((fails + 1)); return; }
  written=$(du -s -B1 "$tmp/$label" | awk '{ print $1 }')
  awk -v l="$label" -v m="$mem" -v r="$rss" -v o="$out" -v w="$written" 'BEGIN {
    rm = m / (r * 1024); ro = o / w
    ok = rm >= 1.0 && rm <= 1.4 && ro >= 1.0 && ro <= 2.0
    printf "%s %s: memory %.1f MB estimated, peak %.1f MB (%.2f; 1.0 ... 1.4), output %.1f MB estimated, %.1f MB written (%.2f; 1.0 ... 2)\n",
      ok ? "ok  " : "FAIL", l, m / 1048576, r / 1024, rm, o / 1048576, w / 1048576, ro
    exit !ok }' || fails=$((fails + 1))
}

size example "$srcdir/inputs/example.conf" --set time.t_end=0.5
size silo3d "$srcdir/inputs/silo3d.conf" --set time.t_end=0.1 --set time.frame_dt=0.02
size silo3d-hyper "$srcdir/inputs/silo3d.conf" --set time.t_end=0.1 --set time.frame_dt=0.02 \
  --set material.model=ngf_hyper

[ "$fails" -eq 0 ] && echo "cli-size: all passed"
exit $((fails > 0))
