//! One tree's levels of detail as a binary glTF, for engines' LOD groups: a parent node named
//! after the tree with a child per level, `NAME_LOD0` (full detail) to `NAME_LODn` (the
//! impostor's cards), each child's mesh named like it. Unity's and Unreal's importers group
//! children named this way (directly, or with a few lines of import script that read the
//! names); every child carries its level and the distance it is drawn from in `extras`.

use std::path::Path;

use serde_json::json;
use sylva_forest::Species;
use sylva_turtle::Mesh;

use super::in_memory::InMemory;
use super::schema::Node;
use super::shared::TextureSet;
use crate::error::ExportError;

/// Roughness of the pack's materials.
const ROUGHNESS: f32 = 0.9;

/// One level of a tree: its mesh and the distance (metres, at 1080p) it is drawn from.
#[derive(Debug, Clone, Copy)]
pub(crate) struct LodMesh<'a> {
    pub(crate) mesh: &'a Mesh,
    pub(crate) from: f32,
}

/// An impostor as cards: their mesh, the distance they are drawn from, the texture (PNG)
/// their coordinates address and its alpha cutoff.
#[derive(Debug, Clone, Copy)]
pub(crate) struct LodCards<'a> {
    pub(crate) mesh: &'a Mesh,
    pub(crate) from: f32,
    pub(crate) atlas: &'a [u8],
    pub(crate) cutoff: f32,
}

/// Writes `levels` (meshes drawn with `species`' materials) and the impostor's `cards`, if
/// any, as `name` at `path`. Returns the file's size.
pub(crate) fn write_lod_glb(
    name: &str,
    species: &Species,
    levels: &[LodMesh<'_>],
    cards: Option<LodCards<'_>>,
    path: &Path,
) -> Result<usize, ExportError> {
    let mut glb = InMemory::default();
    let textures = TextureSet::of(std::iter::once(species));
    let (bark, leaves) =
        glb.doc
            .species_materials(species, ROUGHNESS, textures.of_species(species));
    // The cards' texture is the last; its material exists only with the cards.
    let atlas_texture = textures.images().len();
    let impostor = cards.map(|c| {
        glb.doc
            .card_material(format!("{name} impostor"), atlas_texture, c.cutoff)
    });
    let mut children = Vec::new();
    let all = levels.iter().map(|l| (l.mesh, l.from, bark, leaves)).chain(
        cards
            .iter()
            .zip(impostor)
            .map(|(c, m)| (c.mesh, c.from, m, m)),
    );
    for (k, (mesh, from, bark, leaves)) in all.enumerate() {
        let primitives = glb.tree(mesh, bark, leaves);
        if primitives.is_empty() {
            continue;
        }
        let child = format!("{name}_LOD{k}");
        let index = glb.doc.mesh(child.clone(), primitives);
        let mut node = Node::of_mesh(child, index);
        node.extras = Some(json!({
            "sylva_lod": k,
            "triangles": mesh.triangle_count(),
            "from_distance_1080p": from,
            "impostor": k == levels.len(),
        }));
        glb.doc.root.nodes.push(node);
        children.push(glb.doc.root.nodes.len() - 1);
    }
    glb.doc.root.nodes.push(Node {
        name: Some(name.to_owned()),
        children,
        ..Node::default()
    });
    let mut views: Vec<(usize, bool)> = textures
        .images()
        .iter()
        .enumerate()
        .map(|(k, png)| (glb.view(png, None, None), k >= textures.first_bark()))
        .collect();
    if let Some(c) = cards {
        views.push((glb.view(c.atlas, None, None), false));
    }
    glb.doc.images(views);
    glb.write(path)
}
