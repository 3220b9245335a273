//! Coarse tiles as GLB: whole-tree proxies placed once per tree through
//! EXT_mesh_gpu_instancing, over a coarse terrain.

use std::path::Path;

use serde_json::{Value, json};
use sylva_forest::{Species, tree_tint};
use sylva_instancing::CompactTree;
use sylva_terrain::TerrainMesh;
use sylva_turtle::Mesh;

use super::FLOAT;
use super::json_glb::{Builder, write_glb_file};
use crate::error::ExportError;

/// Writes `trees` as instances of `proxies` (one mesh per variant; a tree's variant picks
/// it), coloured by their species (bark, leaves) and tinted per tree, over `terrain`.
pub(crate) fn write_coarse_glb(
    trees: &[CompactTree],
    proxies: &[(Mesh, usize)],
    species: &[Species],
    terrain: &TerrainMesh,
    path: &Path,
) -> Result<usize, ExportError> {
    let mut b = Builder::default();
    let (mut nodes, mut meshes, mut materials) = (Vec::new(), Vec::new(), Vec::<Value>::new());
    if !terrain.indices.is_empty() {
        materials.push(json!({"name": "terrain", "pbrMetallicRoughness": {"metallicFactor": 0.0, "roughnessFactor": 0.9}}));
        meshes.push(b.terrain(terrain, 0));
        nodes.push(json!({"name": "terrain", "mesh": 0}));
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
        let base = materials.len();
        for (name, colour) in [("trunk", sp.bark), ("crown", sp.leaf)] {
            let [r, g, bl] = colour;
            materials.push(json!({"name": format!("{} proxy {name}", sp.name), "pbrMetallicRoughness": {"baseColorFactor": [r, g, bl, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.9}}));
        }
        let primitives = b.tree(mesh, base, base + 1);
        meshes.push(json!({"name": format!("{} proxy", sp.name), "primitives": primitives}));
        let (mut t, mut r, mut sc, mut c) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for tree in &placed {
            let root = tree.root();
            t.extend_from_slice(&root.translation.to_array());
            r.extend_from_slice(&root.rotation.normalize().to_array());
            sc.extend_from_slice(&[root.scale; 3]);
            c.extend_from_slice(&tree_tint(tree));
        }
        let n = placed.len();
        let mut accessor = |data: &[f32], kind: &str| {
            let view = b.view(bytemuck::cast_slice(data), None, None);
            b.accessor(view, 0, FLOAT, n, kind)
        };
        let attributes = json!({
            "TRANSLATION": accessor(&t, "VEC3"),
            "ROTATION": accessor(&r, "VEC4"),
            "SCALE": accessor(&sc, "VEC3"),
            "_COLOR_0": accessor(&c, "VEC3"),
        });
        nodes.push(json!({
            "name": format!("{} proxies", sp.name),
            "mesh": meshes.len() - 1,
            "extensions": {"EXT_mesh_gpu_instancing": {"attributes": attributes}},
        }));
    }
    let mut doc = b.document(nodes, meshes, materials);
    let instanced = doc["nodes"]
        .as_array()
        .is_some_and(|n| n.iter().any(|n| n.get("extensions").is_some()));
    if instanced {
        doc["extensionsUsed"] = json!(["EXT_mesh_gpu_instancing"]);
    }
    write_glb_file(&doc, &b.bin, path)
}
