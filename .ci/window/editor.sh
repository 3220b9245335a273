#!/usr/bin/env bash
# Drives the viewer's species editor (--editor) on a virtual X display (Xvfb) with xdotool,
# the way a user does, reading the window's title (the editor's status) after each step:
# types a broken production into the oak's grammar and sees its problem with its line, takes
# it back, moves the generations slider, saves the project and reads it back with
# `sylva forest`'s species reader (the headless panel), moves the slider again and kills the
# viewer (SIGKILL) once the edit is autosaved; the next start offers the autosave, and
# Restore brings the edit back. Then the forest tab: the terrain's roughness moved, the world
# is built again while frames go on, swapped in. Then the tools tab: painting started from
# its button, the eraser chosen, a stroke; Ctrl+Z and Ctrl+Y undo and redo it through the
# editor's one history; saved with the project, whose masks `sylva forest --project` grows.
# usage: .ci/window/editor.sh VIEWER SYLVA WORKDIR
# Needs Debian's xvfb and xdotool, and a Vulkan or GL driver (Mesa's lavapipe will do).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
viewer="$(realpath "$1")"; sylva="$(realpath "$2")"; work="$3"
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
grammar_box=(200 200); generations_slider_y=443; save_button=(138 40); restore_button=(38 81)
forest_tab=(125 14); roughness_slider_y=159; tools_tab=(233 14); paint_button=(60 81)
erase_radio=(200 128)
# frames N: waits until N more frames have been drawn (the title changes every frame: it
# carries the frame time), however slow frames are (a rebuild shares the cores).
frames() {
  local k before
  for k in $(seq 1 "$1"); do
    before=$(title)
    wait_until changed "$before"
  done
}
changed() { [ "$(title)" != "$1" ]; }
# tap X Y: a click at (X, Y) once the panel has seen the cursor there, as a button takes it.
tap() {
  xdotool mousemove --window "$window" "$1" "$2"
  frames 2
  xdotool click 1
  # What the click changed is laid out in the frames after it.
  frames 2
}
# press X Y: the left button held over frames at (X, Y), as a slider needs to take it (a
# button takes a press that long as no click).
press() {
  xdotool mousemove --window "$window" "$1" "$2"
  frames 2
  xdotool mousedown 1
  frames 2
  xdotool mouseup 1
  # The release gets frames of its own: a move in the same frame would drag on.
  frames 2
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
# 190 points from x = 8: x = 35 is 6 generations, x = 62 is 7.
press 35 "$generations_slider_y"
wait_until other_than "$first"
saved=$(triangles)
echo "editor: the slider moved; $saved triangles"
tap "${save_button[@]}"
wait_until test -f proj/oak.species
grep -q "^generations: " proj/oak.species || fail "the saved species has no generations"
press 62 "$generations_slider_y"
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

# The species restored, the forest follows them: built again in the background.
wait_until shows "(build 1,"
# The forest tab: roughness runs from 0 to 1 over the slider's 190 points from x = 8, so
# x = 65 is 0.3. The world is built again in the background, frames going on meanwhile,
# then swapped in.
tap "${forest_tab[@]}"
press 65 "$roughness_slider_y"
wait_until shows "(build 2,"
built=$(title | sed -n 's/.*\(forest built in [^;]*\).*/\1/p')
echo "editor: the terrain's roughness moved; $built"
[[ "$built" =~ \ ([1-9][0-9]*)\ frames\ drawn ]] || fail "no frames were drawn while the forest was built"
# The tools tab: the painting tool from its button, the eraser, a stroke across the ground.
tap "${tools_tab[@]}"
tap "${paint_button[@]}"
wait_until shows "painting: add oak"
tap "${erase_radio[@]}"
wait_until shows "painting: erase"
xdotool mousemove --window "$window" 500 420
frames 2
xdotool mousedown 1
frames 2
for x in 540 580 620 660 700; do
  xdotool mousemove --window "$window" "$x" 430
  frames 1
done
xdotool mouseup 1
wait_until shows "undo 1, redo 0"
echo "editor: painted a stroke from the tools tab"
# Undo and redo go through the editor's history, in turn with its edits.
xdotool key ctrl+z
wait_until shows "undo 0, redo 1"
xdotool key ctrl+y
wait_until shows "undo 1, redo 0"
echo "editor: Ctrl+Z and Ctrl+Y undid and redid the stroke"
tap "${save_button[@]}"
rough() { grep -q '"roughness": 0\.[0-6]' proj/world.json 2>/dev/null; }
wait_until rough
masks() { [ "$(find proj/masks -name '*.png' 2>/dev/null | wc -l)" -eq 5 ]; }
wait_until masks
"$sylva" forest --project proj --out forest.glb --quiet > forest.out 2>&1 || { cat forest.out >&2; fail "sylva forest did not take the project"; }
[ -s forest.glb ] || fail "sylva forest wrote nothing"
echo "editor: saved with its masks; sylva forest --project made its forest ($(stat -c %s forest.glb) bytes)"
