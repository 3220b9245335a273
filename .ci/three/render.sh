#!/usr/bin/env bash
# Renders a GLB with three.js in headless Chromium and checks that three.js loaded its
# instanced meshes and leaf textures. usage: .ci/three/render.sh FILE.glb OUT.png [EYE [QUERY]]
# EYE is x,y,z,tx,ty,tz (camera and target); QUERY more of the page's parameters, such as
# roles=1 (flat colours by material role, with the coverage of each in the title).
# Needs Debian's chromium and npm's three in .ci/three/node_modules (CI installs both).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
glb="$(realpath "$1")"; out="$(realpath -m "$2")"; eye="${3:-}"; query="${4:-}"
cp "$glb" "$here/forest.glb"
port=$((20000 + RANDOM % 10000))
# A static server on loopback only, stopped when the script ends.
node "$here/../serve.js" "$here" "$port" &
server=$!
# Chromium's profile for this run, removed with the rest on exit.
profile="$(mktemp -d)"
trap 'kill $server 2>/dev/null; rm -f "$here/forest.glb"; rm -rf "$profile"' EXIT
sleep 1
url="http://127.0.0.1:$port/render.html?file=forest.glb${eye:+&eye=$eye}${query:+&$query}"
flags=(--headless --no-sandbox --disable-gpu --use-angle=swiftshader --enable-unsafe-swiftshader
  --disable-quic --no-first-run --disable-background-networking --disable-component-update
  --disable-sync --user-data-dir="$profile" --window-size=960,540
  --virtual-time-budget=120000)
title=$(chromium "${flags[@]}" --dump-dom "$url" 2>/dev/null | grep -o '<title>[^<]*</title>' || true)
echo "three.js: $title"
chromium "${flags[@]}" --screenshot="$out" "$url" 2>/dev/null
case "$title" in
  *"rendered instanced="*) ;;
  *) echo "three.js did not render the file" >&2; exit 1 ;;
esac
if [[ "$title" == *"instanced=0 "* || "$title" == *"textured=0 "* || "$title" == *"masked=0"* ]]; then
  echo "three.js found no instanced meshes or no textured, alpha-masked leaves" >&2
  exit 1
fi
