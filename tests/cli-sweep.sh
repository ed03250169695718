#!/bin/sh
# cli-sweep.sh: a sweep killed halfway and started again repeats no finished
# run (scripts/run-once in every sweep script).
#
# scripts/sweep-hstop on a small NGF chute (ngf-chute-quick at 27 deg, four
# depths, 60 ms each, one job at a time) runs under its own process group;
# once two runs have finished and the third has written its first frame,
# the whole group gets SIGTERM (what a queue sends at its time limit): the
# third run stops with a checkpoint (or, if the signal came before its
# first step could end, with none). The same sweep started again must leave
# the two finished runs alone, resume the third from its checkpoint (or
# start it again when it has none), run the fourth, and finish all four.
# Every granmpm run and resume goes through a wrapper that logs it, and the
# log is what is counted. Then a sweep whose shell alone is killed by
# SIGKILL: its running run stops with a checkpoint, no other starts, and
# the sweep started again resumes it. Skipped (77) without GNU parallel.
set -u
: "${GRANMPM:?set GRANMPM to the granmpm program (make check does)}"
srcdir=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
command -v parallel >/dev/null || { echo "SKIP: GNU parallel not found"; exit 77; }
command -v setsid >/dev/null || { echo "SKIP: setsid not found"; exit 77; }
tmp=$(mktemp -d "${TMPDIR:-/tmp}/cli-sweep.XXXXXX") || exit 99
group=""
trap 'if [ -n "$group" ]; then kill -KILL -"$group" 2>/dev/null; fi; rm -rf "$tmp"' EXIT INT TERM
export OMP_NUM_THREADS=1
fails=0

fail() {
  echo "FAIL $1"
  fails=$((fails + 1))
}

log=$tmp/log
cat >"$tmp/granmpm" <<EOF
#!/bin/sh
case "\$1" in
  run) for a in "\$@"; do [ "\$prev" = --output ] && echo "run \$a" >>"$log"; prev=\$a; done ;;
  resume) echo "resume \$2" >>"$log" ;;
esac
exec "$GRANMPM" "\$@"
EOF
chmod +x "$tmp/granmpm"
out=$tmp/sweep
sweep() {
  GRANMPM=$tmp/granmpm "$srcdir/scripts/sweep-hstop" --out "$out" \
    --input "$srcdir/inputs/ngf-chute-quick.conf" --angles 27 --ratios "0.7 1.1 1.4 2" \
    --t-end 0.06 --t-min 0.01 --jobs 1 >"$tmp/sweep.out" 2>&1
}
finished() {
  [ "$("$GRANMPM" info "$out/runs/$1" --status 2>/dev/null)" = finished ]
}

: >"$log"
setsid sh -c "GRANMPM='$tmp/granmpm' '$srcdir/scripts/sweep-hstop' --out '$out' \
  --input '$srcdir/inputs/ngf-chute-quick.conf' --angles 27 --ratios '0.7 1.1 1.4 2' \
  --t-end 0.06 --t-min 0.01 --jobs 1 >'$tmp/first.out' 2>&1" &
group=$!
# the third run of the log has written its first frame
third=""
while [ -z "$third" ] || [ ! -s "$out/runs/$third/diagnostics.csv" ]; do
  kill -0 "$group" 2>/dev/null || break
  third=$(sed -n '3s/^run //p' "$log")
  sleep 0.01
done
kill -TERM -"$group" 2>/dev/null
while kill -0 "$group" 2>/dev/null; do sleep 0.05; done
group=""
[ -n "$third" ] || fail "the first sweep ended before its third run began"
first=$(sed -n '1s/^run //p' "$log") second=$(sed -n '2s/^run //p' "$log")
finished "$first" && finished "$second" || fail "the first two runs did not finish"
finished "$third" && fail "the third run was not interrupted"
had_checkpoint=0
[ -f "$out/runs/$third/checkpoint.h5" ] && had_checkpoint=1
lines=$(wc -l <"$log")

