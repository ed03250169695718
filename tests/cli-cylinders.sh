#!/bin/sh
# cli-cylinders.sh: 3D cylinders along x, y and z from the input
# (tests/inputs/good/cylinders.conf; docs/input-reference.md, fill.axis).
#
# A run of a few steps fills each cylinder with exactly the sub-cell centres
# inside it: its first frame holds the centres that an awk computation of
# its own finds, fill by fill, and as many as counted by hand. The resolved
# input the run stores (`granmpm info`) checks and prints itself again, and
# run again it gives the same run, bit for bit.
set -u
: "${GRANMPM:?set GRANMPM to the granmpm program (make check does)}"
srcdir=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/cli-cylinders.XXXXXX") || exit 99
trap 'rm -rf "$tmp"' EXIT INT TERM
fails=0
fail() { echo "FAIL $1"; fails=$((fails + 1)); }

conf=$srcdir/tests/inputs/good/cylinders.conf
steps="--set time.t_end=0.0005 --set time.frame_dt=0.00025"
"$GRANMPM" run "$conf" --quiet --output "$tmp/run" $steps 2>"$tmp/err" ||
  { echo "FAIL: run: $(cat "$tmp/err")"; exit 1; }
"$GRANMPM" extract "$tmp/run" --frame 0 --fields x,y,z >"$tmp/frame0" 2>"$tmp/err" ||
  { echo "FAIL: extract: $(cat "$tmp/err")"; exit 1; }

# The sub-cell centres of the mesh (8 x 6 x 6 units of 0.1 m from the
# origin) inside each cylinder, as in cylinders.conf: AXIS LO HI, the centre
# across the axis (the two other axes in the order x, y, z), the radius, and
# n sub-cells a unit. Printed to 1e-9 m, one "x,y,z" line a point.
centres() { # AXIS LO HI C1 C2 R N
  awk -v a="$1" -v lo="$2" -v hi="$3" -v c1="$4" -v c2="$5" -v r="$6" -v n="$7" 'BEGIN {
    nu[0] = 8; nu[1] = 6; nu[2] = 6; h = 0.1 / n
    for (i = 0; i < nu[0] * n; i++)
      for (j = 0; j < nu[1] * n; j++)
        for (k = 0; k < nu[2] * n; k++) {
          p[0] = (i + 0.5) * h; p[1] = (j + 0.5) * h; p[2] = (k + 0.5) * h
          u = a == 0 ? 1 : 0; v = a == 2 ? 1 : 2          # the axes across a
          if (p[a] < lo || p[a] > hi)
            continue
          if ((p[u] - c1) ^ 2 + (p[v] - c2) ^ 2 > r * r)
            continue
          printf "%.9f,%.9f,%.9f\n", p[0], p[1], p[2]
        }
  }'
}
centres 2 0.05 0.55 0.15 0.15 0.1 2 >"$tmp/post"     # along z: (cx, cy)
centres 0 0.3 0.75 0.15 0.2 0.12 2 >"$tmp/log"       # along x: (cy, cz)
centres 1 0.3 0.55 0.5 0.4 0.15 3 >"$tmp/pillar"     # along y: (cx, cz)

# By hand: the post has 12 centres a layer (offsets of odd multiples of
# 0.025 m: 1^2 + 1^2 and 1^2 + 3^2 within 16) in 10 layers; the log 16 a
# section (1, 1; 1, 3; 3, 1; 3, 3 within 0.12^2 / 0.025^2 = 23.04) in 9;
# the pillar, at 3 sub-cells a unit (odd multiples of 1/60 m, within 9^2),
# 60 a section in 8.
for f in post:120 log:144 pillar:480; do
  n=$(wc -l <"$tmp/${f%%:*}")
  [ "$n" -eq "${f#*:}" ] || fail "${f%%:*}: awk finds $n centres (by hand ${f#*:})"
done
sort "$tmp/post" "$tmp/log" "$tmp/pillar" >"$tmp/want"
awk -F, 'NR > 1 { printf "%.9f,%.9f,%.9f\n", $1, $2, $3 }' "$tmp/frame0" | sort >"$tmp/got"
[ "$(wc -l <"$tmp/got")" -eq 744 ] || fail "frame 0 has $(wc -l <"$tmp/got") points (want 744)"
cmp -s "$tmp/got" "$tmp/want" ||
  { fail "frame 0 is not the sub-cell centres inside the cylinders"; diff "$tmp/got" "$tmp/want" | head; }

# The stored input: each cylinder with its own keys only.
"$GRANMPM" info "$tmp/run" >"$tmp/info" || fail "info"
sed -n '/^input:$/,$p' "$tmp/info" | sed '1d; s/^  //' >"$tmp/stored.conf"
fill_keys() { # TITLE: the keys of that fill in the stored input, on one line
  sed -n "/^fill $1 {/,/^}/p" "$tmp/stored.conf" | awk '$2 == "=" { printf "%s ", $1 }'
}
want_keys() { for k in "$@"; do printf "%s " "$k"; done; }
[ "$(fill_keys post)" = "$(want_keys shape cx cy radius ppu density vx vy zmin zmax axis vz lithostatic k0 pressure)" ] ||
  fail "post's stored keys: $(fill_keys post)"
[ "$(fill_keys log)" = "$(want_keys shape xmin xmax cy radius ppu density vx vy axis cz vz lithostatic k0 pressure)" ] ||
  fail "log's stored keys: $(fill_keys log)"
[ "$(fill_keys pillar)" = "$(want_keys shape ymin ymax cx radius ppu density vx vy axis cz vz lithostatic k0 pressure)" ] ||
  fail "pillar's stored keys: $(fill_keys pillar)"
for v in 'post axis "z"' 'log axis "x"' 'log cz 0.2' 'pillar axis "y"' 'pillar cz 0.4' 'pillar ppu 3'; do
  set -- $v
  sed -n "/^fill $1 {/,/^}/p" "$tmp/stored.conf" | grep -qx "  $2 = $3" ||
    fail "fill $1 stored without '$2 = $3'"
done

# It checks, and prints itself.
if "$GRANMPM" check "$tmp/stored.conf" >"$tmp/again.conf" 2>"$tmp/err"; then
  sed '1d' "$tmp/stored.conf" >"$tmp/a"
  sed '1d; /^# /d' "$tmp/again.conf" >"$tmp/b"
  cmp -s "$tmp/a" "$tmp/b" || { fail "the stored input changes when checked"; diff "$tmp/a" "$tmp/b"; }
else
  fail "the stored input does not check: $(cat "$tmp/err")"
fi

# Run again from it: the same frames.
"$GRANMPM" run "$tmp/stored.conf" --quiet --output "$tmp/again" 2>"$tmp/err" ||
  fail "run of the stored input: $(cat "$tmp/err")"
for frame in 0 last; do
  "$GRANMPM" extract "$tmp/run" --frame $frame >"$tmp/first" &&
    "$GRANMPM" extract "$tmp/again" --frame $frame >"$tmp/second" ||
    { fail "extract frame $frame"; continue; }
  [ "$(wc -l <"$tmp/first")" -eq 745 ] || fail "frame $frame: $(wc -l <"$tmp/first") lines"
  cmp -s "$tmp/first" "$tmp/second" || fail "frame $frame differs when run from the stored input"
done

echo "cylinders: $fails failed"
[ "$fails" -eq 0 ]
