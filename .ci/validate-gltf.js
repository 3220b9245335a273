// Validates glTF files with the Khronos glTF-Validator and checks the parts of
// EXT_mesh_gpu_instancing it does not: attribute accessor types, float components, equal
// counts and unit quaternions. Exits non-zero on any error.
// usage: node .ci/validate-gltf.js FILE.glb [EXPECTED_PLACEMENTS | none]
// ('none': a file without instancing, such as a grown stand, which must also have no warnings)
const fs = require('fs');
const path = require('path');
const validator = require(process.env.GLTF_VALIDATOR || 'gltf-validator');

async function main() {
  const [file, expected] = process.argv.slice(2);
  const data = new Uint8Array(fs.readFileSync(file));
  const report = await validator.validateBytes(data, {
    uri: path.basename(file),
    maxIssues: 100000,
    // Tiles refer to the world's shared geometry beside them (`../shared.bin`).
    externalResourceFunction: (uri) =>
      fs.promises.readFile(path.resolve(path.dirname(file), decodeURIComponent(uri))).then((b) => new Uint8Array(b)),
  });
  const { numErrors, numWarnings, numInfos, numHints } = report.issues;
  console.log(`${file}: ${numErrors} errors, ${numWarnings} warnings, ${numInfos} infos, ${numHints} hints`);
  for (const m of report.issues.messages.filter((m) => m.severity === 0).slice(0, 20)) {
    console.log(`  error ${m.code} at ${m.pointer}: ${m.message}`);
  }
  const warnings = {};
  for (const m of report.issues.messages.filter((m) => m.severity === 1)) warnings[m.code] = (warnings[m.code] || 0) + 1;
  for (const [code, n] of Object.entries(warnings)) console.log(`  warning ${code} x${n}`);

  // Our own checks of EXT_mesh_gpu_instancing.
  const json = parseGlbJson(data);
  const bin = parseGlbBin(data);
  let problems = 0;
  let placements = 0;
  // A grown stand (expected count 'none') has no instancing; a forest must declare it.
  if (expected === 'none') {
    const instanced = (json.nodes || []).some((n) => n.extensions && n.extensions.EXT_mesh_gpu_instancing);
    console.log(`  ${(json.nodes || []).length} nodes, ${instanced ? 'some' : 'none'} instanced`);
    process.exit(numErrors === 0 && numWarnings === 0 && !instanced ? 0 : 1);
  }
  if (!(json.extensionsUsed || []).includes('EXT_mesh_gpu_instancing')) {
    console.log('  instancing: EXT_mesh_gpu_instancing missing from extensionsUsed');
    problems++;
  }
  const want = { TRANSLATION: 'VEC3', ROTATION: 'VEC4', SCALE: 'VEC3' };
  const inScene = reachable(json, json.scenes[json.scene || 0].nodes);
  for (const [n, node] of (json.nodes || []).entries()) {
    const ext = node.extensions && node.extensions.EXT_mesh_gpu_instancing;
    if (!ext) continue;
    let count = null;
    for (const [attr, type] of Object.entries(want)) {
      const a = json.accessors[ext.attributes[attr]];
      // EXT_mesh_gpu_instancing: floats, or for ROTATION normalized signed bytes or shorts.
      const quantized = attr === 'ROTATION' && a && a.normalized && (a.componentType === 5120 || a.componentType === 5122);
      if (!a || a.type !== type || !(a.componentType === 5126 || quantized)) {
        console.log(`  instancing: node ${n} ${attr} must be a float (or for ROTATION a normalized byte or short) ${type} accessor`);
        problems++;
        continue;
      }
      if (count === null) count = a.count;
      if (a.count !== count) {
        console.log(`  instancing: node ${n} attribute counts differ`);
        problems++;
      }
      if (attr === 'ROTATION') {
        const view = json.bufferViews[a.bufferView];
        const at = bin.byteOffset + (view.byteOffset || 0) + (a.byteOffset || 0);
        // Normalized integers decode as max(c / max, -1) (glTF 2.0, 3.11).
        const [Kind, max, tolerance] = { 5126: [Float32Array, 1, 1e-4], 5122: [Int16Array, 32767, 2e-4], 5120: [Int8Array, 127, 2e-2] }[a.componentType];
        const raw = new Kind(bin.buffer, at, a.count * 4);
        const f = (k) => Math.max(raw[k] / max, -1);
        for (let i = 0; i < a.count; i++) {
          const len = Math.hypot(f(4 * i), f(4 * i + 1), f(4 * i + 2), f(4 * i + 3));
          if (Math.abs(len - 1) > tolerance) {
            console.log(`  instancing: node ${n} rotation ${i} has length ${len}`);
            problems++;
            break;
          }
        }
      }
    }
    // A forest's placements are its full detail: the nodes a scene reaches. Coarser levels
    // (MSFT_lod) place the same trees again, so they are checked below, not counted.
    if (inScene.has(n)) placements += count || 0;
  }
  problems += checkLevels(json);
  console.log(`  instancing: ${placements} placements, ${problems} problems`);
  if (expected !== undefined && Number(expected) !== placements) {
    console.log(`  instancing: expected ${expected} placements`);
    problems++;
  }
  process.exit(numErrors === 0 && problems === 0 ? 0 : 1);
}

