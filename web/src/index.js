// sylva-three: draws a sylva forest GLB in three.js within a frame budget.
//
// A sylva forest file groups its trees in square cells, a node per cell and variant, and
// gives every such node its levels of detail with MSFT_lod (the coarser levels place the
// same trees with coarser meshes) and its impostor in extras.sylva_levels (the impostor's
// cards placed once per tree). three.js's GLTFLoader reads none of it and would draw every tree at
// full detail. This module adds two things:
//
// - `SylvaLevels`, a GLTFLoader plugin that loads each node's coarser levels (nodes outside
//   the scene) and reads what the file says of them;
// - `SylvaForest`, an Object3D that draws the forest from them: each frame it culls the
//   cells against the camera's frustum and picks each tree's level by its distance, the
//   switch distances the file gives for a 1080-row screen scaled to the camera (a tree
//   past a switch distance cross-fades, dithered, over the file's fade band), and draws
//   every prototype at every level as one InstancedMesh for the whole forest (a draw call
//   per prototype and level, not per cell).
//
//   const loader = new GLTFLoader().register((parser) => new SylvaLevels(parser));
//   const gltf = await loader.loadAsync('forest.glb');
//   const forest = new SylvaForest(gltf);
//   scene.add(gltf.scene, forest);
//   renderer.setAnimationLoop(() => { forest.update(camera); renderer.render(scene, camera); });

import { Box3, BufferGeometry, DoubleSide, Frustum, ShaderChunk, InstancedBufferAttribute, InstancedMesh, Matrix4, Object3D, Vector3 } from 'three';

/** The name of the glTF extension sylva declares its levels with. */
export const LEVELS_EXTENSION = 'MSFT_lod';

/** What `_WIND_TREE`'s offsets are in units of, when a node does not say. */
const WIND_TREE_REACH = 256;

/** The objects an instanced node became: its InstancedMesh, or a group of them. */
function instancedMeshes(object) {
  if (!object) return [];
  if (object.isInstancedMesh) return [object];
  return object.children.filter((c) => c.isInstancedMesh);
}

/**
 * A GLTFLoader plugin that reads a sylva forest's levels: `gltf.userData.sylva` holds, per
 * node with levels, its placements and the meshes of each level. Register it before
 * loading; without it GLTFLoader loads full detail only.
 */
export class SylvaLevels {
  constructor(parser) {
    this.parser = parser;
    this.name = LEVELS_EXTENSION;
  }

  async afterRoot(gltf) {
    const { parser } = this;
    const json = parser.json;
    const pending = [];
    for (let index = 0; index < (json.nodes || []).length; index++) {
      const def = json.nodes[index];
      const lod = def.extensions && def.extensions[LEVELS_EXTENSION];
      const levels = def.extras && def.extras.sylva_levels;
      if (levels) pending.push(this.group(index, lod ? lod.ids : [], levels));
    }
    const groups = await Promise.all(pending);
    gltf.userData.sylva = { groups };
  }

  // One node with levels: its full level's prototypes, each with its placements (matrices,
  // colours, trees' bases) and its mesh at each level, and its impostor.
  async group(index, ids, levels) {
    const { parser } = this;
    const json = parser.json;
    const def = json.nodes[index];
    const full = await parser.getDependency('node', index);
    const meshLevels = ids.length + 1;
    const byPlacements = new Map();
    const protos = [];
    for (const child of def.children || []) {
      const proto = await this.placements(child);
      if (!proto) continue;
      proto.meshes = new Array(meshLevels).fill(null);
      proto.meshes[0] = { key: json.nodes[child].mesh, object: proto.object };
      byPlacements.set(proto.translation, proto);
      protos.push(proto);
    }
    for (let k = 1; k < meshLevels; k++) {
      const levelDef = json.nodes[ids[k - 1]];
      await parser.getDependency('node', ids[k - 1]);
      for (const child of levelDef.children || []) {
        const inst = json.nodes[child].extensions.EXT_mesh_gpu_instancing;
        const proto = byPlacements.get(inst.attributes.TRANSLATION);
        if (!proto) continue;
        proto.meshes[k] = { key: json.nodes[child].mesh, object: await parser.getDependency('node', child) };
      }
    }
    let impostor = null;
    if (levels.impostor != null) {
      const id = levels.impostor;
      impostor = await this.placements(id, true);
      if (impostor) impostor.meshes = [{ key: json.nodes[id].mesh, object: impostor.object }];
    }
    return { index, full, levels, meshLevels, protos, impostor };
  }

