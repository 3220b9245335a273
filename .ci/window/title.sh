# Shared by the window drivers (drive.sh, editor.sh): the viewer's window title is its status
# line; these read it and wait on it. Source after setting `window` (the window's id).
title() { xdotool getwindowname "$window"; }
fail() { echo "$1; the title reads: $(title)" >&2; cat viewer.err >&2; exit 1; }
# wait_until COMMAND...: polls until the command succeeds, four minutes at most (a frame
# takes about a second on a software driver, and the title shows the frame before).
wait_until() {
  for _ in $(seq 1 480); do
    if "$@"; then return 0; fi
    sleep 0.5
  done
  fail "timed out waiting for: $*"
}
shows() { [[ "$(title)" == *"$1"* ]]; }
