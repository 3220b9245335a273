// Reading a sylva GLB in Node for the tests: its JSON, its terrain's vertices, and the eyes
// the measures are taken from.
import { readFileSync } from 'node:fs';

/** The JSON chunk and the BIN chunk of a GLB file. */
export function readGlb(path) {
  const data = readFileSync(path);
  const jsonLength = data.readUInt32LE(12);
  const json = JSON.parse(data.subarray(20, 20 + jsonLength).toString('utf8'));
  const binAt = 20 + jsonLength;
  const bin = binAt < data.length ? data.subarray(binAt + 8, binAt + 8 + data.readUInt32LE(binAt)) : null;
  return { json, bin };
}

/** The terrain's vertex positions, as [x, y, z] triples. */
function terrainPositions({ json, bin }) {
  const node = json.nodes.find((n) => n.name === 'terrain');
  if (!node) throw new Error('the file has no terrain node');
  const accessor = json.accessors[json.meshes[node.mesh].primitives[0].attributes.POSITION];
  const view = json.bufferViews[accessor.bufferView];
  const stride = view.byteStride || 12;
  const at = (view.byteOffset || 0) + (accessor.byteOffset || 0);
  const out = [];
  for (let i = 0; i < accessor.count; i++) {
    const o = at + i * stride;
    out.push([bin.readFloatLE(o), bin.readFloatLE(o + 4), bin.readFloatLE(o + 8)]);
  }
  return out;
}

/**
 * The two eyes of issue 59's table, as `x,y,z,tx,ty,tz`: `edge`, 1.7 m above the ground at
 * the middle of the forest's west edge (1 m in), looking east along the ground; `above`,
 * 250 m above that ground, looking at the forest's centre.
 */
export function eyes(glb) {
  const positions = terrainPositions(glb);
  let [minX, minZ, maxX, maxZ] = [Infinity, Infinity, -Infinity, -Infinity];
  for (const [x, , z] of positions) {
    minX = Math.min(minX, x); maxX = Math.max(maxX, x);
    minZ = Math.min(minZ, z); maxZ = Math.max(maxZ, z);
  }
  const centreZ = (minZ + maxZ) / 2;
  const ground = (x, z) => {
    let best = null;
    for (const p of positions) {
      const d = (p[0] - x) ** 2 + (p[2] - z) ** 2;
      if (!best || d < best.d) best = { d, y: p[1] };
    }
    return best.y;
  };
  const x = minX + 1;
  const y = ground(x, centreZ);
  const centreY = ground((minX + maxX) / 2, centreZ);
  const round = (v) => Number(v.toFixed(2));
  return {
    edge: [x, y + 1.7, centreZ, x + 10, y + 1.7, centreZ].map(round).join(','),
    above: [x, y + 250, centreZ, (minX + maxX) / 2, centreY, centreZ].map(round).join(','),
  };
}
