#!/bin/sh
# cli-faults.sh: faults while a run writes, damaged output read back, and a
# run that blows up. Each must end with one error line and a stated exit
# status, never a crash:
#  - a file-size limit (ulimit -f; SIGXFSZ is ignored by a run, so the write
#    fails with EFBIG), a full file system (a 200 kB tmpfs, when this test
#    may mount one; skipped otherwise), /dev/full behind diagnostics.csv and
#    behind the checkpoint's temporary file: exit 1, "cannot ...: REASON";
#    a full disk used to crash in HDF5's exit handler (status 139), then
#    left run.h5 "running": it records "failed" and why (granmpm info);
#  - the size check: a run that would not fit the tmpfs is refused (exit 2);
#  - run.h5 with a frame that lost its x and a frame whose npoints says
#    2^60 (tests/test_output --damage), and one cut in half, through
#    extract, extract --series, state and info: exit 2 naming the damage
#    (extract used to print the other columns and exit 0; --series asked for
#    2^63 bytes);
#  - a time step 20 times the stable one, declared deliberate: the run ends
#    (exit 1) naming the point, the runaway and the time step as the likely
#    cause, not a point "leaving the mesh"; info shows "failed" and that line;
#  - an unstable explicit diffusion of g, plane and 3D (ngf_hyper): the run
#    ends (exit 1) naming the point, the absurd fluidity, the time and the
#    diffusion as the likely cause (it used to finish with g = inf).
set -u
: "${GRANMPM:?set GRANMPM to the granmpm program (make check does)}"
srcdir=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
builddir=${GRANMPM_BUILDDIR:-$srcdir}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/cli-faults.XXXXXX") || exit 99
mnt=""
trap 'if [ -n "$mnt" ]; then umount "$mnt"; fi; rm -rf "$tmp"' EXIT INT TERM
export OMP_NUM_THREADS=1
fails=0
count=0

fail() {
  echo "FAIL $1"
  fails=$((fails + 1))
}

# expect LABEL STATUS WANT CMD...: CMD exits with STATUS (not a signal) and
# prints exactly one line on stderr, WANT (a shell pattern).
expect() {
  label=$1
  want_st=$2
  want=$3
  shift 3
  count=$((count + 1))
  "$@" >"$tmp/out" 2>"$tmp/err"
  st=$?
  if [ "$st" -ge 128 ]; then
    fail "$label: killed by signal $((st - 128))"
    return
  fi
  [ "$st" -eq "$want_st" ] || { fail "$label: exit status $st (want $want_st)"; cat "$tmp/err"; return; }
  lines=$(wc -l <"$tmp/err")
  [ "$lines" -eq 1 ] || { fail "$label: $lines lines on stderr (want 1)"; cat "$tmp/err"; return; }
  # shellcheck disable=SC2254
  case "$(cat "$tmp/err")" in
    $want) ;;
    *) fail "$label"; echo "  want: $want"; echo "  got:  $(cat "$tmp/err")" ;;
  esac
}

input=$srcdir/inputs/example.conf
small="--set time.t_end=0.01 --set time.frame_dt=0.0025"   # 5 frames of 1600 points

# ---- writing fails
d=$tmp/limit
expect "file-size limit" 1 "granmpm: cannot * '$d/run.h5': File too large" \
  sh -c "ulimit -f 100 && exec \"\$0\" \"\$@\"" "$GRANMPM" run "$input" $small --output "$d" --quiet

mkdir -p "$tmp/csv"
ln -s /dev/full "$tmp/csv/diagnostics.csv"
expect "diagnostics.csv on /dev/full" 1 "granmpm: cannot write '$tmp/csv/diagnostics.csv': No space left on device" \
  "$GRANMPM" run "$input" $small --output "$tmp/csv" --quiet

mkdir -p "$tmp/ck"
ln -s /dev/full "$tmp/ck/checkpoint.h5.tmp"
expect "checkpoint on /dev/full" 1 "granmpm: cannot write '$tmp/ck/checkpoint.h5.tmp': No space left on device" \
  "$GRANMPM" run "$input" $small --set output.checkpoint_dt=0.002 --output "$tmp/ck" --quiet
[ -e "$tmp/ck/checkpoint.h5" ] || [ -L "$tmp/ck/checkpoint.h5.tmp" ] &&
  fail "a failed checkpoint left checkpoint.h5 or its temporary file"

mkdir -p "$tmp/fs"
if mount -t tmpfs -o size=200k granmpm-test "$tmp/fs" 2>/dev/null; then
  mnt=$tmp/fs
  expect "output larger than the free space" 2 "granmpm: --set 'time.frame_dt=0.0025': key 'time.frame_dt': the run writes about * bytes (* frames of 1600 points), more than the * bytes free on the file system of '$mnt/run' (allowed: at most the free space, or output.allow_large = true)" \
    "$GRANMPM" run "$input" $small --output "$mnt/run" --quiet
  expect "full file system" 1 "granmpm: cannot * '$mnt/run/run.h5': No space left on device" \
    "$GRANMPM" run "$input" $small --set output.allow_large=true --output "$mnt/run" --quiet
  # the run records that it failed and why (it used to stay "running")
  "$GRANMPM" info "$mnt/run" >"$tmp/info" 2>&1
  grep -qx "status:     failed" "$tmp/info" &&
    grep -q "^failure:    cannot .* '$mnt/run/run.h5': No space left on device\$" "$tmp/info" ||
    { fail "info on the run that filled its disk"; head -n 4 "$tmp/info"; }
  [ -e "$mnt/run/.granmpm-reserve" ] && fail "the failed run left its reserve"
