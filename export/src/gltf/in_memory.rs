//! Small GLB files assembled in memory: grown stands and the coarse tiles of a world (tens of
//! meshes, where the streamed writer serves millions of placements). The document is built by
//! the same [`DocumentBuilder`] as the streamed writer's; the bytes follow each view.

use std::path::Path;

use sylva_base::file::AtomicFile;
use sylva_terrain::TerrainMesh;
use sylva_turtle::Mesh;

use super::builder::{DocumentBuilder, TreeViews, padding};
use super::extras::VertexLayout;
use super::indices::IndexWidth;
use super::schema::Primitive;
use super::{ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER, glb_header};
use crate::error::ExportError;

/// A document and its binary buffer, growing together.
#[derive(Debug, Default)]
pub(super) struct InMemory {
    pub(super) doc: DocumentBuilder,
    bin: Vec<u8>,
}

impl InMemory {
    /// Appends `bytes` (padded to a word) as a buffer view.
    pub(super) fn view(&mut self, bytes: &[u8], stride: Option<u32>, target: Option<u32>) -> usize {
        let view = self.doc.view(bytes.len(), stride, target);
        self.bin.extend_from_slice(bytes);
        self.bin.resize(self.bin.len() + padding(bytes.len()), 0);
        view
    }

    /// An index view of `indices` and its accessor, none when empty.
    pub(super) fn indices(&mut self, indices: &[u32]) -> Option<usize> {
        (!indices.is_empty()).then(|| {
            let view = self.view(
                bytemuck::cast_slice(indices),
                None,
                Some(ELEMENT_ARRAY_BUFFER),
            );
            self.doc.indices(view, 0, (IndexWidth::Int, indices.len()))
        })
    }

    /// A tree mesh's primitives: bark and leaves over one vertex buffer with wind data and
    /// tangents, none for a mesh without vertices. Float normals and tangents
    /// ([`VertexLayout::Float`]): one tree's file is for any importer.
    pub(super) fn tree(&mut self, mesh: &Mesh, bark: usize, leaves: usize) -> Vec<Primitive> {
        if mesh.vertices.is_empty() {
            return Vec::new();
        }
        let layout = VertexLayout::Float;
        let vertices = self.view(
            &layout.vertices(&mesh.vertices),
            Some(layout.vertex_bytes() as u32),
            Some(ARRAY_BUFFER),
        );
        let extras = layout.extras(&mesh.vertices, &mesh.bark, &mesh.leaves);
        let views = TreeViews {
            vertices,
            extras: self.view(
                &extras,
                Some(layout.extras_bytes() as u32),
                Some(ARRAY_BUFFER),
            ),
            bark: None,
            leaves: None,
        };
        let positions = mesh.vertices.iter().map(|v| v.position);
        let attributes = self.doc.tree_attributes(views, positions, layout);
        let mut primitives = Vec::new();
        for (indices, material) in [(&mesh.bark, bark), (&mesh.leaves, leaves)] {
            if let Some(indices) = self.indices(indices) {
                primitives.push(Primitive {
                    attributes,
                    indices: Some(indices),
                    material,
                });
            }
        }
        primitives
    }

    /// The terrain's mesh and node, with its ground colours, drawn with `material`.
    pub(super) fn terrain(&mut self, terrain: &TerrainMesh, material: usize) {
        let vertices = self.view(
            bytemuck::cast_slice(&terrain.vertices),
            Some(32),
            Some(ARRAY_BUFFER),
        );
        let index_view = (!terrain.indices.is_empty()).then(|| {
            self.view(
                bytemuck::cast_slice(&terrain.indices),
                None,
                Some(ELEMENT_ARRAY_BUFFER),
            )
        });
        let colours = terrain.ground_colours();
        let colour_view = self.view(bytemuck::cast_slice(&colours), None, Some(ARRAY_BUFFER));
        self.doc.terrain(
            vertices,
            terrain.vertices.iter().map(|v| v.position),
            (index_view, (IndexWidth::Int, terrain.indices.len())),
            (colour_view, colours.len()),
            material,
        );
    }

    /// Writes the document and its buffer as a GLB at `path`, whole or not at all. Returns
    /// the file's size.
    pub(super) fn write(self, path: &Path) -> Result<usize, ExportError> {
        let (header, bin) = self.chunks()?;
        let mut file = AtomicFile::create(path)?;
        file.put(&header)?;
        file.put(&bin)?;
        file.commit()?;
        Ok(header.len() + bin.len())
    }

    /// The document and its buffer as one GLB in memory.
    pub(super) fn into_bytes(self) -> Result<Vec<u8>, ExportError> {
        let (mut header, bin) = self.chunks()?;
        header.extend_from_slice(&bin);
        Ok(header)
    }

    /// The GLB's header and JSON chunk, and its buffer (the BIN chunk's payload).
    fn chunks(mut self) -> Result<(Vec<u8>, Vec<u8>), ExportError> {
        self.doc.own_buffer(0);
        let text = self.doc.into_json()?;
        // No BIN chunk when there is nothing to put in it.
        let bin = (!self.bin.is_empty()).then_some(self.bin.len());
        let total = 12 + 8 + text.len() + bin.map_or(0, |len| 8 + len);
        let header = glb_header(total, &text, bin)?;
        Ok((header, self.bin))
    }
}
