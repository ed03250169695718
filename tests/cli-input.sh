#!/bin/sh
# cli-input.sh: `granmpm check` and `granmpm run` on bad inputs, `check` on
# good ones (docs/input-reference.md).
#
# Every file in tests/inputs/bad must give exit status 2 (not a signal),
# nothing on stdout and exactly one line on stderr, naming the file and the
# line: "granmpm: FILE:LINE: ...", equal to the message on the file's
# "# expect: " line (one ending in "..." is a prefix: for lists of names that
# other modules own, such as the material models, and for the machine's
# memory and free space); the hostile ones give it from `run` too, which
# then writes nothing. So must a missing file, a directory, a file with a NUL byte,
# bad --set arguments, a line too long and a text of unclosed "${" (in
# linear time), and an output directory the run cannot write. Good inputs (tests/inputs/good and the shipped inputs/) exit
# 0, and the resolved input they print is itself an input that checks and
# prints the same.
set -u
: "${GRANMPM:?set GRANMPM to the granmpm program (make check does)}"
srcdir=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/cli-input.XXXXXX") || exit 99
mnt=""
trap 'if [ -n "$mnt" ]; then umount "$mnt"; fi; rm -rf "$tmp"' EXIT INT TERM
fails=0
count=0

fail() {
  echo "FAIL $1"
  fails=$((fails + 1))
}

# check_bad LABEL WANT [ARGS...]: `granmpm $cmd ARGS` (cmd: check unless
# set) must exit 2 and print exactly the line WANT on stderr, nothing on
# stdout.
cmd=check
check_bad() {
  label=$1
  want=$2
  shift 2
  count=$((count + 1))
  "$GRANMPM" $cmd "$@" >"$tmp/out" 2>"$tmp/err"
  st=$?
  if [ "$st" -ge 128 ]; then
    fail "$label: killed by signal $((st - 128))"
    return
  fi
  [ "$st" -eq 2 ] || { fail "$label: exit status $st (want 2)"; return; }
  [ -s "$tmp/out" ] && { fail "$label: output on stdout"; return; }
  lines=$(wc -l <"$tmp/err")
  [ "$lines" -eq 1 ] || { fail "$label: $lines lines on stderr (want 1)"; cat "$tmp/err"; return; }
  got=$(cat "$tmp/err")
  case "$want" in
    *...) case "$got" in "${want%...}"*) return ;; esac ;;  # a prefix
    *) [ "$got" = "$want" ] && return ;;
  esac
  fail "$label"
  echo "  want: $want"
  echo "  got:  $got"
}

