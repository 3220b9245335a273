// The two designs issue 59 asked sylva-three to weigh, built from the same loaded file, for
// test/run.mjs to measure beside SylvaForest (`--modes runtime,im2,batched`):
//
// - `im2`: an InstancedMesh2 (@three.ez/instanced-mesh) per prototype's primitive for the
//   whole forest, its levels added with addLOD at the file's switch distances (an empty
//   level past the impostor's, or past a seedling's reach), culled per placement by its BVH;
//   an InstancedMesh2 per impostor, empty until the impostor's distance. It picks a level
//   by each placement's own distance, not its tree's, and cannot cross-fade.
// - `batched`: a BatchedMesh per material, every prototype at every level a geometry of it
//   and every placement an instance; `update(camera)` sets each instance's geometry by its
//   tree's level (the same rule as SylvaForest's), and three.js culls each instance.
//
// Neither is sylva-three's design; the table in docs/engines.md says why.
import { BatchedMesh, BufferGeometry, Color, Matrix4, Object3D, Vector3 } from 'three';
import { InstancedMesh2 } from '@three.ez/instanced-mesh';
import { NONE, switchScale, treeLevels } from '../src/levels.js';

function primitives(object) {
  if (!object) return [];
  if (object.isInstancedMesh) return [object];
  return object.children.filter((c) => c.isInstancedMesh);
}

// The file's cell nodes only hold data once a forest draws it.
function detachCells(groups) {
  for (const g of groups) {
    const cell = g.full.parent;
    if (cell && cell.parent) cell.parent.remove(cell);
  }
}

// Every prototype's placements across the forest: key -> { sources, meshes, levels, ... }.
function chains(groups) {
  const byKey = new Map();
  for (const g of groups) {
    for (const source of g.sources) {
      const impostor = source === g.impostor;
      const key = `${impostor ? 'impostor' : 'mesh'} ${source.meshes[0]}`;
      if (!byKey.has(key)) byKey.set(key, { impostor, meshes: source.meshes, levels: g.levels, meshLevels: g.meshLevels, sources: [] });
      byKey.get(key).sources.push(source);
    }
  }
  return byKey;
}

// A geometry sharing `geometry`'s attributes (and so its bounds) that draws nothing.
function nothingOf(geometry) {
  const nothing = new BufferGeometry();
  for (const [name, attribute] of Object.entries(geometry.attributes)) nothing.setAttribute(name, attribute);
  nothing.setIndex(geometry.index);
  nothing.setDrawRange(0, 0);
  return nothing;
}

/** InstancedMesh2 with its own LOD and BVH culling. */
export function instancedMesh2(gltf, renderer, { screenHeight = 1080, fov = 60 } = {}) {
  const { groups, templates } = gltf.userData.sylva;
  detachCells(groups);
  const root = new Object3D();
  root.name = 'InstancedMesh2 forest';
  const empty = new BufferGeometry();
  const matrix = new Matrix4();
  const color = new Color();
  for (const chain of chains(groups).values()) {
    const s = switchScale(chain.levels, fov * Math.PI / 180, screenHeight, null);
    const from = chain.levels.from.map((d) => d * s);
    const reach = chain.levels.reach == null ? null : chain.levels.reach * s;
    const n = chain.sources.reduce((sum, source) => sum + source.n, 0);
    const full = primitives(templates.get(chain.meshes[0]));
    full.forEach((template, j) => {
      // Near, an impostor draws nothing; but InstancedMesh2 culls every level by its first
      // level's bounds, so that level is the cards with nothing in their draw range.
      const first = chain.impostor ? nothingOf(template.geometry) : template.geometry;
      const mesh = new InstancedMesh2(first, template.material, { capacity: n, renderer });
      mesh.addInstances(n);
      let at = 0;
      for (const source of chain.sources) {
        for (let i = 0; i < source.n; i++, at++) {
          mesh.setMatrixAt(at, matrix.fromArray(source.matrices, 16 * i));
          if (source.colors) mesh.setColorAt(at, color.fromArray(source.colors, 3 * i));
        }
      }
      if (chain.impostor) {
        // Cards from the impostor's distance on (the level after the last mesh level).
        const at = from[chain.meshLevels - 1];
        if (at !== undefined && (reach === null || at < reach)) mesh.addLOD(template.geometry, template.material, at);
      } else {
        for (let k = 1; k < chain.meshLevels; k++) {
          const level = primitives(templates.get(chain.meshes[k]))[j];
          if (level && from[k - 1] !== undefined) mesh.addLOD(level.geometry, level.material, from[k - 1]);
        }
        const gone = from[chain.meshLevels - 1];
        if (gone !== undefined) mesh.addLOD(empty, template.material, gone);
      }
      // A young tree is drawn no farther than its reach, cards or branches.
      if (reach !== null) mesh.addLOD(chain.impostor ? first : empty, template.material, reach);
      mesh.computeBVH();
      root.add(mesh);
    });
  }
  root.update = () => {};
  return root;
}

