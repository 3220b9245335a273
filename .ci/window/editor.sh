#!/usr/bin/env bash
# Drives the viewer's species editor (--editor) on a virtual X display (Xvfb) with xdotool,
# the way a user does, reading the window's title (the editor's status) after each step:
# types a broken production into the oak's grammar and sees its problem with its line, takes
# it back, moves the generations slider, saves the project and reads it back with
# `sylva forest`'s species reader (the headless panel), moves the slider again and kills the
# viewer (SIGKILL) once the edit is autosaved; the next start offers the autosave, and
# Restore brings the edit back.
# usage: .ci/window/editor.sh VIEWER WORKDIR
# Needs Debian's xvfb and xdotool, and a Vulkan or GL driver (Mesa's lavapipe will do).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
viewer="$(realpath "$1")"; work="$2"
mkdir -p "$work"; cd "$work"; rm -rf proj
source "$here/common.sh"
virtual_display
viewer_pid=""
trap 'kill -9 $viewer_pid 2>/dev/null || true; kill $xvfb 2>/dev/null || true' EXIT

start() {
  "$viewer" --area 150 --editor --project proj --autosave-seconds 1 > viewer.out 2> viewer.err &
  viewer_pid=$!
  window=""
  for _ in $(seq 1 480); do
    window=$(xdotool search --pid "$viewer_pid" --name '^sylva' 2>/dev/null | head -1 || true)
    [ -n "$window" ] && break
    sleep 0.5
  done
  [ -n "$window" ] || { echo "the viewer opened no window" >&2; cat viewer.err >&2; exit 1; }
  xdotool windowfocus --sync "$window"
}
triangles() { title | sed -n 's/.*editing oak: \([0-9]*\) triangles.*/\1/p'; }
other_than() { local n; n=$(triangles); [ -n "$n" ] && [ "$n" != "$1" ]; }
# Where the panel's controls stand (points from the window's top left; the panel's layout is
# fixed, see viewer/src/editor/panel.rs).
grammar_box=(200 200); generations_slider_y=439; save_button=(138 36); restore_button=(38 77)
# tap X Y: a click at (X, Y) once the panel has seen the cursor there, as a button takes it.
tap() {
  xdotool mousemove --window "$window" "$1" "$2"
  sleep 1.5
  xdotool click 1
}
# press X Y: the left button held over a frame at (X, Y), as a slider needs to take it
# (a button takes a press that long as no click).
press() {
  xdotool mousemove --window "$window" "$1" "$2"
  sleep 1.5
  xdotool mousedown 1
  sleep 2.5
  xdotool mouseup 1
  # The release gets a frame of its own: a move in the same frame would drag on.
  sleep 2.5
}

start
wait_until shows "editing oak: "
first=$(triangles)
echo "editor: the oak previews at $first triangles"
# A frame takes a second or more on a software driver: the click must reach the panel (a
# frame) before the keys do.
xdotool mousemove --window "$window" "${grammar_box[@]}" click 1
sleep 3
xdotool key ctrl+End
sleep 2
xdotool type --delay 40 $'\nF -> FF(1,'
wait_until shows "editing oak: grammar, line"
echo "editor: $(title | sed -n 's/.*editing oak: \(grammar, line [0-9]*, column [0-9]*\).*/\1/p')"
# The typed line goes, and the line break before it.
xdotool key shift+Home
sleep 2
xdotool key BackSpace BackSpace
wait_until shows "editing oak: $first triangles"
# The oak's generations run from 5 (past its 4 seedling generations) to 12 over the slider's
# 100 points from x = 8: x = 23 is 6 generations, x = 37 is 7.
press 23 "$generations_slider_y"
wait_until other_than "$first"
saved=$(triangles)
echo "editor: the slider moved; $saved triangles"
tap "${save_button[@]}"
wait_until test -f proj/oak.species
grep -q "^generations: " proj/oak.species || fail "the saved species has no generations"
press 37 "$generations_slider_y"
wait_until other_than "$saved"
unsaved=$(triangles)
echo "editor: moved again, not saved; $unsaved triangles"
autosaved() { [ -f proj/.autosave/unsaved ] && ! cmp -s proj/.autosave/oak.species proj/oak.species; }
wait_until autosaved
sleep 1.5
kill -9 "$viewer_pid"; wait "$viewer_pid" 2>/dev/null || true
echo "editor: killed (SIGKILL)"
"$viewer" --editor-screenshot panel.png --project proj | tee headless.out
grep -q "autosave of 5 species to restore" headless.out || { echo "no autosave offered" >&2; exit 1; }
start
wait_until shows "an autosave to restore"
# The offer stands under the heading; its Restore button first.
tap "${restore_button[@]}"
wait_until shows "editing oak: $unsaved triangles"
shows "an autosave to restore" && fail "the offer stayed after Restore"
echo "editor: restored the autosave; $unsaved triangles again"