sweep || { fail "the second sweep: exit $?"; cat "$tmp/sweep.out"; }
sed -n "$((lines + 1)),\$p" "$log" >"$tmp/again"
grep -q " $first\$" "$tmp/again" && fail "finished run $first ran again"
grep -q " $second\$" "$tmp/again" && fail "finished run $second ran again"
if [ "$had_checkpoint" -eq 1 ]; then
  grep -qx "resume $third" "$tmp/again" || fail "$third was not resumed"
  grep -qx "run $third" "$tmp/again" && fail "$third started again despite its checkpoint"
fi
nruns=$(wc -l <"$out/runs.txt")
[ "$nruns" -eq 4 ] || fail "$nruns runs in the sweep (want 4)"
while read -r name _; do
  finished "$name" || fail "run $name did not finish"
  n=$(grep -c "^run $name\$" "$log")
  most=1                    # the third, stopped before a checkpoint: started twice
  [ "$name" = "$third" ] && [ "$had_checkpoint" -eq 0 ] && most=2
  [ "$n" -ge 1 ] && [ "$n" -le "$most" ] || fail "run $name started $n times"
done <"$out/runs.txt"
[ "$(grep -c ',' "$out/hstop.csv")" -eq 5 ] || fail "hstop.csv: $(cat "$out/hstop.csv")"
grep -q failed "$out/hstop.csv" && fail "hstop.csv: $(cat "$out/hstop.csv")"

# The sweep alone killed outright (SIGKILL of its shell, as `kill -9` of the
# sweep's pid does; GNU parallel and its job live on): the running run is
# stopped with a checkpoint within seconds (scripts/run-once watches the
# sweep) and no other run starts; the sweep started again resumes it.
out=$tmp/killed
: >"$log"
setsid sh -c "exec env GRANMPM='$tmp/granmpm' '$srcdir/scripts/sweep-hstop' --out '$out' \
  --input '$srcdir/inputs/ngf-chute-quick.conf' --angles 27 --ratios '2 2.5' \
  --t-end 0.2 --t-min 0.01 --jobs 1 >'$tmp/killed.out' 2>&1" &
group=$!
first=""
while [ -z "$first" ] || [ ! -s "$out/runs/$first/diagnostics.csv" ]; do
  kill -0 "$group" 2>/dev/null || break
  first=$(sed -n '1s/^run //p' "$log")
  sleep 0.01
done
[ -n "$first" ] || fail "killed sweep: it ended before its first run began"
kill -KILL "$group"
waited=0
while [ "$("$GRANMPM" info "$out/runs/$first" --status 2>/dev/null)" = running ] && [ $waited -lt 300 ]; do
  sleep 0.1
  waited=$((waited + 1))
done
[ "$("$GRANMPM" info "$out/runs/$first" --status)" = stopped ] ||
  fail "killed sweep: its run is '$("$GRANMPM" info "$out/runs/$first" --status)' after $waited tenths of a second, not stopped"
[ -f "$out/runs/$first/checkpoint.h5" ] || fail "killed sweep: its run left no checkpoint"
sleep 1.5                     # GNU parallel, orphaned, tries the next job
kill -KILL -"$group" 2>/dev/null
group=""
[ "$(wc -l <"$log")" -eq 1 ] || fail "killed sweep: runs started after the kill: $(cat "$log")"
GRANMPM=$tmp/granmpm "$srcdir/scripts/sweep-hstop" --out "$out" \
  --input "$srcdir/inputs/ngf-chute-quick.conf" --angles 27 --ratios "2 2.5" \
  --t-end 0.2 --t-min 0.01 --jobs 1 >"$tmp/sweep.out" 2>&1 ||
  { fail "killed sweep: started again: exit $?"; cat "$tmp/sweep.out"; }
grep -qx "resume $first" "$log" || fail "killed sweep: $first was not resumed"
finished "$first" || fail "killed sweep: $first did not finish"

echo "log:"; cat "$log"
[ "$fails" -eq 0 ]