# Every bad input file names itself and a line.
for f in "$srcdir"/tests/inputs/bad/*.conf; do
  msg=$(sed -n 's/^# expect: //p' "$f" | head -n 1)
  [ -n "$msg" ] || { fail "$f: no '# expect: ' line"; continue; }
  case "$msg" in
    [0-9]*:*) ;;
    *) fail "$f: the expected message has no line number"; continue ;;
  esac
  check_bad "$(basename "$f")" "granmpm: $f:$msg" "$f"
done
[ "$count" -ge 50 ] || fail "only $count bad inputs found under $srcdir/tests/inputs/bad"

# run stops at the same line as check, before it writes anything: the
# hostile inputs (those found by fuzzing and fault injection, and those that
# pass the reader) and one of each kind of reader error.
cmd=run
for name in dt-unstable size-memory size-output dt-sub-tiny dt-sub-too-many fill-no-point \
            real-denormal real-hex real-nan real-inf real-overflow int-overflow env-unclosed \
            unclosed-section unknown-key syntax-missing-equals polygon-no-area 3d-size-memory \
            bom-twice nul-in-comment escape-nul-path 3d-escape-nul-axis nested-braces; do
  f=$srcdir/tests/inputs/bad/$name.conf
  msg=$(sed -n 's/^# expect: //p' "$f" | head -n 1)
  check_bad "run $(basename "$f")" "granmpm: $f:$msg" "$f" --output "$tmp/run"
  [ -e "$tmp/run/run.h5" ] && fail "run $(basename "$f"): wrote $tmp/run/run.h5"
done
cmd=check

# A fill that holds no point at a coarser mesh: check used to pass it, and
# run failed naming neither line nor key.
for cmd in check run; do
  check_bad "$cmd fill without points" "granmpm: $srcdir/tests/inputs/good/full.conf:52: key 'fill.block.ppu': the region holds no point: no centre of the 3 x 3 sub-cells of a unit (5.33 m x 0.0333 m each) lies in it (allowed: a region or a ppu that puts at least one point in the fill)" \
    "$srcdir/tests/inputs/good/full.conf" --set mesh.dx=16 --output "$tmp/run"
done
cmd=check

# Unclosed "${" and long lines cost one pass: 4 MB of "${" took 82 s, a
# 4 MB line 10 s; under a second here with room for a slow machine.
awk 'BEGIN { for (i = 0; i < 65536; i++) { for (j = 0; j < 32; j++) printf "${"; printf "\n" } }' \
  >"$tmp/dollars.conf"
start=$(date +%s)
check_bad dollars "granmpm: $tmp/dollars.conf:1: '\${' starts no variable reference (allowed: \${NAME} or \${NAME:-fallback}, NAME of letters, digits, '_')" \
  "$tmp/dollars.conf"
awk 'BEGIN { printf "mesh {\n  nx = "; for (i = 0; i < 4194304; i++) printf "1"; printf "\n}\n" }' \
  >"$tmp/long.conf"
check_bad long-line "granmpm: $tmp/long.conf:2: a line of 4194311 characters (allowed: at most 65536 per line)" \
  "$tmp/long.conf"
[ $(($(date +%s) - start)) -le 5 ] || fail "unclosed \${ and a long line: $(($(date +%s) - start)) s"

# A huge 3D fill is refused at once: the point count went through every row
# of sub-cells of the box (4 x 4000 x 4000 units at 8 points a side: 1e9
# rows, 36 s here), now through one slice across the fill's gate axis
# (0.05 s). Under timeout, so that it cannot hang the suite; the bound of
# 15 s leaves a noisy machine or a sanitizer build room while the row-by-row
# count stays far beyond it.
count=$((count + 1))
start=$(date +%s)
timeout 60 "$GRANMPM" check "$srcdir/inputs/silo3d.conf" --set mesh.nx=4 --set mesh.ny=4000 \
  --set mesh.nz=4000 --set fill.grains.xmax=0.04 --set fill.grains.ymax=40 \
  --set fill.grains.zmax=40 --set fill.grains.ppu=8 --set outlet.to=0.02 >"$tmp/out" 2>"$tmp/err"
st=$?
took=$(($(date +%s) - start))
case "$st $(cat "$tmp/err")" in
  "2 granmpm: --set 'fill.grains.ppu=8': key 'fill.grains.ppu': the run needs about "*" bytes of memory (32768000000 points, 80040005 nodes), more than the "*) ;;
  *) fail "huge 3D fill: exit $st"; cat "$tmp/err" ;;
esac
[ "$took" -le 15 ] || fail "huge 3D fill: check took $took s"

# An output directory the run cannot write is refused by check as by run
# (exit 2, before anything is written; check used to pass it and run failed
# with exit 1), and trying it leaves nothing behind: a file (/etc/passwd as
# the audit found it), a path through a file, a read-only directory (mode 555
# for a user; a read-only tmpfs for root, who may write in any mode, when it
# may mount one), named from --output and from the input's output.dir.
good="$srcdir/tests/inputs/good/minimal.conf"
allowed="(allowed: a directory that can be created, or one this user may write in)"
printf 'x\n' >"$tmp/file"
for cmd in check run; do
  check_bad "$cmd --output FILE" "granmpm: output directory '$tmp/file': the run cannot write its output there: it is not a directory $allowed" \
    "$good" --output "$tmp/file"
  check_bad "$cmd --output FILE/x" "granmpm: output directory '$tmp/file/x': the run cannot write its output there: Not a directory $allowed" \
    "$good" --output "$tmp/file/x"
done
cmd=check
check_bad "check --output /etc/passwd" "granmpm: output directory '/etc/passwd': the run cannot write its output there: it is not a directory $allowed" \
  "$good" --output /etc/passwd
{ cat "$good"; printf 'output {\n  dir = "%s"\n}\n' "$tmp/file"; } >"$tmp/outfile.conf"
check_bad "output.dir a file" "granmpm: $tmp/outfile.conf:19: key 'output.dir': the run cannot write its output in '$tmp/file': it is not a directory $allowed" \
  "$tmp/outfile.conf"
ro=""
if [ "$(id -u)" -ne 0 ]; then
  mkdir "$tmp/ro" && chmod 555 "$tmp/ro" && ro=$tmp/ro
  why="Permission denied"
elif mkdir "$tmp/ro" && mount -t tmpfs -o ro,size=20m granmpm-ro "$tmp/ro" 2>/dev/null; then
  ro=$tmp/ro
  mnt=$ro
  why="Read-only file system"
fi
if [ -n "$ro" ]; then
  for cmd in check run; do
    check_bad "$cmd --output read-only" "granmpm: output directory '$ro': the run cannot write its output there: cannot create a file in it: $why $allowed" \
      "$good" --output "$ro"
    check_bad "$cmd --output read-only/new" "granmpm: output directory '$ro/new': the run cannot write its output there: cannot create a directory in '$ro': $why $allowed" \
      "$good" --output "$ro/new"
  done
  cmd=check
  [ "$(id -u)" -ne 0 ] && chmod 755 "$ro"
  if [ -n "$mnt" ]; then umount "$mnt" && mnt=""; fi
else
  echo "SKIP read-only output directory: neither a user nor able to mount a tmpfs"
fi
count=$((count + 1))
"$GRANMPM" check "$good" --output "$tmp/new/run" >/dev/null 2>"$tmp/err" || fail "check --output NEW: $(cat "$tmp/err")"
[ -e "$tmp/new" ] && fail "check --output NEW created it"
[ -z "$(find "$tmp" -name '.granmpm-check-*')" ] || fail "check left its try of the output behind"

# The file itself is the problem.
check_bad missing "granmpm: $tmp/missing.conf: cannot open input file: No such file or directory" \
  "$tmp/missing.conf"
check_bad directory "granmpm: $tmp: cannot read input file: Is a directory" "$tmp"
printf 'mesh {\n  nx = 1\000\n}\n' >"$tmp/nul.conf"
check_bad nul-byte "granmpm: $tmp/nul.conf:2: NUL byte in the input file (allowed: text)" \
  "$tmp/nul.conf"
if [ "$(id -u)" -ne 0 ]; then  # root can read anything
  cp "$srcdir/tests/inputs/good/minimal.conf" "$tmp/unreadable.conf"
  chmod 000 "$tmp/unreadable.conf"
  check_bad unreadable "granmpm: $tmp/unreadable.conf: cannot open input file: Permission denied" \
    "$tmp/unreadable.conf"
fi

# Bad --set arguments name the argument instead of a line.
good="$srcdir/tests/inputs/good/minimal.conf"
check_bad set-type "granmpm: --set 'mesh.nx=abc': key 'mesh.nx': expected an integer, got 'abc'" \
  "$good" --set mesh.nx=abc
check_bad set-range "granmpm: --set 'fill.ppu=9': key 'fill.ppu': value 9 out of range (allowed: 1 ... 8)" \
  "$good" --set fill.ppu=9
check_bad set-key "granmpm: --set 'time.tend=1': unknown key 'time.tend' (allowed keys in 'time': dt, cfl, t_end, frame_dt, flip, transfer, dt_unstable_ok)" \
  "$good" --set time.tend=1
check_bad set-form "granmpm: --set 'mesh.nx': expected section.key=value" "$good" --set mesh.nx
check_bad set-cross "granmpm: --set 'time.t_end=0.001': key 'time.t_end': frame_dt = 0.01 > t_end = 0.001 (allowed: frame_dt <= t_end)" \
  "$good" --set time.t_end=0.001

# NGF with an unstable explicit diffusion of g: a warning, not an error (exit
# 0, the resolved input on stdout, one line on stderr naming the smallest n_sub);
# with that n_sub, silence. dt = 3e-5 s (within the stable 3.34e-5 s) and
# A = 0.6: 3e-5 * 0.6^2 * 0.005^2 / 1e-3 * 4e6 = 1.08.
chute="$srcdir/inputs/ngf-chute.conf"
count=$((count + 1))
"$GRANMPM" check "$chute" --set time.dt=3e-5 --set material.A=0.6 >"$tmp/out" 2>"$tmp/err"
st=$?
want="granmpm: warning: $chute: NGF explicit diffusion unstable: (dt/n_sub) A^2 d^2/t0 (2/dx^2 + 2/dy^2) = 1.08 > 1 with dt = 3e-05 s, n_sub = 1; needs n_sub >= 2 (key 'material.n_sub')"
if [ "$st" -ne 0 ] || [ ! -s "$tmp/out" ] || [ "$(cat "$tmp/err")" != "$want" ]; then
  fail "ngf diffusion warning: exit $st, stderr '$(cat "$tmp/err")'"
  echo "  want: $want"
fi
count=$((count + 1))
"$GRANMPM" check "$chute" --set time.dt=3e-5 --set material.A=0.6 --set material.n_sub=2 >"$tmp/out" 2>"$tmp/err"
st=$?
[ "$st" -eq 0 ] && [ ! -s "$tmp/err" ] || fail "ngf diffusion with n_sub = 2: exit $st, stderr '$(cat "$tmp/err")'"

# check prints the size of the run: the example's column of 0.2 m x 0.2 m in
# units of 0.01 m with 2 x 2 points each has 40 x 40 = 1600 points, its mesh
# of 60 x 25 units 61 x 26 = 1586 nodes; 3 s in steps of 5.27799e-05 s
# (cfl 0.5 of the stable 1.05560e-4 s) make ceil(56839.8) = 56840 steps;
# frames at 0, every 0.02 s and at the end: at most 2 + 150.
count=$((count + 1))
"$GRANMPM" check "$srcdir/inputs/example.conf" >"$tmp/out" 2>"$tmp/err"
grep -qx "# size: 1600 points, 1586 nodes, 56840 steps of 5.27799e-05 s (stable: 0.00010556 s), 1 substeps per step, at most 152 frames" "$tmp/out" &&
  grep -q "^# estimated memory .* MB (.* available), output .* MB (.* free where it goes)\$" "$tmp/out" ||
  { fail "the size of the example"; grep '^# ' "$tmp/out"; }

# check estimates the run time (steps x substeps x points at the rates of
# scripts/bench, solver/plan.c) and warns above a day on one thread:
# material.n_sub = 1e6 used to pass silently (133 days for the example).
count=$((count + 1))
grep -q "^# estimated run time 19 s on one thread (56840 steps x 1 substeps x 1600 points; docs/input-reference.md, \"The size of a run\")\$" "$tmp/out" ||
  { fail "the run time of the example"; grep '^# ' "$tmp/out"; }
count=$((count + 1))
"$GRANMPM" check "$srcdir/inputs/example.conf" --set material.n_sub=1000000 >"$tmp/out" 2>"$tmp/err"
st=$?
want="granmpm: warning: $srcdir/inputs/example.conf: the run would take about 133 days on one thread (56840 steps x 1e+06 substeps x 1600 points; more than a day) (key 'material.n_sub')"
if [ "$st" -ne 0 ] || ! grep -q "^# estimated run time 133 days on one thread" "$tmp/out" ||
   [ "$(cat "$tmp/err")" != "$want" ]; then
  fail "n_sub = 1e6: exit $st, stderr '$(cat "$tmp/err")'"
  echo "  want: $want"
fi

# Good inputs: exit 0, and the printed input reads back to the same.
for f in "$srcdir"/tests/inputs/good/*.conf "$srcdir"/inputs/*.conf; do
  [ -f "$f" ] || continue
  count=$((count + 1))
  name=$(basename "$f")
  if ! "$GRANMPM" check "$f" >"$tmp/resolved.conf" 2>"$tmp/err"; then
    fail "$name: exit status $? for a good input"
    cat "$tmp/err"
    continue
  fi
  [ -s "$tmp/err" ] && { fail "$name: output on stderr"; cat "$tmp/err"; }
  if ! "$GRANMPM" check "$tmp/resolved.conf" >"$tmp/again.conf" 2>"$tmp/err"; then
    fail "$name: its resolved input does not check"
    cat "$tmp/err"
    continue
  fi
  # line 1 names the source file; the machine's free memory and disk change
  sed '1d; /^# estimated memory /d' "$tmp/resolved.conf" >"$tmp/a"
  sed '1d; /^# estimated memory /d' "$tmp/again.conf" >"$tmp/b"
  cmp -s "$tmp/a" "$tmp/b" || fail "$name: the resolved input changes when checked again"
done

echo "$count cases, $fails failed"
[ "$fails" -eq 0 ]
