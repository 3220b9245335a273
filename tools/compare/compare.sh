#!/usr/bin/env bash
# Renders each species of tools/compare/references.json beside the ez-tree preset named there,
# in three.js (headless Chromium), measures both silhouettes and holds ours against the
# reference ranges. Writes, in OUT_DIR:
#   <species>.png        side by side with the ez-tree preset, eye level
#   <species>-stand.png  seven copies in a loose stand, from 1.7 m eye height
#   <species>-10m.png    the tree alone at its own size from 10 m at eye level
#   <species>-seasons.png the tree in spring, summer, autumn and winter, left to right
#   measures.json        both trees' measures and, per reference range, whether ours is inside
#   shapes.md            a table of the crown-shape measures against the ranges, and the sources
# and prints a table and "N of M species inside every range". A range missed is evidence, not a
# failure: the script still exits 0. Species the sylva binary does not know yet are skipped.
# usage: tools/compare/compare.sh OUT_DIR [SYLVA_BINARY [SPECIES_DIR [SPECIES...]]]
# SPECIES_DIR holds <species>.species files to draw instead of the bundled ones (for tuning a
# species); SPECIES limits the run to those named.
# Needs Debian's chromium and node; installs npm's three and @dgreenheck/ez-tree beside this
# script on first use.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
out="$(realpath -m "$1")"; sylva="$(realpath "${2:-target/release/sylva}")"
species_dir="${3:+$(realpath "$3")}"; only=("${@:4}")
references="$here/references.json"
mkdir -p "$out"
if [ ! -d "$here/node_modules/@dgreenheck/ez-tree" ]; then
  (cd "$here" && npm install --no-save --no-audit --no-fund --silent three@0.170.0 @dgreenheck/ez-tree@1.1.0)
