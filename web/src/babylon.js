// sylva-three/babylon: draws a sylva forest GLB in Babylon.js within a frame budget.
//
// Babylon.js's glTF loader reads MSFT_lod as progressive loading: it shows the coarsest
// level first and ends at full detail, every tree of the forest (the default forest is
// 424 M triangles, and its page runs out of memory). This module loads the levels and draws
// them by distance, as `index.js` does for three.js, with the same rule (`levels.js`):
//
// - `registerSylvaLevels()` adds a glTF loader extension that, after the scene, loads each
//   cell's coarser levels and impostor (nodes outside the scene) and reads their placements;
// - `SylvaForest` culls the cells against the active camera's frustum before Babylon picks
//   its active meshes, picks each tree's level by its distance (cross-fading over the
//   file's fade band with Babylon's own `DitheredTileFadeMaterialPlugin`), and draws each
//   prototype at each level as one thin-instanced mesh for the whole forest.
//
//   import { loadSylvaForest } from 'sylva-three/babylon';
//   const { container, forest } = await loadSylvaForest('forest.glb', scene);

import { GLTFLoader } from '@babylonjs/loaders/glTF/2.0/glTFLoader.js';
import { LoadAssetContainerAsync } from '@babylonjs/core/Loading/sceneLoader.js';
import { Mesh } from '@babylonjs/core/Meshes/mesh.js';
import { SubMesh } from '@babylonjs/core/Meshes/subMesh.js';
import '@babylonjs/core/Meshes/thinInstanceMesh.js';
import { Matrix, Quaternion, Vector3 } from '@babylonjs/core/Maths/math.vector.js';
import { Camera } from '@babylonjs/core/Cameras/camera.js';
import { DitheredTileFadeMaterialPlugin } from '@babylonjs/core/Materials/ditheredTileFadeMaterialPlugin.js';
import { Bin, binForest, boxOf, cellGroup, drawPlan, localPlanes, meshSphere, placementSpheres, switchScale, treeBases, WIND_TREE_REACH } from './levels.js';

/** The name sylva's loader extension registers under (no file names it). */
export const SYLVA_LEVELS = 'sylva_levels';

const INSTANCING = 'EXT_mesh_gpu_instancing';

/**
 * A glTF loader extension that loads a sylva forest's levels: after the scene it loads
 * every cell's coarser levels and impostor and keeps, in the root mesh's
 * `metadata.sylva`, each cell's placements and the meshes of each level. Babylon's own
 * MSFT_lod must be off (it would load each cell's levels in turn and keep only full
 * detail): `loadSylvaForest` turns it off.
 */
class SylvaLevelsExtension {
  constructor(loader) {
    this.name = SYLVA_LEVELS;
    this.enabled = true;
    this.loader = loader;
    /** Placement nodes, by index: the copy of each that Babylon loads. */
    this.copies = new Map();
    this.copyDefs = new WeakSet();
  }

  // Babylon's own loading of an instanced node costs too much for a forest's tens of
  // thousands: it gives each node its own geometry and index buffer (the default forest's
  // meshes would be loaded ~20 times over), and measures every placement's every vertex for
  // the node's bounds. The forest needs each mesh once, unplaced, and the placements, which
  // it reads from the accessors: a placement node is loaded as a copy without its
  // instancing, and without its mesh when another node loads that mesh.
  onLoading() {
    const nodes = this.loader.gltf.nodes || [];
    const loaded = new Set();
    const placement = (index) => {
      const def = nodes[index];
      if (!def || def.mesh === undefined || !(def.extensions && def.extensions[INSTANCING])) return;
      const copy = { ...def, extensions: undefined };
      if (loaded.has(def.mesh)) copy.mesh = undefined;
      else loaded.add(def.mesh);
      this.copies.set(index, copy);
      this.copyDefs.add(copy);
    };
    for (const def of nodes) {
      const levels = def.extras && def.extras.sylva_levels;
      if (!levels) continue;
      const ids = (def.extensions && def.extensions.MSFT_lod && def.extensions.MSFT_lod.ids) || [];
      for (const id of [def.index, ...ids]) for (const child of nodes[id].children || []) placement(child);
      if (levels.impostor != null) placement(levels.impostor);
    }
  }

  loadNodeAsync(context, node, assign) {
    if (this.copyDefs.has(node) || !this.copies.has(node.index)) return null;
    return this.loader.loadNodeAsync(context, this.copies.get(node.index), assign);
  }