  // An instanced node's placements: its matrices and colours as three.js composed them,
  // and each placement's tree base (the placement itself for an impostor).
  async placements(nodeIndex, atBase = false) {
    const { parser } = this;
    const def = parser.json.nodes[nodeIndex];
    const inst = def.extensions && def.extensions.EXT_mesh_gpu_instancing;
    if (!inst) return null;
    const object = await parser.getDependency('node', nodeIndex);
    const mesh = instancedMeshes(object)[0];
    if (!mesh) return null;
    const translation = await parser.getDependency('accessor', inst.attributes.TRANSLATION);
    const wind = !atBase && inst.attributes._WIND_TREE !== undefined
      ? await parser.getDependency('accessor', inst.attributes._WIND_TREE)
      : null;
    const reach = (def.extras && def.extras.sylva_wind_tree_reach) || WIND_TREE_REACH;
    const n = translation.count;
    const bases = new Float32Array(3 * n);
    for (let i = 0; i < n; i++) {
      for (let c = 0; c < 3; c++) {
        const offset = wind ? wind.getComponent(i, c) * reach : 0;
        bases[3 * i + c] = translation.getComponent(i, c) + offset;
      }
    }
    const box = new Box3();
    const p = new Vector3();
    for (let i = 0; i < n; i++) box.expandByPoint(p.fromBufferAttribute(translation, i));
    return {
      object,
      translation: inst.attributes.TRANSLATION,
      n,
      matrices: mesh.instanceMatrix.array,
      colors: mesh.instanceColor ? mesh.instanceColor.array : null,
      bases,
      box,
    };
  }
}

// Levels cross-fade over a band past each switch distance, dithered: each instance carries
// a fade, 0 when whole; f > 0 when fading out, drawn where the screen's dither is at least
// f; -f when fading in, drawn where it is below f. The two levels of a tree in the band
// cover complementary pixels, so its silhouette never changes at once.
const FADE_VERTEX = `
attribute float sylvaFade;
varying float vSylvaFade;`;
const FADE_FRAGMENT = `
varying float vSylvaFade;
float sylvaDither() {
  // Interleaved gradient noise (Jimenez 2014): a fine, even dither of the screen.
  return fract(52.9829189 * fract(dot(gl_FragCoord.xy, vec2(0.06711056, 0.00583715))));
}`;
const patched = new WeakSet();

/** Teaches `material` the fade (once; every mesh drawing with it has `sylvaFade`). */
function fading(material) {
  if (patched.has(material)) return material;
  patched.add(material);
  const before = material.onBeforeCompile;
  material.onBeforeCompile = (shader, renderer) => {
    if (before) before.call(material, shader, renderer);
    shader.vertexShader = shader.vertexShader
      .replace('#include <common>', `#include <common>${FADE_VERTEX}`)
      .replace('#include <begin_vertex>', '#include <begin_vertex>\n  vSylvaFade = sylvaFade;');
    shader.fragmentShader = shader.fragmentShader
      .replace('#include <common>', `#include <common>${FADE_FRAGMENT}`)
      .replace('void main() {', `void main() {
  if (vSylvaFade > 0.0 && sylvaDither() < vSylvaFade) discard;
  if (vSylvaFade < 0.0 && sylvaDither() >= -vSylvaFade) discard;`);
  };
  const key = material.customProgramCacheKey.bind(material);
  material.customProgramCacheKey = () => `${key()}|sylva-fade`;
  material.needsUpdate = true;
  return material;
}

/**
 * The impostor cards' material drawn once, both sides: the file writes each card twice, one
 * per winding, for clients that flip a double-sided face's normal on its back (its cards
 * face the sky as far as light goes, from either side). Here the back keeps the front's
 * normal, and half the triangles are drawn.
 */
const onceMaterials = new WeakMap();
function cardsOnce(material) {
  if (onceMaterials.has(material)) return onceMaterials.get(material);
  const once = material.clone();
  once.side = DoubleSide;
  once.onBeforeCompile = (shader) => {
    const front = ShaderChunk.normal_fragment_begin.replace('gl_FrontFacing ? 1.0 : - 1.0', '1.0');
    shader.fragmentShader = shader.fragmentShader.replace('#include <normal_fragment_begin>', front);
  };
  once.customProgramCacheKey = () => 'sylva-cards-once';
  onceMaterials.set(material, once);
  return once;
}

