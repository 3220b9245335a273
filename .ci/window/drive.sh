#!/usr/bin/env bash
# Drives the windowed viewer on a virtual X display (Xvfb) with xdotool, the way a user does:
# keys, mouse buttons and cursor moves through winit's event loop, which no headless test
# reaches. Paints a stroke (P, E, a left-button drag), saves the masks (Ctrl+S), undoes and
# redoes it (Ctrl+Z, Ctrl+Y), then starts the guided walk (G); then opens a forest over time
# and moves it on with Y and Shift+Y. The window's title is the
# viewer's status line; the script reads it to follow what the viewer did.
# usage: .ci/window/drive.sh VIEWER FOREST_EXAMPLE WORKDIR
# Needs Debian's xvfb and xdotool, and a Vulkan or GL driver (Mesa's lavapipe will do).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
viewer="$(realpath "$1")"; sylva="$(realpath "$2")"; work="$3"
mkdir -p "$work"; cd "$work"; rm -rf paint_masks
source "$here/common.sh"
virtual_display
"$viewer" --area 150 > viewer.out 2> viewer.err &
viewer_pid=$!
trap 'kill $viewer_pid $xvfb 2>/dev/null || true' EXIT

# find_window ERRFILE: the viewer's window, waited for up to four minutes.
find_window() {
  local found=""
  for _ in $(seq 1 480); do
    found=$(xdotool search --name '^sylva' 2>/dev/null | head -1 || true)
    [ -n "$found" ] && break
    sleep 0.5
  done
  [ -n "$found" ] || { echo "the viewer opened no window" >&2; cat "$1" >&2; exit 1; }
  echo "$found"
}
window=$(find_window viewer.err)
trees() { title | sed -n 's/.*; \([0-9]*\) trees in .*/\1/p'; }
settled() { shows " trees in 4 cells" && ! shows "coming"; }
trees_are() { [ "$(trees)" = "$1" ]; }
fewer_than() { local n; n=$(trees); [ -n "$n" ] && [ "$n" -lt "$1" ]; }

wait_until settled
before=$(trees)
echo "window: $before trees streamed"
xdotool windowfocus --sync "$window"
xdotool key p
wait_until shows "painting: add oak"
xdotool key e
wait_until shows "painting: erase"
# A stroke across the ground in front of the camera.
xdotool mousemove --window "$window" 300 420 mousedown 1
for x in 340 380 420 460 500; do
  xdotool mousemove --window "$window" "$x" 430
  sleep 0.2
done
xdotool mouseup 1
wait_until shows "undo 1, redo 0"
wait_until fewer_than "$before"
after=$(trees)
echo "window: the stroke erased $((before - after)) trees"
xdotool key ctrl+s
masks() { [ "$(find paint_masks -name '*.png' 2>/dev/null | wc -l)" -eq 5 ]; }
wait_until masks
xdotool key ctrl+z
wait_until shows "undo 0, redo 1"
wait_until trees_are "$before"
xdotool key ctrl+y
wait_until shows "undo 1, redo 0"
wait_until trees_are "$after"
echo "window: undo restored $before trees, redo erased them again"
xdotool key p
xdotool key g
wait_until shows "guided walk"
echo "window: the guided walk started"
# The masks the window saved grow the same forest in `sylva forest`.
exported=$("$sylva" forest --area 150 --paint paint_masks --out painted.glb --stats 2>/dev/null \
  | sed -n 's/^{"trees":\([0-9]*\),.*/\1/p')
if [ "$exported" != "$after" ]; then
  echo "the window showed $after trees; its masks grow $exported" >&2; exit 1
fi
echo "window: its saved masks grow the same $after trees in sylva forest"

# A forest over time: Y moves it on ten years, Shift+Y one, and the title follows.
kill "$viewer_pid" 2>/dev/null || true
wait "$viewer_pid" 2>/dev/null || true
"$viewer" --area 150 --no-floor --year 20 > years.out 2> years.err &
viewer_pid=$!
trap 'kill $viewer_pid $xvfb 2>/dev/null || true' EXIT
window=$(find_window years.err)
wait_until shows "year 20"
xdotool windowfocus --sync "$window"
xdotool key y
wait_until shows "year 30"
xdotool key shift+y
wait_until shows "year 31"
echo "window: Y moved the forest over time from year 20 to 30, Shift+Y to 31"