// A geometry BatchedMesh can take: its vertices' attributes only (GLTFLoader puts the
// placements' own, such as _WIND_TREE, on the geometry too), each laid out on its own (it
// copies arrays whole; GLTFLoader interleaves a strided buffer view's).
function plain(geometry) {
  const out = new BufferGeometry();
  for (const [name, attribute] of Object.entries(geometry.attributes)) {
    if (attribute.isInstancedBufferAttribute) continue;
    out.setAttribute(name, attribute.isInterleavedBufferAttribute ? attribute.clone() : attribute);
  }
  out.setIndex(geometry.index);
  return out;
}

/** BatchedMesh per material; each instance's geometry set by its tree's level. */
export function batchedMesh(gltf, { screenHeight = 1080 } = {}) {
  const { groups, templates } = gltf.userData.sylva;
  detachCells(groups);
  const root = new Object3D();
  root.name = 'BatchedMesh forest';
  // Per material: the geometries (key, level, primitive) and the instances.
  const batches = new Map();
  const batchOf = (material) => {
    if (!batches.has(material)) batches.set(material, { material, geometries: [], ids: new Map(), instances: 0, vertices: 0, indices: 0 });
    return batches.get(material);
  };
  const chainList = [...chains(groups).values()];
  for (const chain of chainList) {
    const keys = chain.impostor ? [chain.meshes[0]] : chain.meshes;
    chain.primitives = primitives(templates.get(keys[0])).map((template, j) => {
      const batch = batchOf(template.material);
      const perLevel = keys.map((key) => {
        const p = key === null ? null : primitives(templates.get(key))[j];
        if (!p) return null;
        const id = `${key} ${j}`;
        if (!batch.ids.has(id)) {
          batch.ids.set(id, batch.geometries.length);
          batch.geometries.push(plain(p.geometry));
          batch.vertices += p.geometry.attributes.position.count;
          batch.indices += p.geometry.index ? p.geometry.index.count : 0;
        }
        return id;
      });
      batch.instances += chain.sources.reduce((sum, source) => sum + source.n, 0);
      return { batch, perLevel };
    });
  }
  const matrix = new Matrix4();
  const color = new Color();
  for (const batch of batches.values()) {
    const mesh = new BatchedMesh(batch.instances, batch.vertices, batch.indices, batch.material);
    batch.geometryIds = new Map();
    batch.geometries.forEach((geometry, k) => batch.geometryIds.set([...batch.ids.keys()][k], mesh.addGeometry(geometry)));
    batch.mesh = mesh;
    root.add(mesh);
  }
  // Every placement an instance of its full level (or its cards), in each batch.
  for (const chain of chainList) {
    for (const p of chain.primitives) {
      p.instances = [];
      const geometry = p.batch.geometryIds.get(p.perLevel.find((id) => id));
      for (const source of chain.sources) {
        const ids = new Int32Array(source.n);
        for (let i = 0; i < source.n; i++) {
          const id = p.batch.mesh.addInstance(geometry);
          p.batch.mesh.setMatrixAt(id, matrix.fromArray(source.matrices, 16 * i));
          if (source.colors) p.batch.mesh.setColorAt(id, color.fromArray(source.colors, 3 * i));
          ids[i] = id;
        }
        p.instances.push(ids);
      }
    }
  }
  const eye = new Vector3();
  let last = null;
  root.update = (camera) => {
    camera.updateMatrixWorld();
    const key = camera.matrixWorld.elements.join(',');
    if (key === last) return;
    last = key;
    camera.getWorldPosition(eye);
    const fov = camera.fov * Math.PI / 180;
    for (const chain of chainList) {
      const s = switchScale(chain.levels, fov, screenHeight, null);
      chain.sources.forEach((source, k) => {
        const b = source.bases;
        for (let i = 0; i < source.n; i++) {
          const dx = b[3 * i] - eye.x, dy = b[3 * i + 1] - eye.y, dz = b[3 * i + 2] - eye.z;
          // The level drawn whole: past a fade band's middle, the next one (no cross-fade).
          const [first, fade, second] = treeLevels(chain.levels, Math.sqrt(dx * dx + dy * dy + dz * dz), s);
          const level = second !== NONE && fade > 0.5 ? second : first;
          for (const p of chain.primitives) {
            const id = p.instances[k][i];
            const wanted = chain.impostor ? (level === chain.meshLevels ? p.perLevel[0] : null) : (level < chain.meshLevels && level !== NONE ? p.perLevel[level] : null);
            p.batch.mesh.setVisibleAt(id, !!wanted);
            if (wanted) p.batch.mesh.setGeometryIdAt(id, p.batch.geometryIds.get(wanted));
          }
        }
      });
    }
  };
  return root;
}
