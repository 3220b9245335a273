//! glTF 2.0 binary (.glb) export: the terrain, one mesh per cached instance, and each
//! instance's placements through EXT_mesh_gpu_instancing.

use std::io::Write;

use serde_json::{Value, json};
use sylva_terrain::TerrainMesh;
use sylva_turtle::Vertex;

use crate::error::ForestError;
use crate::forest::{Forest, VariantPlacements};

/// Export settings.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct GltfOptions {
    /// Terrain colour, linear RGB.
    pub terrain_colour: [f32; 3],
    /// Roughness of every material (all are dielectric: metallic 0).
    pub roughness: f32,
}

impl Default for GltfOptions {
    fn default() -> Self {
        GltfOptions {
            terrain_colour: [0.32, 0.30, 0.18],
            roughness: 0.9,
        }
    }
}

/// What was written.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct GlbStats {
    /// File size in bytes.
    pub bytes: usize,
    /// Instance meshes written (one node each).
    pub instance_nodes: usize,
    /// Instance placements written.
    pub placements: usize,
}

const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;
const FLOAT: u32 = 5126;
const UNSIGNED_INT: u32 = 5125;

#[derive(Default)]
struct Doc {
    bin: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
    meshes: Vec<Value>,
    nodes: Vec<Value>,
    materials: Vec<Value>,
}

impl Doc {
    fn view(&mut self, bytes: &[u8], stride: Option<u32>, target: Option<u32>) -> usize {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let mut v = json!({ "buffer": 0, "byteOffset": self.bin.len(), "byteLength": bytes.len() });
        if let Some(s) = stride {
            v["byteStride"] = json!(s);
        }
        if let Some(t) = target {
            v["target"] = json!(t);
        }
        self.bin.extend_from_slice(bytes);
        self.views.push(v);
        self.views.len() - 1
    }

    fn accessor(
        &mut self,
        view: usize,
        offset: usize,
        component: u32,
        count: usize,
        kind: &str,
        bounds: Option<([f32; 3], [f32; 3])>,
    ) -> usize {
        let mut a = json!({ "bufferView": view, "byteOffset": offset, "componentType": component, "count": count, "type": kind });
        if let Some((lo, hi)) = bounds {
            a["min"] = json!(lo);
            a["max"] = json!(hi);
        }
        self.accessors.push(a);
        self.accessors.len() - 1
    }

    fn material(
        &mut self,
        name: &str,
        colour: [f32; 3],
        roughness: f32,
        double_sided: bool,
    ) -> usize {
        self.materials.push(json!({
            "name": name,
            "pbrMetallicRoughness": { "baseColorFactor": [colour[0], colour[1], colour[2], 1.0], "metallicFactor": 0.0, "roughnessFactor": roughness },
            "doubleSided": double_sided,
        }));
        self.materials.len() - 1
    }

    /// Interleaved position/normal/uv vertices (32 bytes each) and their three accessors.
    fn vertices(
        &mut self,
        bytes: &[u8],
        positions: impl Iterator<Item = [f32; 3]>,
        count: usize,
    ) -> Result<Value, ForestError> {
        let mut lo = [f32::INFINITY; 3];
        let mut hi = [f32::NEG_INFINITY; 3];
        for p in positions {
            if !p.iter().all(|c| c.is_finite()) {
                return Err(ForestError::InvalidExport(
                    "a vertex position is not finite".into(),
                ));
            }
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let view = self.view(bytes, Some(32), Some(ARRAY_BUFFER));
        let position = self.accessor(view, 0, FLOAT, count, "VEC3", Some((lo, hi)));
        let normal = self.accessor(view, 12, FLOAT, count, "VEC3", None);
        let uv = self.accessor(view, 24, FLOAT, count, "VEC2", None);
        Ok(json!({ "POSITION": position, "NORMAL": normal, "TEXCOORD_0": uv }))
    }
}

fn check_normals<'a>(normals: impl Iterator<Item = &'a [f32; 3]>) -> Result<(), ForestError> {
    for n in normals {
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        if !(len - 1.0).abs().lt(&1e-3) {
            return Err(ForestError::InvalidExport(format!(
                "normal {n:?} is not unit length"
            )));
        }
    }
    Ok(())
}