else
  echo "SKIP full file system: cannot mount a tmpfs here"
fi

# ---- damaged output
"$GRANMPM" run "$input" $small --output "$tmp/good" --quiet || fail "the run to damage"
cp -R "$tmp/good" "$tmp/bad"
"$builddir/tests/test_output" --damage "$tmp/bad" 4 || fail "damaging the run"
nox="granmpm: frame 4 of '$tmp/bad/run.h5' has no field 'x' (a damaged run)"
huge="granmpm: frame 0 of '$tmp/bad/run.h5': npoints = 1152921504606846976 but field 'x' holds 1600 values (a damaged run)"
expect "extract, no x" 2 "$nox" "$GRANMPM" extract "$tmp/bad" --frame last
expect "extract, 2^60 points" 2 "$huge" "$GRANMPM" extract "$tmp/bad" --frame 0
expect "extract --series, 2^60 points" 2 "$huge" "$GRANMPM" extract "$tmp/bad" --series
expect "state, no x" 2 "$nox" "$GRANMPM" state "$input" "$tmp/bad" --frame last
expect "state, 2^60 points" 2 "$huge" "$GRANMPM" state "$input" "$tmp/bad" --frame 0
cp -R "$tmp/good" "$tmp/cut"
head -c 300000 "$tmp/good/run.h5" >"$tmp/cut/run.h5"
for c in "extract" "extract --series" "info"; do
  # shellcheck disable=SC2086
  expect "$c, run.h5 cut short" 2 "granmpm: cannot open '$tmp/cut/run.h5'*truncated file*" \
    "$GRANMPM" $c "$tmp/cut"
done
expect "state, run.h5 cut short" 2 "granmpm: cannot open '$tmp/cut/run.h5'*truncated file*" \
  "$GRANMPM" state "$input" "$tmp/cut"

# ---- a blow-up is named as what it is
unstable=$srcdir/tests/inputs/bad/dt-unstable.conf
expect "unstable time step" 1 "granmpm: point *: speed * m/s at (*) m, t = * s: a runaway, more than a mesh unit per step *; likely cause: the time step: dt = 0.00211 s is 20 times the stable step 0.000106 s (key 'time.dt', allowed only with time.dt_unstable_ok)" \
  "$GRANMPM" run "$unstable" --set time.dt_unstable_ok=true --output "$tmp/unstable" --quiet
[ "$("$GRANMPM" info "$tmp/unstable" --status)" = failed ] || fail "the blown-up run is not 'failed'"
# info says why: the error's line, recorded in run.h5 (attribute failure)
"$GRANMPM" info "$tmp/unstable" >"$tmp/info" 2>&1
grep -q "^failure:    point .*: speed .* a runaway, .*likely cause: the time step: " "$tmp/info" ||
  { fail "info does not say why the blown-up run failed"; head -n 4 "$tmp/info"; }

# An unstable explicit diffusion of g (warned before the first step): the
# run used to finish (exit 0) with g = inf at 224 of 480 points in the plane,
# g = 1.6e33 in 3D, the stress still finite. Each update's fields are looked
# at: the run fails at once naming the point, g, the time and the diffusion.
warned_fail() {   # LABEL WANT CMD...: exit 1, the plan's warning, then WANT
  label=$1
  want=$2
  shift 2
  count=$((count + 1))
  "$@" >"$tmp/out" 2>"$tmp/err"
  st=$?
  [ "$st" -eq 1 ] || { fail "$label: exit status $st (want 1)"; cat "$tmp/err"; return; }
  [ "$(wc -l <"$tmp/err")" -eq 2 ] && grep -q "^granmpm: warning: .*NGF explicit diffusion unstable" "$tmp/err" ||
    { fail "$label: want the warning and one error line"; cat "$tmp/err"; return; }
  # shellcheck disable=SC2254
  case "$(tail -n 1 "$tmp/err")" in
    $want) ;;
    *) fail "$label"; echo "  want: $want"; echo "  got:  $(tail -n 1 "$tmp/err")" ;;
  esac
}
gwant="granmpm: point *: fluidity g = * 1/s at (*) m, t = * s: the fluidity is absurd: |g| dt = * > 1000 with dt = * s *; likely cause: the diffusion of g: NGF explicit diffusion unstable: * (key 'material.n_sub')"
warned_fail "unstable diffusion of g, plane" "$gwant" \
  "$GRANMPM" run "$srcdir/inputs/ngf-chute-quick.conf" --set material.A=50 --set material.t0=1e-6 \
  --set time.t_end=0.1 --output "$tmp/g2" --quiet
[ "$("$GRANMPM" info "$tmp/g2" --status)" = failed ] || fail "the run with g blown up is not 'failed'"
"$GRANMPM" info "$tmp/g2" | grep -q "^failure:    point .*: fluidity g = .*likely cause: the diffusion of g" ||
  fail "info does not say why the run with g blown up failed"
warned_fail "unstable diffusion of g, 3D ngf_hyper" "$gwant" \
  "$GRANMPM" run "$srcdir/inputs/silo3d.conf" --set mesh.nx=6 --set mesh.ny=8 --set mesh.nz=6 \
  --set fill.grains.xmax=0.06 --set fill.grains.ymax=0.06 --set fill.grains.zmax=0.06 \
  --set outlet.to=0.02 --set outlet.to2=0.02 --set material.model=ngf_hyper \
  --set material.p_sample=point --set material.A=100 --set material.t0=1e-9 \
  --set time.t_end=0.02 --set time.frame_dt=0.01 --output "$tmp/g3" --quiet

echo "$count cases, $fails failed"
[ "$fails" -eq 0 ]
