# Shared by the window drivers (drive.sh, editor.sh): a virtual display, and readers of the
# viewer's window title, its status line (they need `window`, the window's id, set).

# virtual_display: starts Xvfb on a free display for this shell and the viewer (its pid in
# `xvfb`), with a runtime folder of its own in the working folder.
virtual_display() {
  local display=":$((100 + RANDOM % 400))"
  Xvfb "$display" -screen 0 800x600x24 -nolisten tcp > xvfb.log 2>&1 &
  xvfb=$!
  export DISPLAY="$display"
  export XDG_RUNTIME_DIR="$PWD/run"
  mkdir -p -m 700 "$XDG_RUNTIME_DIR"
  sleep 1
}

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
