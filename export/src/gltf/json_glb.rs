//! Small GLB files assembled in memory with serde_json: grown stands and the coarse tiles of a
//! world (tens of meshes, where the streamed writer serves millions of placements).

use std::path::Path;

use serde_json::{Value, json};
use sylva_turtle::{Mesh, Vertex};

use super::document::padding;
use super::tangent::tangents;
use sylva_base::file::AtomicFile;

use super::{ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER, FLOAT, UNSIGNED_INT, glb_header, position_bounds};
use crate::error::{ExportError, Invalid};

/// The binary buffer and the JSON arrays that point into it.
#[derive(Debug, Default)]
pub(super) struct Builder {
    pub(super) bin: Vec<u8>,
    pub(super) views: Vec<Value>,
    pub(super) accessors: Vec<Value>,
}

impl Builder {
    /// Appends `bytes` (padded to a word) as a buffer view.
    pub(super) fn view(
        &mut self,
        bytes: &[u8],
        stride: Option<usize>,
        target: Option<u32>,
    ) -> usize {
        let mut v = json!({"buffer": 0, "byteOffset": self.bin.len(), "byteLength": bytes.len()});
        if let Some(s) = stride {
            v["byteStride"] = json!(s);
        }
        if let Some(t) = target {
            v["target"] = json!(t);
        }
        self.bin.extend_from_slice(bytes);
        self.bin.resize(self.bin.len() + padding(bytes.len()), 0);
        self.views.push(v);
        self.views.len() - 1
    }

    pub(super) fn accessor(
        &mut self,
        view: usize,
        offset: usize,
        component: u32,
        count: usize,
        kind: &str,
    ) -> usize {
        self.accessors.push(json!({
            "bufferView": view, "byteOffset": offset, "componentType": component,
            "count": count, "type": kind,
        }));
        self.accessors.len() - 1
    }

    /// Position (with bounds), normal and uv accessors over `vertices` of `stride` bytes.
    pub(super) fn attributes(
        &mut self,
        view: usize,
        positions: impl IntoIterator<Item = [f32; 3]>,
    ) -> Value {
        let (lo, hi, n) = position_bounds(positions);
        let position = self.accessor(view, 0, FLOAT, n, "VEC3");
        self.accessors[position]["min"] = json!(lo);
        self.accessors[position]["max"] = json!(hi);
        let normal = self.accessor(view, 12, FLOAT, n, "VEC3");
        let uv = self.accessor(view, 24, FLOAT, n, "VEC2");
        json!({"POSITION": position, "NORMAL": normal, "TEXCOORD_0": uv})
    }

    pub(super) fn indices(&mut self, indices: &[u32]) -> Option<usize> {
        (!indices.is_empty()).then(|| {
            let view = self.view(
                bytemuck::cast_slice(indices),
                None,
                Some(ELEMENT_ARRAY_BUFFER),
            );
            self.accessor(view, 0, UNSIGNED_INT, indices.len(), "SCALAR")
        })
    }

    /// A tree mesh's primitives: bark and leaves over one vertex buffer with wind data and
    /// tangents.
    pub(super) fn tree(&mut self, mesh: &Mesh, bark: usize, leaves: usize) -> Vec<Value> {
        if mesh.vertices.is_empty() {
            return Vec::new();
        }
        let stride = size_of::<Vertex>();
        let view = self.view(
            bytemuck::cast_slice(&mesh.vertices),
            Some(stride),
            Some(ARRAY_BUFFER),
        );
        let mut attributes = self.attributes(view, mesh.vertices.iter().map(|v| v.position));
        let wind = self.accessor(view, 32, FLOAT, mesh.vertices.len(), "VEC4");
        let t = tangents(&mesh.vertices, &mesh.bark);
        let tview = self.view(bytemuck::cast_slice(&t), None, Some(ARRAY_BUFFER));
        let tangent = self.accessor(tview, 0, FLOAT, t.len(), "VEC4");
        attributes["_WIND"] = json!(wind);
        attributes["TANGENT"] = json!(tangent);
        let mut primitives = Vec::new();
        for (indices, material) in [(&mesh.bark, bark), (&mesh.leaves, leaves)] {
            if let Some(acc) = self.indices(indices) {
                primitives
                    .push(json!({"attributes": attributes, "indices": acc, "material": material}));
            }
        }
        primitives
    }
}

impl Builder {
    /// The glTF JSON of one scene holding every node, with the arrays built so far; the
    /// binary chunk is `self.bin`.
    pub(super) fn document(
        &self,
        nodes: Vec<Value>,
        meshes: Vec<Value>,
        materials: Vec<Value>,
    ) -> Value {
        json!({
            "asset": {"version": "2.0", "generator": "sylva"},
            "scene": 0,
            "scenes": [{"nodes": (0..nodes.len()).collect::<Vec<_>>()}],
            "nodes": nodes,
            "meshes": meshes,
            "materials": materials,
            "accessors": self.accessors,
            "bufferViews": self.views,
            "buffers": [{"byteLength": self.bin.len()}],
        })
    }

    /// The terrain as a mesh of one primitive with its ground colours (`COLOR_0`), drawn with
    /// `material`: the JSON of the mesh.
    pub(super) fn terrain(
        &mut self,
        terrain: &sylva_terrain::TerrainMesh,
        material: usize,
    ) -> Value {
        let view = self.view(
            bytemuck::cast_slice(&terrain.vertices),
            Some(32),
            Some(ARRAY_BUFFER),
        );
        let mut attributes = self.attributes(view, terrain.vertices.iter().map(|v| v.position));
        let colours = terrain.ground_colours();
        let cview = self.view(bytemuck::cast_slice(&colours), None, Some(ARRAY_BUFFER));
        attributes["COLOR_0"] = json!(self.accessor(cview, 0, FLOAT, colours.len(), "VEC3"));
        let indices = self.indices(&terrain.indices);
        json!({"name": "terrain", "primitives": [{"attributes": attributes, "indices": indices, "material": material}]})
    }
}

/// Writes the glTF JSON `doc` and the binary chunk `bin` as a GLB at `path`, whole or not at
/// all. Returns the file's size.
pub(super) fn write_glb_file(doc: &Value, bin: &[u8], path: &Path) -> Result<usize, ExportError> {
    let mut text = serde_json::to_string(doc).map_err(|e| Invalid::Json(e.to_string()))?;
    while !text.len().is_multiple_of(4) {
        text.push(' ');
    }
    let total = 12 + 8 + text.len() + 8 + bin.len();
    let header = glb_header(total, &text, Some(bin.len()))?;
    let mut file = AtomicFile::create(path)?;
    file.put(&header)?;
    file.put(bin)?;
    file.commit()?;
    Ok(total)
}
