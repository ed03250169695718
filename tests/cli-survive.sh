#!/bin/sh
# cli-survive.sh: runs that stop and continue (README.md, "Checkpoints,
# signals and resuming").
#
#  - The example stopped by SIGTERM on two threads: exit 3 and one line
#    naming the resume command; the directory is then refused by `run`
#    (naming --force and resume), `resume --t-end T` on one thread finishes
#    it, and its diagnostics.csv, run.xdmf and every frame of run.h5 are
#    bitwise those of an uninterrupted run to T (the stop frame written off
#    schedule is gone); info says finished, resumed once; no checkpoint is
#    left. T is chosen after the stop, at least 0.015 s later (the signal
#    lands wherever the run is). Runs on two threads wait passively (a
#    spinning OpenMP thread on a busy core makes them several times slower).
#  - The same for the NGF chute (ngf-chute-quick, shortened) stopped by
#    SIGUSR1 after its fluidity was seeded (t_seed = 10 ms), two threads
#    before, one after.
#  - A layer with a free wheel turning on it and a plate pushed through it
#    along a velocity table (tests/inputs/bodies.conf), stopped by SIGTERM:
#    bodies.csv and bodies.xdmf too are bitwise those of the uninterrupted
#    run, and `extract --bodies` reads the same rows back from run.h5.
#  - The NGF chute with the implicit diffusion and checkpoints every 12.5 ms
#    of simulated time, on one thread, killed by SIGKILL (no chance to write
#    anything) two frames after a checkpoint (frames every 5 ms): resumed
#    from the checkpoint on two threads, the frames written after it are
#    replaced and the result is bitwise the same.
#    A copy of the stopped example with one byte of its checkpoint changed
#    is refused by resume and shown unusable by info, naming the checksum.
#    While the run writes, a second run (--force too) and a resume of its
#    directory are refused, naming its pid and host; killed, it leaves no
#    lock behind (the resume above).
#  - A body over the fill is refused with the file, line and key.
#  - --force replaces a run; a second signal ends a run at once.
set -u
: "${GRANMPM:?set GRANMPM to the granmpm program (make check does)}"
srcdir=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
builddir=${GRANMPM_BUILDDIR:-$srcdir}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/cli-survive.XXXXXX") || exit 99
pid=""
trap 'if [ -n "$pid" ]; then kill -KILL "$pid" 2>/dev/null; fi; rm -rf "$tmp"' EXIT INT TERM
export OMP_NUM_THREADS=1          # two only where the test says so
fails=0

fail() {
  echo "FAIL $1"
  fails=$((fails + 1))
}

# wait_rows FILE N: until FILE has N lines (or the run in $pid has ended).
wait_rows() {
  while [ "$(cat "$1" 2>/dev/null | wc -l)" -lt "$2" ]; do
    kill -0 "$pid" 2>/dev/null || return 1
    sleep 0.01
  done
}

# same_run A B LABEL: diagnostics, XDMF index and every dataset of every
# frame of run.h5 bitwise equal (tests/test_output --same-frames), and the
# last frame extracted alike.
same_run() {
  cmp -s "$1/diagnostics.csv" "$2/diagnostics.csv" || fail "$3: diagnostics.csv differs"
  cmp -s "$1/run.xdmf" "$2/run.xdmf" || fail "$3: run.xdmf differs"
  if [ -e "$1/bodies.xdmf" ] || [ -e "$2/bodies.xdmf" ]; then
    cmp -s "$1/bodies.xdmf" "$2/bodies.xdmf" || fail "$3: bodies.xdmf differs"
  fi
  if [ -e "$1/bodies.csv" ] || [ -e "$2/bodies.csv" ]; then
    cmp -s "$1/bodies.csv" "$2/bodies.csv" || fail "$3: bodies.csv differs"
    [ -e "$2/bodies.xdmf" ] || fail "$3: a run with bodies wrote no bodies.xdmf"
    "$GRANMPM" extract "$2" --bodies | cmp -s - "$2/bodies.csv" ||
      fail "$3: extract --bodies (run.h5) differs from bodies.csv"
  fi
  n=$(($(wc -l <"$1/diagnostics.csv") - 1))
  [ "$n" -ge 3 ] || fail "$3: only $n frames"
  "$builddir/tests/test_output" --same-frames "$1" "$2" || fail "$3: the frames of run.h5 differ"
  "$GRANMPM" extract "$1" --frame last >"$tmp/a.csv" && "$GRANMPM" extract "$2" --frame last >"$tmp/b.csv" &&
    cmp -s "$tmp/a.csv" "$tmp/b.csv" || fail "$3: the last frame extracted differs"
}

# The end time for a run stopped at t: at least `least`, 0.015 s after t.
end_after() {
  awk -v t="$1" -v least="$2" 'BEGIN { e = t + 0.015; if (e < least) e = least; printf "%.3f", e }'
}

