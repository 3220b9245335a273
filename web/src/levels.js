// The engine-free half of drawing a sylva forest within a frame budget: which level each
// tree is drawn at, and the per-frame binning of placements into one draw per prototype and
// level. `index.js` (three.js) and `babylon.js` (Babylon.js) read the file and upload the
// bins; the rule that picks a tree's level lives here once.
//
// A forest's groups are what the engine's loader read from the file, one per cell and
// variant, made by `cellGroup`:
//
//   { levels,      // the node's extras.sylva_levels: from, reach, fade, pixel_error, pixels_per_radian
//     meshLevels,  // mesh levels: 1 + the MSFT_lod ids
//     protos,      // sources, one per prototype of the full level
//     impostor,    // the source of the impostor's cards, or null
//     sources,     // the prototypes' and the impostor's sources together
//     bases,       // { min, max } of the trees' bases, in the file's coordinates
//     box }        // { min, max } of the trees drawn, for the frustum
//
// and a source is the placements of one instanced node: `n`, `matrices` (16 floats each,
// column-major, as glTF and both engines lay them out), `colors` (or null), `colorStride`,
// `bases` (each placement's tree base, 3 floats), `basesBox` and `box` (the boxes of the
// bases and of the translations), `spheres` (each placement's bounds, from
// `placementSpheres`) and `meshes` (per level, a key naming the mesh the engine draws it
// with, or null).

/** Nothing is drawn: a seedling past its reach. */
export const NONE = -1;

/** What `_WIND_TREE`'s offsets are in units of, when a node does not say. */
export const WIND_TREE_REACH = 256;

/**
 * How far a group's drawn trees reach past its placements, in metres per axis: placements
 * are branches' origins, so a cell's box grows by the tallest reach of a tree above and
 * around them (young trees, which have a `reach`, are smaller).
 */
export function treeMargin(levels) {
  return levels.reach == null ? [20, 45, 20] : [6, 10, 6];
}

/**
 * The factor that scales the file's switch distances to a camera: the file's are worked out
 * for its own rows per radian and pixel error; `fov` is the camera's vertical field of view
 * in radians, `screenHeight` its rows, `pixelError` the error allowed (null: the file's).
 */
export function switchScale(levels, fov, screenHeight, pixelError) {
  const ours = screenHeight / fov / (pixelError || levels.pixel_error);
  const theirs = levels.pixels_per_radian / levels.pixel_error;
  return ours / theirs;
}

/**
 * The levels of a tree `d` from the eye, for switch distances scaled by `s`, as
 * [level, fade, level, fade]: one level (a mesh level, the impostor `meshLevels`, or NONE)
 * and NONE, or in the band past a switch distance the level before, fading out (fade f > 0:
 * drawn where the screen's dither is at least f), and the level after, fading in (-f: drawn
 * where it is below f). The two cover complementary pixels, so a silhouette never changes
 * at once. `out`, when given, is filled and returned (the per-frame loop allocates none).
 */
export function treeLevels(levels, d, s, out = [NONE, 0, NONE, 0]) {
  const { from, reach } = levels;
  const fade = levels.fade || 0;
  const answer = (first, firstFade, second, secondFade) => {
    out[0] = first;
    out[1] = firstFade;
    out[2] = second;
    out[3] = secondFade;
    return out;
  };
  if (reach != null && d >= reach * s) return answer(NONE, 0, NONE, 0);
  let level = 0;
  for (let k = 0; k < from.length; k++) if (d >= from[k] * s) level = k + 1;
  if (level > 0 && fade > 0) {
    const at = from[level - 1] * s;
    if (d < at * (1 + fade)) {
      let before = 0;
      for (let k = 0; k < from.length; k++) if (from[k] * s < at) before = k + 1;
      const f = Math.min(1, Math.max(1e-3, (d - at) / (at * fade)));
      return answer(before, f, level, -f);
    }
  }
  return answer(level, 0, NONE, 0);
}

