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

import { BufferGeometry, DoubleSide, Frustum, ShaderChunk, InstancedBufferAttribute, InstancedMesh, Matrix4, Object3D, Vector3 } from 'three';
import { Bin, binForest, boxOf, cellGroup, drawPlan, localPlanes, meshSphere, placementSpheres, switchScale, treeBases, WIND_TREE_REACH } from './levels.js';

export { NONE, treeLevels } from './levels.js';

/** The name of the glTF extension sylva declares its levels with. */
export const LEVELS_EXTENSION = 'MSFT_lod';

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
    /** The loaded node of each mesh a level draws with, by mesh index. */
    this.templates = new Map();
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
    gltf.userData.sylva = { groups, templates: this.templates };
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
      proto.meshes[0] = this.template(json.nodes[child].mesh, proto.object);
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
        proto.meshes[k] = this.template(json.nodes[child].mesh, await parser.getDependency('node', child));
      }
    }
    let impostor = null;
    if (levels.impostor != null) {
      const id = levels.impostor;
      impostor = await this.placements(id, true);
      if (impostor) impostor.meshes = [this.template(json.nodes[id].mesh, impostor.object)];
    }
    return cellGroup({ index, full, levels, meshLevels, protos, impostor });
  }

  // Names a mesh by its index, keeping the node it was loaded as.
  template(mesh, object) {
    if (!this.templates.has(mesh)) this.templates.set(mesh, object);
    return mesh;
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
    const at = (i, c) => translation.getComponent(i, c);
    const bases = treeBases(n, at, wind && ((i, c) => wind.getComponent(i, c)), reach);
    const { center, radius } = meshSphere(parser.json, def.mesh);
    return {
      object,
      translation: inst.attributes.TRANSLATION,
      n,
      matrices: mesh.instanceMatrix.array,
      colors: mesh.instanceColor ? mesh.instanceColor.array : null,
      colorStride: 3,
      bases,
      spheres: placementSpheres(mesh.instanceMatrix.array, n, center, radius),
      basesBox: boxOf(bases, n),
      box: boxOf(treeBases(n, at, null), n),
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

/**
 * One merged draw: a prototype at one level, an InstancedMesh per primitive, and the bin
 * each frame's placements are copied into (the first primitive's own instance buffers).
 */
class Draw {
  constructor(template, capacity, cards = false) {
    const fades = new Float32Array(capacity);
    this.fade = new InstancedBufferAttribute(fades, 1);
    this.meshes = instancedMeshes(template).map((m) => {
      // The primitive's vertex attributes, shared (not the template's placements' own, such
      // as _WIND_TREE, which GLTFLoader puts on the geometry), and this draw's fades.
      const geometry = new BufferGeometry();
      for (const [name, attribute] of Object.entries(m.geometry.attributes)) {
        if (!attribute.isInstancedBufferAttribute) geometry.setAttribute(name, attribute);
      }
      geometry.setIndex(m.geometry.index);
      geometry.setAttribute('sylvaFade', this.fade);
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
    const [first] = this.meshes;
    this.bin = new Bin(capacity, first ? first.instanceMatrix.array : new Float32Array(0),
      first && first.instanceColor ? first.instanceColor.array : null, 3, fades);
  }

  // Hands this frame's placements to every primitive's mesh.
  finish() {
    const { count, matrices, colors } = this.bin;
    const [first] = this.meshes;
    for (const mesh of this.meshes) {
      if (mesh !== first) {
        mesh.instanceMatrix.array.set(matrices.subarray(0, 16 * count));
        if (mesh.instanceColor && colors) mesh.instanceColor.array.set(colors.subarray(0, 3 * count));
      }
      mesh.count = count;
      mesh.visible = count > 0;
      for (const attribute of [mesh.instanceMatrix, mesh.instanceColor]) {
        if (!attribute) continue;
        attribute.clearUpdateRanges();
        attribute.addUpdateRange(0, attribute.itemSize * count);
        attribute.needsUpdate = true;
      }
    }
    this.fade.clearUpdateRanges();
    this.fade.addUpdateRange(0, count);
    this.fade.needsUpdate = true;
  }
}

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
    // The file's own cell nodes now only hold data.
    for (const g of this.groups) {
      const cell = g.full.parent;
      if (cell && cell.parent) cell.parent.remove(cell);
    }
    // Every prototype at every level, as one draw for the forest.
    const { capacity, cards } = drawPlan(this.groups);
    this.draws = new Map();
    for (const [key, n] of capacity) {
      const draw = new Draw(data.templates.get(key), n, cards.has(key));
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

  /** Culls the cells and trees and picks every tree's level for `camera`. */
  update(camera) {
    camera.updateMatrixWorld();
    this.updateMatrixWorld();
    this.matrix4.multiplyMatrices(camera.projectionMatrix, camera.matrixWorldInverse);
    const key = `${this.matrix4.elements.join(',')}|${this.matrixWorld.elements.join(',')}`;
    if (key === this.last) return;
    this.last = key;
    this.frustum.setFromProjectionMatrix(this.matrix4);
    // The frustum and the eye in the forest's own frame, the file's coordinates.
    const planes = localPlanes(this.frustum.planes.map((p) => [p.normal.x, p.normal.y, p.normal.z, p.constant]), this.matrixWorld.elements);
    this.worldToLocal(camera.getWorldPosition(this.eye));
    for (const draw of this.draws.values()) draw.bin.count = 0;
    const fov = (camera.fov || 60) * Math.PI / 180;
    this.stats = binForest(this.groups, this.eye.toArray(), planes,
      (g) => switchScale(g.levels, fov, this.screenHeight, this.pixelError),
      (key) => this.draws.get(key).bin);
    for (const draw of this.draws.values()) draw.finish();
  }
}