# stop_and_resume LABEL INPUT SIGNAL ROWS LEAST SETS...: the run to 1 s on two
# threads, SIGNAL once ROWS lines of diagnostics exist; resumed on one
# thread to T; compared with a run to T on one thread.
stop_and_resume() {
  label=$1
  input=$2
  sig=$3
  rows=$4
  least=$5
  shift 5
  d=$tmp/$label
  OMP_NUM_THREADS=2 OMP_WAIT_POLICY=passive "$GRANMPM" run "$input" --quiet --output "$d" \
    --set time.t_end=1 "$@" 2>"$tmp/err" &
  pid=$!
  wait_rows "$d/diagnostics.csv" "$rows" || fail "$label: the run ended before the signal"
  kill -"$sig" "$pid"
  wait "$pid"
  st=$?
  pid=""
  [ "$st" -eq 3 ] || { fail "$label: exit status $st after SIG$sig (want 3)"; cat "$tmp/err"; return; }
  line=$(cat "$tmp/err")
  case "$line" in
    "granmpm: stopped by SIG$sig at t = "*" s (step "*"), checkpoint written; continue with: granmpm resume $d") ;;
    *) fail "$label: stop message '$line'"; return ;;
  esac
  [ "$("$GRANMPM" info "$d" --status)" = stopped ] || fail "$label: status not 'stopped'"
  [ -f "$d/checkpoint.h5" ] || fail "$label: no checkpoint"
  t=$(echo "$line" | sed 's/.* at t = \([^ ]*\) s .*/\1/')
  T=$(end_after "$t" "$least")
  "$GRANMPM" run "$input" --quiet --output "$d" --set time.t_end=1 "$@" 2>"$tmp/err"
  st=$?
  [ "$st" -eq 2 ] && [ "$(cat "$tmp/err")" = "granmpm: output directory '$d' holds a run (run.h5): replace it with --force, or continue it with: granmpm resume $d" ] ||
    fail "$label: an occupied directory: exit $st, '$(cat "$tmp/err")'"
  if [ "$label" = example ]; then   # a damaged copy is refused, and info says why
    cp -r "$d" "$d.bad"
    printf 'X' | dd of="$d.bad/checkpoint.h5" bs=1 seek=4000 conv=notrunc 2>/dev/null
    "$GRANMPM" resume "$d.bad" --quiet 2>"$tmp/err"
    st=$?
    [ "$st" -eq 2 ] && [ "$(cat "$tmp/err")" = "granmpm: nothing to resume in '$d.bad': '$d.bad/checkpoint.h5': its bytes do not match its checksum (a damaged checkpoint)" ] ||
      fail "$label: a damaged checkpoint: exit $st, '$(cat "$tmp/err")'"
    "$GRANMPM" info "$d.bad" | grep -qx "checkpoint: unusable: '$d.bad/checkpoint.h5': its bytes do not match its checksum (a damaged checkpoint)" ||
      fail "$label: info of a damaged checkpoint: $("$GRANMPM" info "$d.bad" | grep '^checkpoint')"
  fi
  "$GRANMPM" resume "$d" --t-end 0 --quiet 2>"$tmp/err"
  st=$?
  tc=$(sed -n "s/^granmpm: resume: --t-end 0 is not after the checkpoint's t = \([^ ]*\) s .*/\1/p" "$tmp/err")
  [ "$st" -eq 2 ] && awk -v a="$tc" -v b="$t" 'BEGIN { exit !(a != "" && a > 0 && (a - b) ^ 2 < 1e-10 * b * b) }' ||
    fail "$label: an early --t-end: exit $st, '$(cat "$tmp/err")'"
  "$GRANMPM" resume "$d" --t-end "$T" --quiet || fail "$label: resume failed"
  "$GRANMPM" run "$input" --quiet --output "$d.ref" --set time.t_end="$T" "$@" ||
    fail "$label: the reference run failed"
  same_run "$d.ref" "$d" "$label"
  [ -e "$d/checkpoint.h5" ] && fail "$label: a finished run kept its checkpoint"
  "$GRANMPM" info "$d" >"$tmp/info"
  grep -q '^status:     finished$' "$tmp/info" && grep -q '^resumed:    1 time$' "$tmp/info" &&
    grep -q "threads=1: .*resume $d --t-end $T --quiet\$" "$tmp/info" ||
    { fail "$label: info after the resumption"; cat "$tmp/info"; }
}

stop_and_resume example "$srcdir/inputs/example.conf" TERM 3 0.025 --set time.frame_dt=0.005
stop_and_resume ngf "$srcdir/inputs/ngf-chute-quick.conf" USR1 5 0.03 \
  --set time.frame_dt=0.005 --set stop.t_min=2
stop_and_resume bodies "$srcdir/tests/inputs/bodies.conf" TERM 4 0.03

# Killed outright, two frames after a checkpoint.
d=$tmp/killed
sets="--set material.diffusion=implicit --set time.frame_dt=0.005 --set stop.t_min=2"
# shellcheck disable=SC2086
"$GRANMPM" run "$srcdir/inputs/ngf-chute-quick.conf" --quiet --output "$d" \
  --set time.t_end=1 --set output.checkpoint_dt=0.0125 $sets &