// The nodes reachable from `roots` through children.
function reachable(json, roots) {
  const seen = new Set();
  const stack = [...roots];
  while (stack.length) {
    const n = stack.pop();
    if (seen.has(n)) continue;
    seen.add(n);
    stack.push(...((json.nodes[n] || {}).children || []));
  }
  return seen;
}

// The TRANSLATION accessors of the instanced nodes under `n`.
function placedUnder(json, n) {
  const out = new Set();
  for (const k of reachable(json, [n])) {
    const ext = (json.nodes[k].extensions || {}).EXT_mesh_gpu_instancing;
    if (ext) out.add(ext.attributes.TRANSLATION);
  }
  return out;
}

// MSFT_lod as sylva writes it: the coarser levels are outside the scene, each places its
// meshes with the full level's accessors (a branch that a coarser level drops is left out
// of it), MSFT_screencoverage has a share per level, each at most the one before, and the
// impostor that extras.sylva_levels names (a placement per tree) is outside the scene too.
function checkLevels(json) {
  if (!(json.extensionsUsed || []).includes('MSFT_lod')) return 0;
  if ((json.extensionsRequired || []).includes('MSFT_lod')) {
    console.log('  levels: MSFT_lod must not be required (a client without it draws full detail)');
    return 1;
  }
  const scene = reachable(json, json.scenes[json.scene || 0].nodes);
  let problems = 0;
  let groups = 0;
  for (const [n, node] of json.nodes.entries()) {
    const lod = (node.extensions || {}).MSFT_lod;
    if (!lod) continue;
    groups++;
    const full = placedUnder(json, n);
    const levels = (node.extras || {}).sylva_levels || {};
    const impostor = levels.impostor;
    if (impostor != null && (scene.has(impostor) || !((json.nodes[impostor] || {}).extensions || {}).EXT_mesh_gpu_instancing)) {
      console.log(`  levels: node ${n}'s impostor (node ${impostor}) is in the scene or not instanced`);
      problems++;
    }
    for (const [k, id] of lod.ids.entries()) {
      if (scene.has(id)) { console.log(`  levels: node ${n}'s level ${k + 1} (node ${id}) is in the scene`); problems++; }
      const foreign = [...placedUnder(json, id)].filter((a) => !full.has(a));
      if (foreign.length > 0) {
        console.log(`  levels: node ${n}'s level ${k + 1} places accessors ${foreign.slice(0, 5)} that its full level does not`);
        problems++;
      }
    }
    const cover = (node.extras || {}).MSFT_screencoverage || [];
    if (cover.length !== lod.ids.length + 1 || cover.some((c, k) => k > 0 && c > cover[k - 1])) {
      console.log(`  levels: node ${n}'s MSFT_screencoverage ${JSON.stringify(cover)} does not fit its ${lod.ids.length + 1} levels`);
      problems++;
    }
  }
  console.log(`  levels: ${groups} nodes with MSFT_lod, ${problems} problems`);
  return problems;
}

function chunk(data, index) {
  const dv = new DataView(data.buffer, data.byteOffset, data.byteLength);
  let offset = 12;
  for (let i = 0; i <= index; i++) {
    const len = dv.getUint32(offset, true);
    if (i === index) return data.subarray(offset + 8, offset + 8 + len);
    offset += 8 + len;
  }
}
function parseGlbJson(data) {
  return JSON.parse(new TextDecoder().decode(chunk(data, 0)));
}
function parseGlbBin(data) {
  const c = chunk(data, 1);
  return new Uint8Array(c); // copy: aligned for Float32Array views
}

main().catch((e) => {
  console.error(e);
  process.exit(2);
});
