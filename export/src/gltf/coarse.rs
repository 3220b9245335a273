//! Coarse tiles as GLB: whole-tree proxies placed once per tree through
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

/// Writes `trees` as instances of `proxies` (one mesh per variant; a tree's variant picks
/// it), coloured by their species (bark, leaves) and tinted per tree, over `terrain`.
pub(crate) fn write_coarse_glb(
    trees: &[CompactTree],
    proxies: &[(Mesh, usize)],
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
    for (variant, (mesh, s)) in proxies.iter().enumerate() {
        let placed: Vec<&CompactTree> = trees
            .iter()
            .filter(|t| usize::from(t.variant) == variant)
            .collect();
        let Some(sp) = species.get(*s) else { continue };
        if placed.is_empty() || mesh.vertices.is_empty() {
            continue;
        }
        let [trunk, crown] = [("trunk", sp.bark), ("crown", sp.leaf)].map(|(part, colour)| {
            let name = format!("{} proxy {part}", sp.name);
            glb.doc
                .material(name, colour, ROUGHNESS, (None, None), None)
        });
        let primitives = glb.tree(mesh, trunk, crown);
        let mesh = glb.doc.mesh(format!("{} proxy", sp.name), primitives);
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
        glb.doc
            .instanced_node(format!("{} proxies", sp.name), mesh, accessors, None);
    }
    glb.write(path)
}
