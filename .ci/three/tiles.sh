#!/usr/bin/env bash
# Renders a sylva 3D Tiles world with three.js and 3d-tiles-renderer in headless Chromium and
# checks that fine tiles (branches) were drawn near the camera and coarse ones (impostor
# cards) beyond. usage: .ci/three/tiles.sh TILESET_DIR OUT.png [EYE [QUERY]]
# EYE is x,y,z,tx,ty,tz in the world's metres (y up); QUERY more page parameters (sse=N).
# Needs Debian's chromium and npm's three and 3d-tiles-renderer in .ci/three/node_modules.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
world="$(realpath "$1")"; out="$(realpath -m "$2")"; eye="${3:-}"; query="${4:-}"
rm -rf "$here/world"; ln -s "$world" "$here/world"
# A static server on loopback only and a Chromium profile, both gone when the script ends.
source "$here/../headless.sh"
headless_serve "$here" 'rm -f "$here/world"'
url="http://127.0.0.1:$port/tiles.html?tileset=world/tileset.json${eye:+&eye=$eye}${query:+&$query}"
flags=("${headless[@]}" --disable-gpu --window-size=960,540 --virtual-time-budget=900000)
page="$(mktemp)"
chromium "${flags[@]}" --dump-dom "$url" 2>/dev/null > "$page" || true
title=$(grep -o '<title>[^<]*</title>' "$page" || true)
echo "three.js (3d-tiles-renderer): $title"
# The page carries its picture as a PNG data URL.
sed -n 's/.*<pre id="picture">data:image\/png;base64,\([^<]*\)<\/pre>.*/\1/p' "$page" | base64 -d > "$out" || true
rm -f "$page"
case "$title" in
  *"rendered tiles"*) ;;
  *) echo "three.js did not render the tileset" >&2; exit 1 ;;
esac
if [[ "$title" == *"fine=0 "* || "$title" == *"coarse=0 "* ]]; then
  echo "three.js drew no fine tiles near the camera or no coarse tiles beyond" >&2
  exit 1
fi
test -s "$out" || { echo "the page gave no picture" >&2; exit 1; }
