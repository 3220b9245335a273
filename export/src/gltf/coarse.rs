//! Coarse tiles as GLB: each canopy tree as its variant's impostor cards (three upright and
//! one level, over the variant's atlas, a PNG beside the tileset) placed once per tree through
//! EXT_mesh_gpu_instancing, over a coarse terrain.

use std::path::Path;

use sylva_forest::{Species, tree_tint};
use sylva_instancing::CompactTree;
use sylva_terrain::TerrainMesh;
use sylva_turtle::Mesh;

use super::FLOAT;
use super::in_memory::InMemory;
use crate::error::ExportError;

/// Roughness of the coarse tiles' materials.
const ROUGHNESS: f32 = 0.9;

/// A variant's impostor in a coarse tile: its cards, its species, the URI (relative to the
/// tile) of the texture their coordinates address, and its alpha cutoff.
#[derive(Debug, Clone)]
pub(crate) struct CoarseImpostor {
    pub(crate) cards: Mesh,
    pub(crate) species: usize,
    pub(crate) atlas: String,
    /// The cards' alpha cutoff.
    pub(crate) cutoff: f32,
}

/// Writes `trees` as instances of `impostors` (one per variant, none for variants not drawn
/// at this distance; a tree's variant picks it), tinted per tree, over `terrain`.
pub(crate) fn write_coarse_glb(
    trees: &[CompactTree],
    impostors: &[Option<CoarseImpostor>],
    species: &[Species],
    terrain: &TerrainMesh,
    path: &Path,
) -> Result<usize, ExportError> {
    let mut glb = InMemory::default();
    if !terrain.indices.is_empty() {
        let material = glb
            .doc
            .material("terrain".into(), [1.0; 3], ROUGHNESS, (None, None), None);
        glb.terrain(terrain, material);
    }
    for (variant, impostor) in impostors.iter().enumerate() {
        let Some(impostor) = impostor else { continue };
        let placed: Vec<&CompactTree> = trees
            .iter()
            .filter(|t| usize::from(t.variant) == variant)
            .collect();
        let Some(sp) = species.get(impostor.species) else {
            continue;
        };
        if placed.is_empty() || impostor.cards.vertices.is_empty() {
            continue;
        }
        let texture = glb.doc.image_file(impostor.atlas.clone());
        let material = glb.doc.card_material(
            format!("{} impostor {variant}", sp.name),
            texture,
            impostor.cutoff,
        );
        let primitives = glb.tree(&impostor.cards, material, material);
        let mesh = glb
            .doc
            .mesh(format!("{} impostor {variant}", sp.name), primitives);
        let (mut t, mut r, mut sc, mut c) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for tree in &placed {
            let root = tree.root();
            t.extend_from_slice(&root.translation.to_array());
            r.extend_from_slice(&root.rotation.normalize().to_array());
            sc.extend_from_slice(&[root.scale; 3]);
            c.extend_from_slice(&tree_tint(tree));
        }
        let n = placed.len();
        let accessors =
            [(&t, "VEC3"), (&r, "VEC4"), (&sc, "VEC3"), (&c, "VEC3")].map(|(data, kind)| {
                let view = glb.view(bytemuck::cast_slice(data), None, None);
                glb.doc.accessor(view, 0, FLOAT, n, kind)
            });
        glb.doc.instanced_node(
            format!("{} impostors {variant}", sp.name),
            mesh,
            accessors,
            None,
        );
    }
    glb.write(path)
}