/**
 * Each placement's tree base: its translation plus its `_WIND_TREE` offset (in units of
 * `reach` metres), or the translation itself when `wind` is null (an impostor's cards stand
 * at the tree's base). `translation(i, c)` and `wind(i, c)` read component c of placement i.
 */
export function treeBases(n, translation, wind, reach = WIND_TREE_REACH) {
  const bases = new Float32Array(3 * n);
  for (let i = 0; i < n; i++) {
    for (let c = 0; c < 3; c++) bases[3 * i + c] = translation(i, c) + (wind ? wind(i, c) * reach : 0);
  }
  return bases;
}

/** The box { min, max } around `n` points packed three floats each. */
export function boxOf(points, n) {
  const min = [Infinity, Infinity, Infinity];
  const max = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < n; i++) {
    for (let c = 0; c < 3; c++) {
      const v = points[3 * i + c];
      if (v < min[c]) min[c] = v;
      if (v > max[c]) max[c] = v;
    }
  }
  return { min, max };
}

/**
 * A frustum's planes, given in world coordinates as [nx, ny, nz, d] (a point p is on the
 * inner side when n . p + d >= 0, as both engines keep them), moved into the frame of an
 * object whose local-to-world matrix is `m` (16 floats, translation at 12..14, as both
 * engines lay matrices out), so that the file's own coordinates can be tested against them.
 */
export function localPlanes(planes, m) {
  return planes.map(([nx, ny, nz, d]) => {
    const n = [0, 1, 2].map((i) => m[4 * i] * nx + m[4 * i + 1] * ny + m[4 * i + 2] * nz);
    const offset = d + m[12] * nx + m[13] * ny + m[14] * nz;
    const length = Math.hypot(n[0], n[1], n[2]) || 1;
    return [n[0] / length, n[1] / length, n[2] / length, offset / length];
  });
}

/** Where a box { min, max } lies against `planes`: OUTSIDE, CROSSING or INSIDE. */
export function boxAgainst(planes, { min, max }) {
  let inside = true;
  for (const [nx, ny, nz, d] of planes) {
    // The corner farthest along the normal, and the one farthest against it.
    const far = nx * (nx > 0 ? max[0] : min[0]) + ny * (ny > 0 ? max[1] : min[1]) + nz * (nz > 0 ? max[2] : min[2]) + d;
    if (far < 0) return OUTSIDE;
    const near = nx * (nx > 0 ? min[0] : max[0]) + ny * (ny > 0 ? min[1] : max[1]) + nz * (nz > 0 ? min[2] : max[2]) + d;
    if (near < 0) inside = false;
  }
  return inside ? INSIDE : CROSSING;
}

/** A box wholly outside the frustum. */
export const OUTSIDE = 0;
/** A box partly inside the frustum. */
export const CROSSING = 1;
/** A box wholly inside the frustum. */
export const INSIDE = 2;

/**
 * The sphere around a glTF mesh's vertices, { center, radius }, from its primitives'
 * POSITION bounds (which glTF requires) in the file's JSON `json`.
 */
export function meshSphere(json, meshIndex) {
  const min = [Infinity, Infinity, Infinity];
  const max = [-Infinity, -Infinity, -Infinity];
  for (const primitive of json.meshes[meshIndex].primitives) {
    const accessor = json.accessors[primitive.attributes.POSITION];
    const unit = accessor.normalized ? NORMALIZED_MAX[accessor.componentType] || 1 : 1;
    for (let c = 0; c < 3; c++) {
      min[c] = Math.min(min[c], accessor.min[c] / unit);
      max[c] = Math.max(max[c], accessor.max[c] / unit);
    }
  }
  const center = min.map((v, c) => (v + max[c]) / 2);
  return { center, radius: Math.hypot(max[0] - min[0], max[1] - min[1], max[2] - min[2]) / 2 };
}

// The largest value of each normalized component type, by glTF's componentType.
const NORMALIZED_MAX = { 5120: 127, 5121: 255, 5122: 32767, 5123: 65535 };

