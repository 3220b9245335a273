// The engine-free half of drawing a sylva forest within a frame budget: which level each
// tree is drawn at, and the per-frame binning of placements into one draw per prototype and
// level. `index.js` (three.js) and `babylon.js` (Babylon.js) read the file and upload the
// bins; the rule that picks a tree's level lives here once.
//
// A forest's groups are what the engine's loader read from the file, one per cell and
// variant:
//
//   { levels,      // the node's extras.sylva_levels: from, reach, fade, pixel_error, pixels_per_radian
//     meshLevels,  // mesh levels: 1 + the MSFT_lod ids
//     protos,      // sources, one per prototype of the full level
//     impostor,    // the source of the impostor's cards, or null
//     bases }      // { min, max } of the trees' bases, in the file's coordinates
//
// and a source is the placements of one instanced node: `n`, `matrices` (16 floats each,
// column-major, as glTF and both engines lay them out), `colors` (or null), `colorStride`,
// `bases` (each placement's tree base, 3 floats) and `meshes` (per level, a key naming the
// mesh the engine draws it with, or null).

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
 * at once.
 */
export function treeLevels(levels, d, s) {
  const { from, reach } = levels;
  const fade = levels.fade || 0;
  if (reach != null && d >= reach * s) return [NONE, 0, NONE, 0];
  let level = 0;
  for (let k = 0; k < from.length; k++) if (d >= from[k] * s) level = k + 1;
  if (level > 0 && fade > 0) {
    const at = from[level - 1] * s;
    if (d < at * (1 + fade)) {
      let before = 0;
      for (let k = 0; k < from.length; k++) if (from[k] * s < at) before = k + 1;
      const f = Math.min(1, Math.max(1e-3, (d - at) / (at * fade)));
      return [before, f, level, -f];
    }
  }
  return [level, 0, NONE, 0];
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
 * The placements of one draw (a prototype at one level) for one frame: matrices, colours
 * and fades, copied in from the sources' placements. The engine uploads `count` of each.
 */
export class Bin {
  /**
   * @param matrices 16 floats per placement of capacity (the engine's own instance buffer,
   *   so nothing is copied twice); `colors` likewise `colorStride` floats each, or null.
   */
  constructor(capacity, matrices, colors, colorStride) {
    this.capacity = capacity;
    this.matrices = matrices;
    this.colors = colors;
    this.colorStride = colorStride;
    this.fades = new Float32Array(capacity);
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
 * Bins a forest's placements for one frame: every group `inView` is culled in, each tree's
 * level picked by its distance from `eye` ([x, y, z], the file's coordinates) with the
 * switch distances scaled by `scaleOf(group)`, and copied into the bin `binOf(key)` of its
 * mesh at that level. A cell whose nearest and farthest trees agree on one unfaded level
 * is copied whole. Returns what was drawn: cells in view, placements per mesh level,
 * impostors.
 */
export function binForest(groups, eye, inView, scaleOf, binOf) {
  const stats = { cells: 0, placements: [], impostors: 0 };
  const [ex, ey, ez] = eye;
  for (const g of groups) {
    if (!inView(g)) continue;
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
    const whole = lo[0] === hi[0] && lo[2] === NONE && hi[2] === NONE ? lo[0] : null;
    const sources = g.impostor ? [...g.protos, g.impostor] : g.protos;
    for (const source of sources) {
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
      for (let i = 0; i < source.n; i++) {
        const dx = b[3 * i] - ex, dy = b[3 * i + 1] - ey, dz = b[3 * i + 2] - ez;
        const [first, firstFade, second, secondFade] = treeLevels(g.levels, Math.sqrt(dx * dx + dy * dy + dz * dz), s);
        for (const [level, fade] of [[first, firstFade], [second, secondFade]]) {
          const bin = binAt(level);
          if (!bin) continue;
          bin.add(source, i, fade);
          counted(level, 1);
        }
      }
    }
  }
  return stats;
}