/// Writes `forest` (with its expanded placements, `placed`) and optionally a terrain mesh as a binary
/// glTF. The file declares EXT_mesh_gpu_instancing in `extensionsUsed`; every node of an
/// instance mesh carries TRANSLATION, ROTATION and SCALE accessors of equal count, float
/// components and unit quaternions. Everything is checked before a byte is written: on error
/// `out` is untouched.
pub fn write_glb<W: Write>(
    forest: &Forest,
    placed: &[VariantPlacements],
    terrain: Option<&TerrainMesh>,
    options: &GltfOptions,
    mut out: W,
) -> Result<GlbStats, ForestError> {
    let mut doc = Doc::default();
    let mut stats = GlbStats::default();
    if let Some(t) = terrain.filter(|t| !t.indices.is_empty()) {
        let n = t.vertices.len() as u32;
        if t.indices.iter().any(|&i| i >= n) {
            return Err(ForestError::InvalidExport(
                "terrain index out of range".into(),
            ));
        }
        check_normals(t.vertices.iter().map(|v| &v.normal))?;
        let attributes = doc.vertices(
            bytemuck::cast_slice(&t.vertices),
            t.vertices.iter().map(|v| v.position),
            t.vertices.len(),
        )?;
        let iview = doc.view(
            bytemuck::cast_slice(&t.indices),
            None,
            Some(ELEMENT_ARRAY_BUFFER),
        );
        let indices = doc.accessor(iview, 0, UNSIGNED_INT, t.indices.len(), "SCALAR", None);
        let material = doc.material("terrain", options.terrain_colour, options.roughness, false);
        doc.meshes.push(json!({ "name": "terrain", "primitives": [{ "attributes": attributes, "indices": indices, "material": material }] }));
        doc.nodes
            .push(json!({ "name": "terrain", "mesh": doc.meshes.len() - 1 }));
    }
    for variant_placements in placed {
        let variant = forest
            .variants
            .get(variant_placements.variant)
            .ok_or_else(|| {
                ForestError::InvalidExport(format!(
                    "variant_placements of unknown variant {}",
                    variant_placements.variant
                ))
            })?;
        if variant_placements.placements.groups.len() != variant.cache.instances.len() {
            return Err(ForestError::InvalidExport(format!(
                "variant_placements of variant {} has {} instance groups, but the forest's variant has {} \
                 instances: the placements were made by another forest",
                variant_placements.variant,
                variant_placements.placements.groups.len(),
                variant.cache.instances.len()
            )));
        }
        let used: Vec<usize> = (0..variant_placements.placements.groups.len())
            .filter(|&i| !variant_placements.placements.groups[i].is_empty())
            .collect();
        if used.is_empty() {
            continue;
        }
        let cache = &variant.cache;
        let species = &forest.species[variant.species];
        let n = cache.vertices.len() as u32;
        if cache.bark.iter().chain(&cache.leaves).any(|&i| i >= n) {
            return Err(ForestError::InvalidExport(
                "instance index out of range".into(),
            ));
        }
        check_normals(cache.vertices.iter().map(|v: &Vertex| &v.normal))?;
        let attributes = doc.vertices(
            bytemuck::cast_slice(&cache.vertices),
            cache.vertices.iter().map(|v| v.position),
            cache.vertices.len(),
        )?;
        let bark_view = (!cache.bark.is_empty()).then(|| {
            doc.view(
                bytemuck::cast_slice(&cache.bark),
                None,
                Some(ELEMENT_ARRAY_BUFFER),
            )
        });
        let leaf_view = (!cache.leaves.is_empty()).then(|| {
            doc.view(
                bytemuck::cast_slice(&cache.leaves),
                None,
                Some(ELEMENT_ARRAY_BUFFER),
            )
        });
        let tag = if variant.seedling { "seedling" } else { "tree" };
        let bark_material = doc.material(
            &format!("{} bark", species.name),
            species.bark,
            options.roughness,
            false,
        );
        let leaf_material = doc.material(
            &format!("{} leaves", species.name),
            species.leaf,
            options.roughness,
            true,
        );
        for i in used {
            let inst = &cache.instances[i];
            if inst.bark.0 as usize + inst.bark.1 as usize > cache.bark.len()
                || inst.leaves.0 as usize + inst.leaves.1 as usize > cache.leaves.len()
            {
                return Err(ForestError::InvalidExport(format!(
                    "instance {i} of variant {} spans past its cache's indices",
                    variant_placements.variant
                )));
            }
            let mut primitives = Vec::new();
            for (view, (start, count), material) in [
                (bark_view, inst.bark, bark_material),
                (leaf_view, inst.leaves, leaf_material),
            ] {
                if let (Some(view), true) = (view, count > 0) {
                    let acc = doc.accessor(
                        view,
                        start as usize * 4,
                        UNSIGNED_INT,
                        count as usize,
                        "SCALAR",
                        None,
                    );
                    primitives.push(json!({ "attributes": attributes.clone(), "indices": acc, "material": material }));
                }
            }
            if primitives.is_empty() {
                continue;
            }
            let transforms = &variant_placements.placements.groups[i];
            let mut t = Vec::with_capacity(transforms.len() * 3);
            let mut r = Vec::with_capacity(transforms.len() * 4);
            let mut s = Vec::with_capacity(transforms.len() * 3);
            for x in transforms {
                let q = x.rotation;
                if !(x.is_finite() && x.scale > 0.0) || (q.length() - 1.0).abs() > 1e-3 {
                    return Err(ForestError::InvalidExport(format!(
                        "placement {x:?} is not a valid TRS transform"
                    )));
                }
                let q = q.normalize();
                t.extend_from_slice(&x.translation.to_array());
                r.extend_from_slice(&q.to_array());
                s.extend_from_slice(&[x.scale; 3]);
            }
            let count = transforms.len();
            if t.len() != 3 * count || r.len() != 4 * count || s.len() != 3 * count {
                return Err(ForestError::InvalidExport(
                    "instancing attributes of unequal counts".into(),
                ));
            }
            let tv = doc.view(bytemuck::cast_slice(&t), None, None);
            let rv = doc.view(bytemuck::cast_slice(&r), None, None);
            let sv = doc.view(bytemuck::cast_slice(&s), None, None);
            let (ta, ra, sa) = (
                doc.accessor(tv, 0, FLOAT, count, "VEC3", None),
                doc.accessor(rv, 0, FLOAT, count, "VEC4", None),
                doc.accessor(sv, 0, FLOAT, count, "VEC3", None),
            );
            doc.meshes.push(json!({ "name": format!("{} {tag} branch {} age {} #{i}", species.name, inst.id, inst.age), "primitives": primitives }));
            doc.nodes.push(json!({
                "name": format!("{} {tag} instance {i}", species.name),
                "mesh": doc.meshes.len() - 1,
                "extensions": { "EXT_mesh_gpu_instancing": { "attributes": { "TRANSLATION": ta, "ROTATION": ra, "SCALE": sa } } }
            }));
            stats.instance_nodes += 1;
            stats.placements += count;
        }
    }
    while !doc.bin.len().is_multiple_of(4) {
        doc.bin.push(0);
    }
    let mut root = json!({
        "asset": { "version": "2.0", "generator": "sylva" },
        "scene": 0,
        "scenes": [{ "nodes": (0..doc.nodes.len()).collect::<Vec<_>>() }],
        "nodes": doc.nodes,
        "meshes": doc.meshes,
        "materials": doc.materials,
        "accessors": doc.accessors,
        "bufferViews": doc.views,
        "buffers": [{ "byteLength": doc.bin.len() }],
    });
    if stats.instance_nodes > 0 {
        root["extensionsUsed"] = json!(["EXT_mesh_gpu_instancing"]);
    }
    if doc.bin.is_empty() {
        root.as_object_mut().map(|o| o.remove("buffers"));
    }
    let mut json_bytes =
        serde_json::to_vec(&root).map_err(|e| ForestError::InvalidExport(e.to_string()))?;
    while !json_bytes.len().is_multiple_of(4) {
        json_bytes.push(b' ');
    }
    let bin_chunk = if doc.bin.is_empty() {
        0
    } else {
        8 + doc.bin.len()
    };
    let total = 12 + 8 + json_bytes.len() + bin_chunk;
    let total32 = u32::try_from(total).map_err(|_| {
        ForestError::InvalidExport(format!("{total} bytes is beyond the 4 GiB a GLB can hold"))
    })?;
    let io = |e: std::io::Error| ForestError::Io {
        path: "glb output".into(),
        message: e.to_string(),
    };
    let mut w = std::io::BufWriter::new(&mut out);
    w.write_all(b"glTF").map_err(io)?;
    w.write_all(&2u32.to_le_bytes()).map_err(io)?;
    w.write_all(&total32.to_le_bytes()).map_err(io)?;
    w.write_all(&(json_bytes.len() as u32).to_le_bytes())
        .map_err(io)?;
    w.write_all(b"JSON").map_err(io)?;
    w.write_all(&json_bytes).map_err(io)?;
    if !doc.bin.is_empty() {
        w.write_all(&(doc.bin.len() as u32).to_le_bytes())
            .map_err(io)?;
        w.write_all(b"BIN\0").map_err(io)?;
        w.write_all(&doc.bin).map_err(io)?;
    }
    w.flush().map_err(io)?;
    stats.bytes = total;
    Ok(stats)
}