  dispose() {
    this.loader = null;
  }

  // The scene as Babylon loads it, then the levels. Babylon calls the loader's own scene
  // loading (not this extension's again) from inside this one.
  loadSceneAsync(context, scene) {
    const loaded = this.loader.loadSceneAsync(context, scene);
    return loaded.then(() => this.loadLevels());
  }

  async loadLevels() {
    const { loader } = this;
    const nodes = loader.gltf.nodes || [];
    const root = loader.rootBabylonMesh;
    const templates = new Map();
    const template = (def) => {
      const copy = this.copies.get(def.index);
      const meshes = copy ? copy._primitiveBabylonMeshes : def._primitiveBabylonMeshes;
      if (meshes) templates.set(def.mesh, meshes);
      return def.mesh;
    };
    const groups = [];
    const extra = new Set();
    for (const def of nodes) {
      const levels = def.extras && def.extras.sylva_levels;
      if (!levels) continue;
      const ids = (def.extensions && def.extensions.MSFT_lod && def.extensions.MSFT_lod.ids) || [];
      for (const id of ids) extra.add(id);
      if (levels.impostor != null) extra.add(levels.impostor);
      groups.push({ def, ids, levels });
    }
    // The levels' nodes, outside the scene: loaded under the root (which turns glTF's
    // right-handed coordinates into the scene's) and never drawn themselves.
    await Promise.all([...extra].map((id) => loader.loadNodeAsync(`/nodes/${id}`, nodes[id], (node) => {
      node.parent = root;
      node.setEnabled(false);
    })));
    const out = [];
    for (const { def, ids, levels } of groups) {
      const meshLevels = ids.length + 1;
      const protos = [];
      for (const child of def.children || []) {
        const childDef = nodes[child];
        const proto = await this.placements(childDef, false);
        if (!proto) continue;
        proto.meshes = new Array(meshLevels).fill(null);
        proto.meshes[0] = template(childDef);
        protos.push(proto);
      }
      for (let k = 1; k < meshLevels; k++) {
        for (const child of nodes[ids[k - 1]].children || []) {
          const childDef = nodes[child];
          const inst = childDef.extensions && childDef.extensions[INSTANCING];
          const proto = inst && protos.find((p) => p.translation === inst.attributes.TRANSLATION);
          if (proto) proto.meshes[k] = template(childDef);
        }
      }
      let impostor = null;
      if (levels.impostor != null) {
        const impostorDef = nodes[levels.impostor];
        impostor = await this.placements(impostorDef, true);
        if (impostor) impostor.meshes = [template(impostorDef)];
      }
      // The cell's own nodes now only hold data; the forest draws them.
      if (def._babylonTransformNode) def._babylonTransformNode.setEnabled(false);
      out.push(cellGroup({ levels, meshLevels, protos, impostor }));
    }
    root.metadata = { ...(root.metadata || {}), sylva: { groups: out, templates } };
  }

  // An instanced node's placements (the coarser levels place the same ones through the same
  // accessors): its matrices and colours, and each placement's tree base (the placement
  // itself for an impostor).
  async placements(def, atBase) {
    const inst = def.extensions && def.extensions[INSTANCING];
    if (!inst) return null;
    const { loader } = this;
    const read = (name) => {
      const index = inst.attributes[name];
      if (index === undefined) return Promise.resolve(null);
      return loader._loadFloatAccessorAsync(`/accessors/${index}`, loader.gltf.accessors[index]);
    };
    const [translation, rotation, scale, color, wind] = await Promise.all(
      ['TRANSLATION', 'ROTATION', 'SCALE', '_COLOR_0', atBase ? null : '_WIND_TREE'].map((name) => (name ? read(name) : null)));
    const n = translation.length / 3;
    const matrices = new Float32Array(16 * n);
    const t = new Vector3();
    const q = new Quaternion();
    const s = new Vector3(1, 1, 1);
    const m = new Matrix();
    for (let i = 0; i < n; i++) {
      Vector3.FromArrayToRef(translation, 3 * i, t);
      if (rotation) Quaternion.FromArrayToRef(rotation, 4 * i, q);
      if (scale) Vector3.FromArrayToRef(scale, 3 * i, s);
      Matrix.ComposeToRef(s, q, t, m);
      m.copyToArray(matrices, 16 * i);
    }
    const reach = (def.extras && def.extras.sylva_wind_tree_reach) || WIND_TREE_REACH;
    const bases = treeBases(n, (i, c) => translation[3 * i + c], wind && ((i, c) => wind[4 * i + c]), reach);
    const colorStride = color ? color.length / n : 0;
    const { center, radius } = meshSphere(loader.gltf, def.mesh);
    return {
      translation: inst.attributes.TRANSLATION,
      n,
      matrices,
      colors: color,
      colorStride,
      bases,
      spheres: placementSpheres(matrices, n, center, radius),
      basesBox: boxOf(bases, n),
      box: boxOf(translation, n),
    };
  }
}