/**
 * Each placement's bounding sphere (4 floats: centre, radius), from its matrix and its
 * mesh's sphere in the mesh's own coordinates (`center` [x, y, z], `radius`): the
 * frustum culls placements by them.
 */
export function placementSpheres(matrices, n, center, radius) {
  const spheres = new Float32Array(4 * n);
  const [cx, cy, cz] = center;
  for (let i = 0; i < n; i++) {
    const m = matrices.subarray(16 * i, 16 * i + 16);
    spheres[4 * i] = m[0] * cx + m[4] * cy + m[8] * cz + m[12];
    spheres[4 * i + 1] = m[1] * cx + m[5] * cy + m[9] * cz + m[13];
    spheres[4 * i + 2] = m[2] * cx + m[6] * cy + m[10] * cz + m[14];
    const scale = Math.sqrt(Math.max(
      m[0] * m[0] + m[1] * m[1] + m[2] * m[2],
      m[4] * m[4] + m[5] * m[5] + m[6] * m[6],
      m[8] * m[8] + m[9] * m[9] + m[10] * m[10]));
    spheres[4 * i + 3] = radius * scale;
  }
  return spheres;
}

/**
 * A group from what an engine's loader read: its `levels`, mesh levels, prototypes' sources
 * and impostor's source (or null), with `sources`, `bases` and `box` derived from them, and
 * `extra` (the engine's own fields) kept.
 */
export function cellGroup({ levels, meshLevels, protos, impostor, ...extra }) {
  const sources = impostor ? [...protos, impostor] : protos;
  const union = (boxOfSource) => boxOf(Float32Array.from(sources.flatMap((s) => [...boxOfSource(s).min, ...boxOfSource(s).max])), 2 * sources.length);
  const placed = union((s) => s.box);
  const margin = treeMargin(levels);
  return {
    ...extra,
    levels,
    meshLevels,
    protos,
    impostor,
    sources,
    bases: union((s) => s.basesBox),
    box: { min: placed.min.map((v, c) => v - margin[c]), max: placed.max.map((v, c) => v + margin[c]) },
  };
}

/**
 * What a forest draws: per mesh key, the placements it may hold at once (every source that
 * draws with it), whether any of them has colours, and whether it is an impostor's cards.
 */
export function drawPlan(groups) {
  const capacity = new Map();
  const colored = new Set();
  const cards = new Set();
  for (const g of groups) {
    if (g.impostor) cards.add(g.impostor.meshes[0]);
    for (const source of g.sources) {
      for (const key of source.meshes) {
        if (key === null) continue;
        capacity.set(key, (capacity.get(key) || 0) + source.n);
        if (source.colors) colored.add(key);
      }
    }
  }
  return { capacity, colored, cards };
}

/**
 * The placements of one draw (a prototype at one level) for one frame: matrices, colours
 * and fades, copied in from the sources' placements. The engine uploads `count` of each.
 */
export class Bin {
  /**
   * @param matrices 16 floats per placement of capacity (the engine's own instance buffer,
   *   so nothing is copied twice); `colors` likewise `colorStride` floats each, or null;
   *   `fades` one float each (the engine's own, or a new array).
   */
  constructor(capacity, matrices, colors, colorStride, fades = new Float32Array(capacity)) {
    this.capacity = capacity;
    this.matrices = matrices;
    this.colors = colors;
    this.colorStride = colorStride;
    this.fades = fades;
    this.count = 0;
  }

  /** Copies placement `i` of `source` in, with its fade. */
  add(source, i, fade) {
    const at = this.count++;
    this.matrices.set(source.matrices.subarray(16 * i, 16 * i + 16), 16 * at);
    this.copyColors(source, i, 1, at);
    this.fades[at] = fade;
  }

  /** Copies every placement of `source` in, whole. */
  addAll(source) {
    const at = this.count;
    this.matrices.set(source.matrices.subarray(0, 16 * source.n), 16 * at);
    this.copyColors(source, 0, source.n, at);
    this.fades.fill(0, at, at + source.n);
    this.count += source.n;
  }

