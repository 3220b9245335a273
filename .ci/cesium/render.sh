#!/usr/bin/env bash
# Renders a 3D Tiles tileset with CesiumJS in headless Chromium and checks that tiles loaded
# and trees cover part of the picture. usage: .ci/cesium/render.sh TILESET_DIR OUT.png [QUERY]
# (QUERY: extra page parameters, such as sse=64&range=2)
# Needs Debian's chromium and npm's cesium in .ci/cesium/node_modules (CI installs both).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
world="$(realpath "$1")"; out="$(realpath -m "$2")"; query="${3:-}"
rm -rf "$here/world"; ln -s "$world" "$here/world"
port=$((20000 + RANDOM % 10000))
# A static server on loopback only, stopped when the script ends.
node "$here/../serve.js" "$here" "$port" &
server=$!
# Chromium's profile for this run, removed with the rest on exit.
profile="$(mktemp -d)"
trap 'kill $server 2>/dev/null; rm -f "$here/world"; rm -rf "$profile"' EXIT
sleep 1
url="http://127.0.0.1:$port/render.html?tileset=world/tileset.json${query:+&$query}"
flags=(--headless --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader
  --disable-quic --no-first-run --disable-background-networking --disable-component-update
  --disable-sync --user-data-dir="$profile" --window-size=960,540
  --virtual-time-budget=900000)
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