let registered = false;

/** Registers sylva's loader extension with Babylon's glTF loader (once). */
export function registerSylvaLevels() {
  if (registered) return;
  registered = true;
  GLTFLoader.RegisterExtension(SYLVA_LEVELS, (loader) => new SylvaLevelsExtension(loader));
}

/**
 * The impostor cards' material drawn once, both sides: the file writes each card twice, one
 * per winding, for clients that flip a double-sided face's normal on its back (its cards
 * face the sky as far as light goes, from either side). Here the back keeps the front's
 * normal, and half the triangles are drawn.
 */
const onceMaterials = new WeakMap();
function cardsOnce(material) {
  if (!material) return material;
  if (!onceMaterials.has(material)) {
    const once = material.clone(`${material.name} (both sides)`);
    once.backFaceCulling = false;
    once.twoSidedLighting = false;
    onceMaterials.set(material, once);
  }
  return onceMaterials.get(material);
}

/**
 * One merged draw: a prototype at one level, a thin-instanced mesh per primitive sharing
 * the template's geometry and material, and the bin each frame's placements go to.
 */
class Draw {
  constructor(templates, capacity, hasColors, cards, root, scene) {
    this.meshes = templates.map((template) => {
      const mesh = new Mesh(`${template.name} (sylva)`, scene);
      template.geometry.applyToMesh(mesh);
      mesh.material = cards ? cardsOnce(template.material) : template.material;
      if (cards) {
        // Impostor cards: the first half of the triangles (the front windings), both sides.
        const indices = mesh.getTotalIndices();
        mesh.subMeshes = [];
        new SubMesh(0, 0, mesh.getTotalVertices(), 0, indices / 2, mesh);
      }
      mesh.parent = root;
      // The forest culls by cell; a merged draw's bounds change every frame (and Babylon
      // would otherwise measure every placement's vertices on each upload).
      mesh.alwaysSelectAsActiveMesh = true;
      mesh.doNotSyncBoundingInfo = true;
      mesh.thinInstanceSetBuffer('matrix', new Float32Array(16 * capacity), 16, false);
      if (hasColors) mesh.thinInstanceSetBuffer('color', new Float32Array(3 * capacity), 3, false);
      mesh.thinInstanceCount = 0;
      mesh.isVisible = false;
      return mesh;
    });
    const [first] = this.meshes;
    this.bin = new Bin(capacity, first ? first._thinInstanceDataStorage.matrixData : new Float32Array(0),
      first && hasColors ? first._userThinInstanceBuffersStorage.data.instanceColor : null, 3);
    this.fades = this.meshes.map((mesh) => mesh.material && DitheredTileFadeMaterialPlugin.GetOrCreate(mesh.material));
    this.bounds = new Float32Array(2 * capacity);
    this.faded = false;
  }

  // Hands this frame's placements to every primitive's mesh, and their fades to Babylon's
  // dithered fade: a tree fading out (f > 0) is drawn where the dither is in [f, 1), one
  // fading in (-f) where it is in [0, f).
  finish() {
    const { count, matrices, colors, fades } = this.bin;
    let fading = false;
    for (let i = 0; i < count; i++) {
      const f = fades[i];
      this.bounds[2 * i] = f > 0 ? f : 0;
      this.bounds[2 * i + 1] = f < 0 ? -f : 1;
      if (f !== 0) fading = true;
    }
    const [first] = this.meshes;
    this.meshes.forEach((mesh, k) => {
      if (mesh !== first) {
        mesh._thinInstanceDataStorage.matrixData.set(matrices.subarray(0, 16 * count));
        if (colors) mesh._userThinInstanceBuffersStorage.data.instanceColor.set(colors.subarray(0, 3 * count));
      }
      mesh.thinInstanceCount = count;
      // A mesh of no thin instances draws itself once: hidden instead.
      mesh.isVisible = count > 0;
      if (count === 0) return;
      mesh.thinInstanceBufferUpdated('matrix');
      if (colors) mesh.thinInstanceBufferUpdated('color');
      const fade = this.fades[k];
      if (fade && (fading || this.faded)) fade.setThinInstanceFadeBoundsBuffer(mesh, this.bounds.subarray(0, 2 * count));
    });
    this.faded = fading;
  }
}

