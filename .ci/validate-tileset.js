// Checks a 3D Tiles 1.1 tileset against the rules of the specification's JSON schema that
// apply to what sylva writes (tileset: asset.version, geometricError, root; tile:
// boundingVolume with exactly one of box/region/sphere of the right length, non-negative
// geometricError, refine ADD|REPLACE, transform of 16 numbers, content.uri, children), plus
// the spec's structural rules: geometric errors never grow from parent to child, a leaf's is
// the smallest, refine is given at the root, every content file exists and passes the
// Khronos glTF validator (external buffers resolved beside it). Exits non-zero on any problem.
// usage: node .ci/validate-tileset.js DIR/tileset.json [EVERY]
// With EVERY, every content file must exist but only every EVERY-th (and the last) goes
// through the glTF validator: each validation re-reads the world's shared geometry, about 4 s a
// tile on two cores, so a whole model's 129 tiles take minutes.
const fs = require('fs');
const path = require('path');
const validator = require(process.env.GLTF_VALIDATOR || 'gltf-validator');

const file = process.argv[2];
const every = Math.max(1, parseInt(process.argv[3] || '1', 10) || 1);
const dir = path.dirname(file);
const problems = [];
const fail = (where, what) => problems.push(`${where}: ${what}`);
const isNum = (x) => typeof x === 'number' && Number.isFinite(x);

let tileset;
try {
  tileset = JSON.parse(fs.readFileSync(file, 'utf8'));
} catch (e) {
  console.log(`${file}: not JSON: ${e.message}`);
  process.exit(1);
}
if (!tileset.asset || tileset.asset.version !== '1.1') fail('asset', 'version must be "1.1"');
if (!isNum(tileset.geometricError) || tileset.geometricError < 0) fail('tileset', 'geometricError must be a number >= 0');
if (!tileset.root) fail('tileset', 'root is required');

const contents = [];
let tiles = 0;
function visit(tile, where, parentError, parentRefine) {
  tiles += 1;
  const bv = tile.boundingVolume;
  if (!bv) fail(where, 'boundingVolume is required');
  else {
    const kinds = ['box', 'region', 'sphere'].filter((k) => bv[k] !== undefined);
    const lengths = { box: 12, region: 6, sphere: 4 };
    if (kinds.length !== 1) fail(where, 'boundingVolume needs exactly one of box, region, sphere');
    for (const k of kinds) {
      if (!Array.isArray(bv[k]) || bv[k].length !== lengths[k] || !bv[k].every(isNum)) fail(where, `${k} must be ${lengths[k]} numbers`);
    }
  }
  if (!isNum(tile.geometricError) || tile.geometricError < 0) fail(where, 'geometricError must be a number >= 0');
  if (parentError !== undefined && tile.geometricError > parentError) fail(where, `geometricError ${tile.geometricError} exceeds its parent's ${parentError}`);
  if (tile.refine !== undefined && !['ADD', 'REPLACE'].includes(tile.refine)) fail(where, 'refine must be ADD or REPLACE');
  const refine = tile.refine || parentRefine;
  if (!refine) fail(where, 'refine must be given at the root');
  if (tile.transform !== undefined && (!Array.isArray(tile.transform) || tile.transform.length !== 16 || !tile.transform.every(isNum))) fail(where, 'transform must be 16 numbers');
  if (tile.content !== undefined) {
    if (typeof tile.content.uri !== 'string') fail(where, 'content.uri is required');
    else contents.push([where, tile.content.uri]);
  }
  const children = tile.children || [];
  if (!Array.isArray(children)) fail(where, 'children must be an array');
  if (children.length === 0 && tile.geometricError !== 0) fail(where, 'a leaf tile should have geometricError 0');
  children.forEach((c, i) => visit(c, `${where}.children[${i}]`, tile.geometricError, refine));
}
if (tileset.root) visit(tileset.root, 'root', tileset.geometricError, undefined);

(async () => {
  let glb = 0;
  for (const [k, [where, uri]] of contents.entries()) {
    const p = path.resolve(dir, decodeURIComponent(uri));
    if (!fs.existsSync(p)) { fail(where, `content ${uri} does not exist`); continue; }
    if (k % every !== 0 && k !== contents.length - 1) continue;
    const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(p)), {
      uri: path.basename(p),
      externalResourceFunction: (u) =>
        fs.promises.readFile(path.resolve(path.dirname(p), decodeURIComponent(u))).then((b) => new Uint8Array(b)),
    });
    glb += 1;
    if (report.issues.numErrors > 0 || report.issues.numWarnings > 0) {
      const first = report.issues.messages.find((m) => m.severity <= 1);
      fail(where, `${uri}: ${report.issues.numErrors} errors, ${report.issues.numWarnings} warnings (${first && first.code})`);
    }
  }
  console.log(`${file}: ${tiles} tiles, ${glb} contents validated, ${problems.length} problems`);
  problems.slice(0, 20).forEach((p) => console.log(`  ${p}`));
  process.exit(problems.length === 0 ? 0 : 1);
})();