pid=$!
wait_rows "$d/diagnostics.csv" 6 || fail "killed: the run ended before the kill"
# while it writes, neither a second run (even with --force) nor a resume may
# write the same directory; both name the holder
held="is in use by granmpm pid $pid on host $(hostname): one run or resume at a time writes a directory"
"$GRANMPM" run "$srcdir/inputs/example.conf" --quiet --output "$d" --force 2>"$tmp/err"
st=$?
[ "$st" -eq 2 ] && [ "$(cat "$tmp/err")" = "granmpm: output directory '$d' $held" ] ||
  fail "locked: run --force: exit $st, '$(cat "$tmp/err")'"
"$GRANMPM" resume "$d" --quiet 2>"$tmp/err"
st=$?
[ "$st" -eq 2 ] && [ "$(cat "$tmp/err")" = "granmpm: output directory '$d' $held" ] ||
  fail "locked: resume: exit $st, '$(cat "$tmp/err")'"
kill -KILL "$pid"
wait "$pid"
pid=""
t=$("$GRANMPM" info "$d" | sed -n 's/^checkpoint: t = \([^ ]*\) s.*/\1/p')
[ -n "$t" ] || fail "killed: no checkpoint"
[ "$("$GRANMPM" info "$d" --status)" = running ] || fail "killed: status not 'running'"
T=$(end_after "$t" 0.035)
OMP_NUM_THREADS=2 OMP_WAIT_POLICY=passive "$GRANMPM" resume "$d" --t-end "$T" --quiet ||
  fail "killed: resume failed"
# shellcheck disable=SC2086
"$GRANMPM" run "$srcdir/inputs/ngf-chute-quick.conf" --quiet --output "$d.ref" \
  --set time.t_end="$T" $sets || fail "killed: the reference run failed"
same_run "$d.ref" "$d" killed

# A body over the fill is refused at the key to change, where its section opens.
"$GRANMPM" run "$srcdir/tests/inputs/bodies.conf" --quiet --output "$tmp/overlap" \
  --set body.plate.cy=0.06 2>"$tmp/err"
st=$?
[ "$st" -eq 2 ] && [ "$(cat "$tmp/err")" = "granmpm: $srcdir/tests/inputs/bodies.conf:47: key 'body.plate.carve': body 'plate' overlaps 19 points of the fills at t = 0 (allowed: none, or carve = true to leave them out)" ] ||
  fail "overlapping body: exit $st, '$(cat "$tmp/err")'"
# With carve = true the 19 points are left out, and check counts the run's
# points after the carving (its size estimate is for the run it builds).
"$GRANMPM" check "$srcdir/tests/inputs/bodies.conf" --set body.plate.cy=0.06 \
  --set body.plate.carve=true >"$tmp/check.out" || fail "carve: check failed"
"$GRANMPM" run "$srcdir/tests/inputs/bodies.conf" --quiet --output "$tmp/carve" \
  --set body.plate.cy=0.06 --set body.plate.carve=true --set time.t_end=0.001 \
  --set time.frame_dt=0.001 ||
  fail "carve: run failed"
n_check=$(sed -n 's/^# size: \([0-9]*\) points.*/\1/p' "$tmp/check.out")
n_run=$("$GRANMPM" extract "$tmp/carve" --frame 0 --fields id | tail -n +2 | wc -l)
n_full=$("$GRANMPM" check "$srcdir/tests/inputs/bodies.conf" |
  sed -n 's/^# size: \([0-9]*\) points.*/\1/p')
[ "$n_check" = "$n_run" ] && [ "$n_run" -eq $((n_full - 19)) ] ||
  fail "carve: check counts '$n_check' points, the run has $n_run, the fill without the body $n_full"

# --force replaces a run, checkpoint included.
"$GRANMPM" run "$srcdir/inputs/example.conf" --quiet --output "$tmp/ngf" --force \
  --set time.t_end=0.005 --set time.frame_dt=0.005 || fail "--force: exit $?"
[ "$(($(wc -l <"$tmp/ngf/diagnostics.csv") - 1))" -eq 2 ] || fail "--force: not a new run"

# A second signal ends a run at once: both arrive while it is stopped.
"$GRANMPM" run "$srcdir/inputs/example.conf" --quiet --output "$tmp/twice" \
  --set time.t_end=1 2>"$tmp/err" &
pid=$!
wait_rows "$tmp/twice/diagnostics.csv" 2 || fail "twice: the run ended before the signals"
kill -STOP "$pid"
kill -HUP "$pid"
kill -TERM "$pid"
kill -CONT "$pid"
wait "$pid"
st=$?
pid=""
[ "$st" -gt 128 ] && [ ! -s "$tmp/err" ] || fail "two signals: exit $st, '$(cat "$tmp/err")'"

[ "$fails" -eq 0 ] && echo "all passed"
[ "$fails" -eq 0 ]