/**
 * A forest loaded with sylva's loader extension, drawn within a frame budget: it updates
 * itself before Babylon evaluates the active meshes of each frame.
 */
export class SylvaForest {
  /**
   * @param root the loaded file's root mesh (`container.meshes[0]`, named `__root__`).
   * @param options `screenHeight`: the rows of the picture the switch distances are worked
   *   out for (default: 1080, as the file's); `pixelError`: the screen-space error allowed,
   *   in pixels (default: the file's, 2).
   */
  constructor(root, options = {}) {
    const data = root.metadata && root.metadata.sylva;
    if (!data) throw new Error('sylva-three/babylon: call registerSylvaLevels() and load with MSFT_lod off (loadSylvaForest does both)');
    const scene = root.getScene();
    this.root = root;
    this.scene = scene;
    this.groups = data.groups;
    this.screenHeight = options.screenHeight || 1080;
    this.pixelError = options.pixelError || null;
    const { capacity, colored, cards } = drawPlan(this.groups);
    this.draws = new Map();
    for (const [key, n] of capacity) this.draws.set(key, new Draw(data.templates.get(key) || [], n, colored.has(key), cards.has(key), root, scene));
    this.last = null;
    /** What the last update drew: cells in view, placements per mesh level, impostors. */
    this.stats = { cells: 0, placements: [], impostors: 0 };
    this.observer = scene.onBeforeActiveMeshesEvaluationObservable.add(() => {
      if (scene.activeCamera) this.update(scene.activeCamera);
    });
  }

  /** Culls the cells and picks every tree's level for `camera` (the scene's frustum). */
  update(camera) {
    const world = this.root.computeWorldMatrix(true);
    const view = this.scene.getTransformMatrix();
    const key = `${view.m.join(',')}|${world.m.join(',')}`;
    if (key === this.last) return;
    this.last = key;
    // The frustum and the eye in the root's frame, the file's coordinates.
    const planes = localPlanes(this.scene.frustumPlanes.map((p) => [p.normal.x, p.normal.y, p.normal.z, p.d]), world.m);
    const eye = Vector3.TransformCoordinates(camera.globalPosition, world.clone().invert());
    const fov = verticalFov(camera, this.scene.getEngine());
    for (const draw of this.draws.values()) draw.bin.count = 0;
    this.stats = binForest(this.groups, [eye.x, eye.y, eye.z], planes,
      (g) => switchScale(g.levels, fov, this.screenHeight, this.pixelError),
      (k) => this.draws.get(k).bin);
    for (const draw of this.draws.values()) draw.finish();
  }

  /** Stops updating and frees the forest's meshes (the file's own stay in its container). */
  dispose() {
    this.scene.onBeforeActiveMeshesEvaluationObservable.remove(this.observer);
    for (const draw of this.draws.values()) for (const mesh of draw.meshes) mesh.dispose(false, false);
    this.draws.clear();
  }
}

// The camera's vertical field of view in radians, whichever way it fixes its fov.
function verticalFov(camera, engine) {
  if (camera.fovMode === Camera.FOVMODE_HORIZONTAL_FIXED) {
    const aspect = engine.getAspectRatio(camera);
    return 2 * Math.atan(Math.tan(camera.fov / 2) / aspect);
  }
  return camera.fov;
}

/**
 * Loads a sylva forest GLB into `scene` and draws it within a frame budget: registers the
 * loader extension, loads with Babylon's MSFT_lod off, adds everything to the scene, and
 * returns the container and the `SylvaForest` (options as its constructor's).
 */
export async function loadSylvaForest(url, scene, options = {}) {
  registerSylvaLevels();
  const container = await LoadAssetContainerAsync(url, scene, {
    pluginOptions: { gltf: { extensionOptions: { MSFT_lod: { enabled: false } } } },
  });
  container.addAllToScene();
  const root = container.meshes.find((mesh) => mesh.metadata && mesh.metadata.sylva) || container.meshes[0];
  const forest = new SylvaForest(root, options);
  return { container, forest };
}