fi
# sylva species and the ez-tree preset each stands beside, in the references' order.
mapfile -t pairs < <(node -e '
  const refs = JSON.parse(require("fs").readFileSync(process.argv[1], "utf8"));
  for (const [name, s] of Object.entries(refs.species)) console.log(name + ":" + s.ez_tree);
' "$references")
# Each species' measures, one JSON file apiece, until the report gathers them.
work="$(mktemp -d)"
# A static server on loopback only and a Chromium profile, both gone when the script ends.
source "$here/../../.ci/headless.sh"
headless_serve "$here" 'rm -f "$here"/tree_*.glb; rm -rf "$work"'
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
shot() {  # a 1280x720 screenshot of the query $1 into the file $2
  chromium "${flags[@]}" --window-size=1280,720 --screenshot="$2" \
    "http://127.0.0.1:$port/compare.html?$1" 2>/dev/null
}
skipped=()
for pair in "${pairs[@]}"; do
  species="${pair%%:*}"; preset="${pair#*:}"; ez="${preset// /%20}"
  if [ ${#only[@]} -gt 0 ] && [[ ! " ${only[*]} " == *" $species "* ]]; then continue; fi
  source="$species"; [ -z "$species_dir" ] || source="$species_dir/$species.species"
  if ! "$sylva" tree --species "$source" --seed 1 --out "$here/tree_$species.glb" --quiet 2>"$work/error"; then
    echo "$species: skipped, sylva does not draw it yet ($(head -n 1 "$work/error"))" >&2
    skipped+=("$species")
    continue
  fi
  query="sylva=tree_$species.glb&ez=$ez"
  shot "$query&view=side" "$out/$species.png"
  shot "sylva=tree_$species.glb&view=stand" "$out/$species-stand.png"
  shot "sylva=tree_$species.glb&view=near" "$out/$species-10m.png"
  # The season strip: spring, summer, autumn and winter, left to right.
  strip=()
  for season in spring summer autumn winter; do
    "$sylva" tree --species "$source" --season "$season" --seed 1 --out "$here/tree_${species}_$season.glb" --quiet
    strip+=("tree_${species}_$season.glb")
  done
  shot "view=seasons&seasons=$(IFS=,; echo "${strip[*]}")" "$out/$species-seasons.png"
  ours=$(title "$query&view=silhouette-sylva")
  theirs=$(title "$query&view=silhouette-ez")
  if [ -z "$ours" ] || [ -z "$theirs" ]; then
    echo "three.js did not render $species beside $preset (sylva: '$ours', ez-tree: '$theirs')" >&2
    exit 1
  fi
  printf '{"sylva": %s, "ez_tree": {"preset": "%s", "measures": %s}}\n' "$ours" "$preset" "$theirs" > "$work/$species.json"
  echo "$species: sylva $ours"
  echo "$(printf '%*s' ${#species} '') $preset: $theirs"
done
# measures.json and shapes.md: each measure against its reference range.
node -e '
  const fs = require("fs"), path = require("path");
  const [references, work, out, skippedList] = process.argv.slice(1);
  const refs = JSON.parse(fs.readFileSync(references, "utf8"));
  const skipped = skippedList ? skippedList.split(" ") : [];
  const measures = {}, rows = [], cited = new Set();
  const columns = ["cone_ratio", "widest_at", "clear_bole", "porosity", "width_over_height"];
  const fmt = (v) => (v === null || v === undefined ? "–" : typeof v === "number" ? String(v) : v);
  let inside = 0, drawn = 0;
  for (const [name, ref] of Object.entries(refs.species)) {
    const file = path.join(work, name + ".json");
    if (!fs.existsSync(file)) continue;
    const result = JSON.parse(fs.readFileSync(file, "utf8"));
    const ours = result.sylva, checks = {};
    for (const [measure, range] of Object.entries(ref.ranges)) {
      const value = ours[measure];
      const ok = range.expect ? range.expect.includes(value)
        : typeof value === "number" && value >= range.min && value <= range.max;
      checks[measure] = range.expect ? { value, expect: range.expect, inside: ok }
        : { value, min: range.min, max: range.max, inside: ok };
      [].concat(range.source || []).forEach((s) => cited.add(s));
    }
    const every = Object.values(checks).every((c) => c.inside);
    measures[name] = { ...result, reference: checks, inside_every_range: every };
    drawn++; if (every) inside++;
    const cell = (measure) => {
      const c = checks[measure];
      if (!c) return fmt(ours[measure]);
      const range = c.expect ? c.expect.join(" / ") : c.min + "–" + c.max;
      return fmt(c.value) + " (" + range + ")" + (c.inside ? "" : " ✗");
    };
    rows.push("| " + name + " | " + cell("crown_shape") + " | " + columns.map(cell).join(" | ") + " |");
  }
  fs.writeFileSync(path.join(out, "measures.json"), JSON.stringify(measures, null, 2) + "\n");
  const summary = inside + " of " + drawn + " species inside every range";
  const lines = [
    "# Crown shapes against the references",
    "",
    "Each cell: the sylva tree (seed 1) measured on its silhouette, then the reference range in",
    "brackets; ✗ marks a value outside it. Shapes: ours (the accepted classes). The measures and",
    "the shape rules are explained in tools/compare/compare.html (crownShape); the ranges and",
    "their sources are in tools/compare/references.json.",
    "",
    "| species | crown_shape | cone_ratio | widest_at | clear_bole | porosity | width_over_height |",
    "|---|---|---|---|---|---|---|",
    ...rows,
    "",
    summary + ".",
  ];
  if (skipped.length) lines.push("", "Not drawn (sylva does not know them yet): " + skipped.join(", ") + ".");
  lines.push("", "## Sources", "");
  for (const key of Object.keys(refs.sources)) {
    if (!cited.has(key)) continue;
    const s = refs.sources[key];
    lines.push("- **" + key + "**: " + s.cite + (s.url ? " <" + s.url + ">" : "") + (s.says ? ". " + s.says : ""));
  }
  fs.writeFileSync(path.join(out, "shapes.md"), lines.join("\n") + "\n");
  console.log(summary);
' "$references" "$work" "$out" "${skipped[*]}"