/** One merged draw: a prototype at one level, an InstancedMesh per primitive. */
class Draw {
  constructor(template, capacity, cards = false) {
    this.fades = new Float32Array(capacity);
    const fade = new InstancedBufferAttribute(this.fades, 1);
    this.fade = fade;
    this.meshes = instancedMeshes(template).map((m) => {
      // The primitive's own attributes, shared, and this draw's fades.
      const geometry = new BufferGeometry();
      for (const [name, attribute] of Object.entries(m.geometry.attributes)) geometry.setAttribute(name, attribute);
      geometry.setIndex(m.geometry.index);
      geometry.setAttribute('sylvaFade', fade);
      // Impostor cards: the first half of the triangles (the front windings), double-sided.
      if (cards && m.geometry.index) geometry.setDrawRange(0, m.geometry.index.count / 2);
      const own = (material) => fading(cards ? cardsOnce(material) : material);
      const materials = Array.isArray(m.material) ? m.material.map(own) : own(m.material);
      const mesh = new InstancedMesh(geometry, materials, capacity);
      if (m.instanceColor) mesh.instanceColor = new InstancedBufferAttribute(new Float32Array(3 * capacity), 3);
      // The forest culls by cell; a merged draw's bounds change every frame.
      mesh.frustumCulled = false;
      mesh.name = m.name;
      return mesh;
    });
    this.count = 0;
    this.matrices = this.meshes.length ? this.meshes[0].instanceMatrix.array : new Float32Array(0);
    this.colors = this.meshes.length && this.meshes[0].instanceColor ? this.meshes[0].instanceColor.array : null;
  }

  // Copies placement `i` of `source` in, with its fade.
  add(source, i, fade) {
    const at = this.count++;
    this.matrices.set(source.matrices.subarray(16 * i, 16 * i + 16), 16 * at);
    if (this.colors && source.colors) this.colors.set(source.colors.subarray(3 * i, 3 * i + 3), 3 * at);
    this.fades[at] = fade;
  }

  // Copies every placement of `source` in, whole.
  addAll(source) {
    const at = this.count;
    this.matrices.set(source.matrices.subarray(0, 16 * source.n), 16 * at);
    if (this.colors && source.colors) this.colors.set(source.colors.subarray(0, 3 * source.n), 3 * at);
    this.fades.fill(0, at, at + source.n);
    this.count += source.n;
  }

  // Hands this frame's placements to every primitive's mesh.
  finish() {
    const [first] = this.meshes;
    for (const mesh of this.meshes) {
      if (mesh !== first) {
        mesh.instanceMatrix.array.set(this.matrices.subarray(0, 16 * this.count));
        if (mesh.instanceColor && this.colors) mesh.instanceColor.array.set(this.colors.subarray(0, 3 * this.count));
      }
      mesh.count = this.count;
      mesh.visible = this.count > 0;
      for (const attribute of [mesh.instanceMatrix, mesh.instanceColor]) {
        if (!attribute) continue;
        attribute.clearUpdateRanges();
        attribute.addUpdateRange(0, attribute.itemSize * this.count);
        attribute.needsUpdate = true;
      }
    }
    this.fade.clearUpdateRanges();
    this.fade.addUpdateRange(0, this.count);
    this.fade.needsUpdate = true;
  }
}

/** Nothing is drawn: a seedling past its reach. */
const NONE = -1;

/**
 * A forest loaded with `SylvaLevels`, drawn within a frame budget: call `update(camera)`
 * before each render. It takes the place of the file's cell nodes in `gltf.scene` (the
 * terrain stays there).
 */
export class SylvaForest extends Object3D {
  /**
   * @param gltf what GLTFLoader gave, with `SylvaLevels` registered.
   * @param options `screenHeight`: the rows of the picture the switch distances are worked
   *   out for (default: 1080, as the file's); `pixelError`: the screen-space error allowed,
   *   in pixels (default: the file's, 2).
   */
  constructor(gltf, options = {}) {
    super();
    this.name = 'sylva forest';
    const data = gltf.userData && gltf.userData.sylva;
    if (!data) throw new Error('sylva-three: register SylvaLevels with the GLTFLoader before loading');
    this.groups = data.groups;
    this.screenHeight = options.screenHeight || 1080;
    this.pixelError = options.pixelError || null;
    // Every prototype at every level, as one draw for the forest.
    const capacity = new Map();
    const template = new Map();
    const cards = new Set();
    for (const g of this.groups) {
      for (const source of g.impostor ? [...g.protos, g.impostor] : g.protos) {
        for (const m of source.meshes) {
          if (!m) continue;
          capacity.set(m.key, (capacity.get(m.key) || 0) + source.n);
          if (!template.has(m.key)) template.set(m.key, m.object);
        }
      }
      if (g.impostor) cards.add(g.impostor.meshes[0].key);
      // The file's own cell nodes now only hold data.
      const cell = g.full.parent;
      if (cell && cell.parent) cell.parent.remove(cell);
      g.box = new Box3();
      g.bases = new Box3();
      for (const source of g.impostor ? [...g.protos, g.impostor] : g.protos) {
        g.box.union(source.box);
        for (let i = 0; i < source.n; i++) {
          g.bases.expandByPoint(new Vector3(source.bases[3 * i], source.bases[3 * i + 1], source.bases[3 * i + 2]));
        }
      }
      // Placements are branches' origins: the cell's box grows by the tallest reach of a
      // tree above and around them.
      g.box.expandByVector(new Vector3(g.levels.reach == null ? 20 : 6, g.levels.reach == null ? 45 : 10, g.levels.reach == null ? 20 : 6));
    }
    this.draws = new Map();
    for (const [key, n] of capacity) {
      const draw = new Draw(template.get(key), n, cards.has(key));
      this.draws.set(key, draw);
      for (const mesh of draw.meshes) this.add(mesh);
    }
    this.frustum = new Frustum();
    this.matrix4 = new Matrix4();
    this.eye = new Vector3();
    this.last = null;
    /** What the last update drew: placements per level, and cells in view. */
    this.stats = { cells: 0, placements: [], impostors: 0 };
  }

