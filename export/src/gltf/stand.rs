//! A grown stand as a binary glTF: one mesh per tree (grown trees share no geometry, so
//! there is nothing to instance), the terrain, and the species' textures and materials.

use std::path::Path;

use sylva_forest::{GrownStand, Species};
use sylva_terrain::TerrainMesh;
use sylva_turtle::Mesh;

use super::ARRAY_BUFFER;
use super::in_memory::InMemory;
use super::schema::{Attributes, Node, Primitive};
use super::shared::TextureSet;
use crate::error::ExportError;

/// Roughness of the stand's materials but the rock's.
const ROUGHNESS: f32 = 0.9;

/// Writes `stand` (meshed with its `species`' turtle settings) and optionally `terrain` as a
/// binary glTF at `path`: one node per tree, bark with colour and normal textures, leaf cards
/// alpha-masked and double-sided, the same `_WIND` vertex attribute as forests. The file is
/// assembled in memory (a stand is tens of trees) and written under a temporary name, then
/// renamed. Returns the file's size.
pub fn write_stand_glb(
    stand: &GrownStand,
    species: &[Species],
    terrain: Option<&TerrainMesh>,
    path: &Path,
) -> Result<usize, ExportError> {
    let mut glb = InMemory::default();
    if let Some(t) = terrain.filter(|t| !t.indices.is_empty()) {
        let material = glb
            .doc
            .material("terrain".into(), [1.0; 3], ROUGHNESS, (None, None), None);
        glb.terrain(t, material);
    }
    // Obstacles as grey rock, flat-shaded (no normals: clients shade each face flat).
    if !stand.obstacles.is_empty() {
        let rock = glb
            .doc
            .material("rock".into(), [0.35, 0.34, 0.32], 0.95, (None, None), None);
        for (k, (positions, indices)) in stand.obstacles.iter().enumerate() {
            let valid = indices.iter().all(|&i| (i as usize) < positions.len())
                && positions.iter().all(|p| p.is_finite());
            if positions.is_empty() || indices.len() < 3 || !valid {
                continue;
            }
            let points: Vec<[f32; 3]> = positions.iter().map(|p| p.to_array()).collect();
            let view = glb.view(bytemuck::cast_slice(&points), None, Some(ARRAY_BUFFER));
            let position = glb.doc.positions(view, 0, points.iter().copied());
            let whole = indices.len() / 3 * 3;
            let indices = glb.indices(&indices[..whole]);
            let primitive = Primitive {
                attributes: Attributes {
                    position,
                    ..Attributes::default()
                },
                indices,
                material: rock,
            };
            let mesh = glb.doc.mesh(format!("obstacle {k}"), vec![primitive]);
            glb.doc
                .root
                .nodes
                .push(Node::of_mesh(format!("obstacle {k}"), mesh));
        }
    }
    let meshes = stand.meshes(species);
    let meshes: Vec<(usize, &Mesh)> = meshes.iter().map(|(s, m)| (*s, m)).collect();
    trees_document(glb, &meshes, species)?.write(path)
}

/// Writes one tree of `species` (such as [`Species::mesh`] makes) as a binary glTF at `path`:
/// its bark with colour and normal textures and its leaf cards alpha-masked and double-sided,
/// with the `_WIND` vertex attribute of forests, the tree's base at the origin. Returns the
/// file's size.
///
/// ```
/// let oak = sylva_forest::Species::from_preset("sylva-oak", 4)?;
/// let path = std::env::temp_dir().join("sylva-doctest-oak.glb");
/// let bytes = sylva_export::write_tree_glb(&oak, &oak.mesh(4, 1)?, &path)?;
/// assert_eq!(std::fs::metadata(&path).unwrap().len() as usize, bytes);
/// # std::fs::remove_file(&path).ok();
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_tree_glb(species: &Species, mesh: &Mesh, path: &Path) -> Result<usize, ExportError> {
    tree_document(species, mesh)?.write(path)
}

/// The GLB [`write_tree_glb`] writes, as bytes in memory: for a server that sends a tree
/// without a file.
///
/// ```
/// let oak = sylva_forest::Species::from_preset("sylva-oak", 3)?;
/// let glb = sylva_export::tree_glb(&oak, &oak.mesh(3, 1)?)?;
/// assert_eq!(&glb[..4], b"glTF");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn tree_glb(species: &Species, mesh: &Mesh) -> Result<Vec<u8>, ExportError> {
    tree_document(species, mesh)?.into_bytes()
}

/// One tree's document, ready to write.
fn tree_document(species: &Species, mesh: &Mesh) -> Result<InMemory, ExportError> {
    trees_document(
        InMemory::default(),
        &[(0, mesh)],
        std::slice::from_ref(species),
    )
}

/// Adds `meshes` (each with the index of its species in `species`) to `glb`, one node each,
/// with the materials and textures of the species they use.
fn trees_document(
    mut glb: InMemory,
    meshes: &[(usize, &Mesh)],
    species: &[Species],
) -> Result<InMemory, ExportError> {
    // Textures: one per leaf shape and per bark pattern in use, with the barks' normal maps.
    let used: Vec<usize> = {
        let mut u: Vec<usize> = meshes.iter().map(|t| t.0).collect();
        u.sort_unstable();
        u.dedup();
        u
    };
    let mut used_species = Vec::with_capacity(used.len());
    for &s in &used {
        used_species.push(species.get(s).ok_or(ExportError::UnknownSpecies {
            species: s,
            count: species.len(),
        })?);
    }
    let textures = TextureSet::of(used_species.iter().copied());
    let mut species_materials = vec![(0usize, 0usize); species.len()];
    for (&s, sp) in used.iter().zip(&used_species) {
        species_materials[s] = glb
            .doc
            .species_materials(sp, ROUGHNESS, textures.of_species(sp));
    }
    for (k, &(s, mesh)) in meshes.iter().enumerate() {
        let (bark, leaves) = species_materials[s];
        let primitives = glb.tree(mesh, bark, leaves);
        if primitives.is_empty() {
            continue;
        }
        let name = format!("{} {k}", species[s].name);
        let mesh = glb.doc.mesh(name.clone(), primitives);
        glb.doc.root.nodes.push(Node::of_mesh(name, mesh));
    }
    let views: Vec<(usize, bool)> = textures
        .images()
        .iter()
        .enumerate()
        .map(|(k, png)| (glb.view(png, None, None), k >= textures.first_bark()))
        .collect();
    glb.doc.images(views);
    Ok(glb)
}
