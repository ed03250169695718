# display.sh, sourced by the ParaView tests: sets run to the prefix under
# which pvpython gets a display (empty with $DISPLAY, else xvfb-run), or
# skips the test (77) without either. One X server at a time: two xvfb-run
# -a started together can pick the same display, and one then loses it
# (tests run side by side).
if [ -n "${DISPLAY:-}" ]; then
  run=
elif command -v xvfb-run >/dev/null 2>&1; then
  run="xvfb-run -a"
  command -v flock >/dev/null 2>&1 && run="flock ${TMPDIR:-/tmp}/granmpm-xvfb.lock $run"
else
  echo "SKIP: no display and no xvfb-run"
  exit 77
fi
