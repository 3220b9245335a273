#!/usr/bin/env bash
# Renders each default species beside the nearest ez-tree preset in three.js (headless
# Chromium) and measures both silhouettes; writes OUT_DIR/<species>.png (side by side, eye
# level) and OUT_DIR/measures.json, and prints a table.
# usage: tools/compare/compare.sh OUT_DIR [SYLVA_BINARY [SPECIES_DIR [SPECIES...]]]
# SPECIES_DIR holds <species>.species files to draw instead of the bundled ones (for tuning a
# species); SPECIES limits the run to those named.
# Needs Debian's chromium and node; installs npm's three and @dgreenheck/ez-tree beside this
# script on first use.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
out="$(realpath -m "$1")"; sylva="$(realpath "${2:-target/release/sylva}")"
species_dir="${3:+$(realpath "$3")}"; only=("${@:4}")
mkdir -p "$out"
if [ ! -d "$here/node_modules/@dgreenheck/ez-tree" ]; then
  (cd "$here" && npm install --no-save --no-audit --no-fund --silent three@0.170.0 @dgreenheck/ez-tree@1.1.0)
fi
# sylva species and the ez-tree preset each stands beside.
pairs=("oak:Oak Large" "birch:Aspen Large" "pine:Pine Large" "hazel:Bush 1" "spruce:Pine Medium")
# A static server on loopback only and a Chromium profile, both gone when the script ends.
source "$here/../../.ci/headless.sh"
headless_serve "$here" 'rm -f "$here"/tree_*.glb'
flags=("${headless[@]}" --disable-gpu --virtual-time-budget=120000)
title() {  # the page's title for the query $1, trying three times (headless Chromium now and then
           # quits before the page has rendered)
  local t=""
  for _ in 1 2 3; do
    t=$(chromium "${flags[@]}" --window-size=1280,720 --dump-dom "http://127.0.0.1:$port/compare.html?$1" 2>/dev/null \
      | grep -o '<title>measured [^<]*</title>' | sed 's/<[^>]*>//g; s/^measured //' || true)
    [ -n "$t" ] && break
  done
  echo "$t"
}
echo "{" > "$out/measures.json"
first=1
for pair in "${pairs[@]}"; do
  species="${pair%%:*}"; preset="${pair#*:}"; ez="${preset// /%20}"
  if [ ${#only[@]} -gt 0 ] && [[ ! " ${only[*]} " == *" $species "* ]]; then continue; fi
  source="$species"; [ -z "$species_dir" ] || source="$species_dir/$species.species"
  "$sylva" tree --species "$source" --seed 1 --out "$here/tree_$species.glb" --quiet
  query="sylva=tree_$species.glb&ez=$ez"
  chromium "${flags[@]}" --window-size=1280,720 --screenshot="$out/$species.png" \
    "http://127.0.0.1:$port/compare.html?$query&view=side" 2>/dev/null
  ours=$(title "$query&view=silhouette-sylva")
  theirs=$(title "$query&view=silhouette-ez")
  if [ -z "$ours" ] || [ -z "$theirs" ]; then
    echo "three.js did not render $species beside $preset (sylva: '$ours', ez-tree: '$theirs')" >&2
    exit 1
  fi
  [ $first = 1 ] || echo "," >> "$out/measures.json"
  first=0
  printf '  "%s": {"sylva": %s, "ez_tree": {"preset": "%s", "measures": %s}}' "$species" "$ours" "$preset" "$theirs" >> "$out/measures.json"
  echo "$species: sylva $ours"
  echo "$(printf '%*s' ${#species} '') $preset: $theirs"
done
echo "" >> "$out/measures.json"
echo "}" >> "$out/measures.json"
