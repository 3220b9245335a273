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
# A static server on loopback only and a Chromium profile, both gone when the script ends.
source "$here/../headless.sh"
headless_serve "$here" 'rm -f "$here/forest.glb"'
url="http://127.0.0.1:$port/render.html?file=forest.glb${eye:+&eye=$eye}${query:+&$query}"
flags=("${headless[@]}" --disable-gpu --window-size=960,540 --virtual-time-budget=120000)
# One try: a page that crashes or quits before rendering is a failure, not a retry.
title=$(chromium "${flags[@]}" --dump-dom "$url" 2>/dev/null | grep -o '<title>rendered[^<]*</title>' || true)
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
