#!/bin/sh
# bench-callgrind.sh: `scripts/bench --callgrind` gives a figure only from a
# measurement that worked. A program that fails under valgrind, or one that
# exits 0 without doing the run, must stop the bench with exit status 1, a
# message and no figure; the real program on the tiny case gives a count in
# a plausible range for its 512 points and a serial share in percent, or,
# on a CPU with AVX-512 where this build uses it (valgrind 3.19 cannot
# decode it), exit status 1 and a message that says so.
set -u
: "${GRANMPM:?set GRANMPM to the granmpm program (make check does)}"
srcdir=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
if [ -n "${GRANMPM_SANITIZED:-}" ]; then
  echo "SKIP: a sanitizer build (it does not run under valgrind)"
  exit 77
fi
command -v valgrind >/dev/null || { echo "SKIP: no valgrind (scripts/install-deps installs it)"; exit 77; }
tmp=$(mktemp -d "${TMPDIR:-/tmp}/bench-callgrind.XXXXXX") || exit 99
trap 'rm -rf "$tmp"' EXIT INT TERM
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }

# bench BIN: runs the bench on the tiny case; sets rc, out (stdout), err
bench() {
  rc=0
  GRANMPM=$1 "$srcdir/scripts/bench" --callgrind tiny >"$tmp/out" 2>"$tmp/err" || rc=$?
  out=$(cat "$tmp/out")
  err=$(cat "$tmp/err")
}

# refused LABEL SCRIPT MESSAGE: a program with body SCRIPT makes the bench
# exit 1 with MESSAGE (a grep pattern) on stderr and no figure
refused() {
  printf '#!/bin/sh\n%s\n' "$2" >"$tmp/fake"
  chmod +x "$tmp/fake"
  bench "$tmp/fake"
  [ "$rc" -eq 1 ] || fail "$1: exit status $rc (expected 1)"
  echo "$err" | grep -q "$3" || fail "$1: no message: $err"
  echo "$out" | grep -q '^tiny ' && fail "$1: a figure printed: $out"
}
refused "a failing program" 'echo "fake: failing on purpose" >&2; exit 3' \
  'under valgrind failed (exit status 3'
refused "a program that does nothing" 'exit 0' 'no figure'

# the program itself
bench "$GRANMPM"
if [ "$rc" -eq 0 ]; then
  # the tiny case's cost per particle-step: a few hundred instructions (the
  # 20000-point silo takes about 380 with this scheme; the tiny case's
  # per-step overheads, spread over only 512 points, add to it)
  set -- $(echo "$out" | awk '$1 == "tiny" { print $2, $3, $4 }')
  if [ $# -ne 3 ]; then
    fail "exit status 0 without a figure: $out"
  else
    [ "$1" -eq 512 ] || fail "tiny case: $1 points (expected 512)"
    awk -v f="$2" 'BEGIN { exit !(f >= 100 && f <= 5000) }' ||
      fail "tiny case: $2 instructions per particle-step (expected 100 to 5000)"
    # the serial share: a percentage; most of a step is in the parallel
    # regions (the point and node loops), so well below half
    awk -v f="$3" 'BEGIN { exit !(f >= 0 && f <= 50) }' ||
      fail "tiny case: serial share $3 % (expected 0 to 50)"
    echo "tiny case: $2 instructions per particle-step, $3 % serial"
  fi
elif [ "$rc" -eq 1 ] && echo "$err" | grep -q 'cannot decode AVX-512' && grep -qw avx512f /proc/cpuinfo; then
  echo "this build uses AVX-512, which valgrind cannot decode: refused as it should be"
  echo "$out" | grep -q '^tiny ' && fail "AVX-512: a figure printed: $out"
else
  fail "the program: exit status $rc: $err"
fi

[ "$fails" -eq 0 ] || exit 1
echo "PASS"
