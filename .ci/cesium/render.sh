#!/usr/bin/env bash
# Renders a 3D Tiles tileset with CesiumJS in headless Chromium and checks that tiles loaded
# and trees cover part of the picture. usage: .ci/cesium/render.sh TILESET_DIR OUT.png [QUERY]
# (QUERY: extra page parameters, such as sse=64&range=2)
# Needs Debian's chromium and npm's cesium in .ci/cesium/node_modules (CI installs both).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
world="$(realpath "$1")"; out="$(realpath -m "$2")"; query="${3:-}"
rm -rf "$here/world"; ln -s "$world" "$here/world"
# A static server on loopback only and a Chromium profile, both gone when the script ends.
source "$here/../headless.sh"
headless_serve "$here" 'rm -f "$here/world"'
url="http://127.0.0.1:$port/render.html?tileset=world/tileset.json${query:+&$query}"
flags=("${headless[@]}" --window-size=960,540 --virtual-time-budget=900000)
title=$(chromium "${flags[@]}" --dump-dom "$url" 2>/dev/null | grep -o '<title>[^<]*</title>' || true)
echo "CesiumJS: $title"
chromium "${flags[@]}" --screenshot="$out" "$url" 2>/dev/null
case "$title" in
  *"rendered tiles="*) ;;
  *) echo "CesiumJS did not render the tileset" >&2; exit 1 ;;
esac
green=$(echo "$title" | sed -n 's/.*green=\([0-9.]*\).*/\1/p')
if [[ "$title" == *"tiles=0 "* ]] || ! awk -v g="$green" 'BEGIN { exit !(g >= 0.05) }'; then
  echo "CesiumJS loaded no tiles, or trees cover under 5% of the picture" >&2
  exit 1
fi
