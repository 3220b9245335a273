#!/usr/bin/env bash
# The browser as the Garden of Eden had it: starts `sylva serve` on a loopback port, posts a
# world, and has headless Chromium open the server's own page, which streams the world's tiles
# (generated on first request) with three.js and 3d-tiles-renderer. Checks that fine tiles
# (branches) drew near the camera and coarse ones (impostor cards) beyond; writes the frame,
# and one tree of the tree API as serve_tree.glb beside it.
# usage: .ci/serve/browser.sh SYLVA OUT.png CACHE_DIR [WORLD_JSON [EYE [QUERY]]]
# EYE is x,y,z,tx,ty,tz in the world's metres (y up); QUERY more page parameters (sse=N).
# Needs Debian's chromium and npm's three and 3d-tiles-renderer in .ci/three/node_modules.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
sylva="$(realpath "$1")"; out="$(realpath -m "$2")"; cache="$(realpath -m "$3")"
world="${4:-{\"area\": 1000, \"tile_size\": 100, \"group\": 2\}}"
eye="${5:-20,40,20,500,0,500}"; query="${6:-}"
log="$(mktemp)"; profile="$(mktemp -d)"; page="$(mktemp)"
"$sylva" serve --port 0 --cache "$cache" --web-modules "$here/../three/node_modules" > "$log" &
server=$!
trap 'kill $server 2>/dev/null; rm -rf "$profile" "$log" "$page"' EXIT
for _ in $(seq 100); do grep -q 'listening on' "$log" && break; sleep 0.1; done
base=$(grep -o 'http://[0-9.:]*' "$log" | head -1)
[ -n "$base" ] || { echo "sylva serve did not start" >&2; exit 1; }
id=$(curl -sf -X POST "$base/worlds" -d "$world" | node -e 'let s="";process.stdin.on("data",d=>s+=d).on("end",()=>console.log(JSON.parse(s).id))')
echo "sylva serve at $base, world $id"
flags=(--headless --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader --disable-gpu
  --disable-quic --no-first-run --disable-background-networking --disable-component-update
  --disable-sync --user-data-dir="$profile" --window-size=960,540 --virtual-time-budget=900000)
chromium "${flags[@]}" --dump-dom "$base/?world=$id&check=1&eye=$eye${query:+&$query}" 2>/dev/null > "$page" || true
title=$(grep -o '<title>[^<]*</title>' "$page" || true)
echo "the page: $title"
sed -n 's/.*<pre id="picture">data:image\/png;base64,\([^<]*\)<\/pre>.*/\1/p' "$page" | base64 -d > "$out" || true
case "$title" in
  *"rendered world="*) ;;
  *) echo "the page did not render the served world" >&2; exit 1 ;;
esac
if [[ "$title" == *"fine=0 "* || "$title" == *"coarse=0 "* ]]; then
  echo "the page drew no fine tiles near the camera or no coarse tiles beyond" >&2
  exit 1
fi
test -s "$out" || { echo "the page gave no picture" >&2; exit 1; }
# One tree from the tree API, beside the picture, for the validator.
curl -sf -o "$(dirname "$out")/serve_tree.glb" "$base/trees/oak.glb?seed=3&age=40"
# What the server made for the page: generated on request, kept in the cache.
echo "tiles generated into the cache: $(ls "$cache"/worlds/*/"$id"/tiles | wc -l)"
curl -sf "$base/status"; echo