  copyColors(source, from, n, at) {
    if (!this.colors || !source.colors) return;
    const k = this.colorStride;
    if (source.colorStride === k) {
      this.colors.set(source.colors.subarray(k * from, k * (from + n)), k * at);
      return;
    }
    for (let j = 0; j < n; j++) {
      for (let c = 0; c < k; c++) {
        this.colors[k * (at + j) + c] = c < source.colorStride ? source.colors[source.colorStride * (from + j) + c] : 1;
      }
    }
  }
}

/**
 * Bins a forest's placements for one frame: a group whose box is outside `planes` (the
 * camera's frustum in the file's coordinates, from `localPlanes`) is skipped, a placement
 * whose sphere is outside them too; each tree's level is picked by its distance from `eye`
 * ([x, y, z], the file's coordinates) with the switch distances scaled by `scaleOf(group)`,
 * and its placements copied into the bin `binOf(key)` of their mesh at that level. A cell
 * wholly in view whose nearest and farthest trees agree on one unfaded level is copied
 * whole. Returns what was drawn: cells in view, placements per mesh level, impostors.
 */
export function binForest(groups, eye, planes, scaleOf, binOf) {
  const stats = { cells: 0, placements: [], impostors: 0 };
  const [ex, ey, ez] = eye;
  const picked = [NONE, 0, NONE, 0];
  for (const g of groups) {
    const seen = boxAgainst(planes, g.box);
    if (seen === OUTSIDE) continue;
    stats.cells += 1;
    const s = scaleOf(g);
    const { min, max } = g.bases;
    let near = 0;
    let far = 0;
    for (let c = 0; c < 3; c++) {
      const e = eye[c];
      const inside = e < min[c] ? min[c] - e : e > max[c] ? e - max[c] : 0;
      const outside = e < (min[c] + max[c]) / 2 ? max[c] - e : e - min[c];
      near += inside * inside;
      far += outside * outside;
    }
    const lo = treeLevels(g.levels, Math.sqrt(near), s);
    const hi = treeLevels(g.levels, Math.sqrt(far), s);
    const whole = seen === INSIDE && lo[0] === hi[0] && lo[2] === NONE && hi[2] === NONE ? lo[0] : null;
    for (const source of g.sources) {
      const impostor = source === g.impostor;
      const binAt = (level) => {
        if (level === NONE) return null;
        if (impostor) return level === g.meshLevels ? binOf(source.meshes[0]) : null;
        const key = level < g.meshLevels ? source.meshes[level] : null;
        return key === null || key === undefined ? null : binOf(key);
      };
      const counted = (level, n) => {
        if (impostor) stats.impostors += n;
        else stats.placements[level] = (stats.placements[level] || 0) + n;
      };
      if (whole !== null) {
        const bin = binAt(whole);
        if (bin) {
          bin.addAll(source);
          counted(whole, source.n);
        }
        continue;
      }
      const b = source.bases;
      const o = source.spheres;
      for (let i = 0; i < source.n; i++) {
        if (seen === CROSSING && !sphereInside(planes, o[4 * i], o[4 * i + 1], o[4 * i + 2], o[4 * i + 3])) continue;
        const dx = b[3 * i] - ex, dy = b[3 * i + 1] - ey, dz = b[3 * i + 2] - ez;
        treeLevels(g.levels, Math.sqrt(dx * dx + dy * dy + dz * dz), s, picked);
        for (let k = 0; k < 4; k += 2) {
          const bin = binAt(picked[k]);
          if (!bin) continue;
          bin.add(source, i, picked[k + 1]);
          counted(picked[k], 1);
        }
      }
    }
  }
  return stats;
}

// Whether a sphere reaches the inner side of every plane.
function sphereInside(planes, x, y, z, radius) {
  for (const [nx, ny, nz, d] of planes) if (nx * x + ny * y + nz * z + d < -radius) return false;
  return true;
}