  // The switch distances of `g` for this camera: the file's, for a 1080-row screen of 60
  // degrees and its pixel error, scaled to the camera's rows per radian and our error.
  switchScale(camera, g) {
    const fov = (camera.fov || 60) * Math.PI / 180;
    const ours = this.screenHeight / fov / (this.pixelError || g.levels.pixel_error);
    const theirs = g.levels.pixels_per_radian / g.levels.pixel_error;
    return ours / theirs;
  }

  // The levels of a tree `d` from the eye, as [level, fade, level, fade]: one level (a mesh
  // level, the impostor `meshLevels`, or NONE) and NONE, or in the band past a switch
  // distance the level before fading out and the level after fading in.
  static levels(g, d, s) {
    const { from, reach } = g.levels;
    const fade = g.levels.fade || 0;
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

  /** Culls the cells and picks every tree's level for `camera`. */
  update(camera) {
    camera.updateMatrixWorld();
    this.matrix4.multiplyMatrices(camera.projectionMatrix, camera.matrixWorldInverse);
    const key = this.matrix4.elements.join(',');
    if (key === this.last) return;
    this.last = key;
    this.frustum.setFromProjectionMatrix(this.matrix4);
    camera.getWorldPosition(this.eye);
    for (const draw of this.draws.values()) draw.count = 0;
    const stats = { cells: 0, placements: [], impostors: 0 };
    const eye = this.eye;
    const far = new Vector3();
    for (const g of this.groups) {
      if (!this.frustum.intersectsBox(g.box)) continue;
      stats.cells += 1;
      const s = this.switchScale(camera, g);
      const near = g.bases.distanceToPoint(eye);
      far.set(eye.x < (g.bases.min.x + g.bases.max.x) / 2 ? g.bases.max.x : g.bases.min.x,
        eye.y < (g.bases.min.y + g.bases.max.y) / 2 ? g.bases.max.y : g.bases.min.y,
        eye.z < (g.bases.min.z + g.bases.max.z) / 2 ? g.bases.max.z : g.bases.min.z);
      const lo = SylvaForest.levels(g, near, s);
      const hi = SylvaForest.levels(g, far.distanceTo(eye), s);
      // The whole cell at one level, unfaded, when its nearest and farthest trees agree.
      const whole = lo[0] === hi[0] && lo[2] === NONE && hi[2] === NONE ? lo[0] : null;
      const sources = g.impostor ? [...g.protos, g.impostor] : g.protos;
      for (const source of sources) {
        const impostor = source === g.impostor;
        const drawOf = (level) => {
          if (level === NONE) return null;
          if (impostor) return level === g.meshLevels ? this.draws.get(source.meshes[0].key) : null;
          const m = level < g.meshLevels ? source.meshes[level] : null;
          return m ? this.draws.get(m.key) : null;
        };
        if (whole !== null) {
          const draw = drawOf(whole);
          if (draw) {
            draw.addAll(source);
            count(stats, impostor ? 'impostor' : whole, source.n);
          }
          continue;
        }
        const b = source.bases;
        for (let i = 0; i < source.n; i++) {
          const dx = b[3 * i] - eye.x, dy = b[3 * i + 1] - eye.y, dz = b[3 * i + 2] - eye.z;
          const [first, firstFade, second, secondFade] = SylvaForest.levels(g, Math.sqrt(dx * dx + dy * dy + dz * dz), s);
          for (const [level, fade] of [[first, firstFade], [second, secondFade]]) {
            const draw = drawOf(level);
            if (!draw) continue;
            draw.add(source, i, fade);
            count(stats, impostor ? 'impostor' : level, 1);
          }
        }
      }
    }
    for (const draw of this.draws.values()) draw.finish();
    this.stats = stats;
  }
}

function count(stats, level, n) {
  if (level === 'impostor') stats.impostors += n;
  else stats.placements[level] = (stats.placements[level] || 0) + n;
}
