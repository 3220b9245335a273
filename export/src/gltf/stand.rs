//! A grown stand as a binary glTF: one mesh per tree (grown trees share no geometry, so
//! there is nothing to instance), the terrain, and the species' textures and materials.

use std::path::Path;

use serde_json::{Value, json};
use sylva_forest::{BarkPattern, GrownStand, LeafShape, Species};
use sylva_terrain::TerrainMesh;

use super::json_glb::{Builder, write_glb_file};
use super::{ARRAY_BUFFER, FLOAT, position_bounds};
use crate::error::ExportError;
use crate::texture::Texture;

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
    let mut b = Builder::default();
    let mut nodes = Vec::new();
    let mut meshes = Vec::new();
    let mut materials = Vec::new();
    if let Some(t) = terrain.filter(|t| !t.indices.is_empty()) {
        materials.push(json!({"name": "terrain", "pbrMetallicRoughness": {"metallicFactor": 0.0, "roughnessFactor": 0.9}}));
        meshes.push(b.terrain(t, 0));
        nodes.push(json!({"name": "terrain", "mesh": 0}));
    }
    // Obstacles as grey rock, flat-shaded (no normals: clients shade each face flat).
    if !stand.obstacles.is_empty() {
        materials.push(json!({"name": "rock", "pbrMetallicRoughness": {"baseColorFactor": [0.35, 0.34, 0.32, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.95}}));
        let rock = materials.len() - 1;
        for (k, (positions, indices)) in stand.obstacles.iter().enumerate() {
            let valid = indices.iter().all(|&i| (i as usize) < positions.len())
                && positions.iter().all(|p| p.is_finite());
            if positions.is_empty() || indices.len() < 3 || !valid {
                continue;
            }
            let points: Vec<[f32; 3]> = positions.iter().map(|p| p.to_array()).collect();
            let view = b.view(bytemuck::cast_slice(&points), None, Some(ARRAY_BUFFER));
            let position = b.accessor(view, 0, FLOAT, points.len(), "VEC3");
            let (lo, hi, _) = position_bounds(points.iter().copied());
            b.accessors[position]["min"] = json!(lo);
            b.accessors[position]["max"] = json!(hi);
            let whole = indices.len() / 3 * 3;
            let acc = b.indices(&indices[..whole]);
            meshes.push(json!({"name": format!("obstacle {k}"), "primitives": [{"attributes": {"POSITION": position}, "indices": acc, "material": rock}]}));
            nodes.push(json!({"name": format!("obstacle {k}"), "mesh": meshes.len() - 1}));
        }
    }
    // Textures: one per leaf shape and per bark pattern in use, with the barks' normal maps.
    let used: Vec<usize> = {
        let mut u: Vec<usize> = stand.trees.iter().map(|t| t.0).collect();
        u.sort_unstable();
        u.dedup();
        u
    };
    let mut images: Vec<Vec<u8>> = Vec::new();
    let mut textures = Vec::new();
    let mut texture_of = |image: Vec<u8>, tiled: bool, images: &mut Vec<Vec<u8>>| {
        images.push(image);
        textures.push(json!({"sampler": usize::from(tiled), "source": images.len() - 1}));
        textures.len() - 1
    };
    let mut leaf_textures: Vec<(LeafShape, usize)> = Vec::new();
    let mut bark_textures: Vec<(BarkPattern, usize, usize)> = Vec::new();
    let mut species_materials = vec![(0usize, 0usize); species.len()];
    for &s in &used {
        let sp = species.get(s).ok_or(ExportError::UnknownSpecies {
            species: s,
            count: species.len(),
        })?;
        let leaf = match leaf_textures.iter().find(|l| l.0 == sp.leaf_shape) {
            Some(l) => l.1,
            None => {
                let t = texture_of(Texture::leaf(sp.leaf_shape).png(), false, &mut images);
                leaf_textures.push((sp.leaf_shape, t));
                t
            }
        };
        let (colour, normal) = match bark_textures.iter().find(|t| t.0 == sp.bark_pattern) {
            Some(t) => (t.1, t.2),
            None => {
                let c = texture_of(Texture::bark(sp.bark_pattern).png(), true, &mut images);
                let n = texture_of(
                    Texture::bark_normal(sp.bark_pattern).png(),
                    true,
                    &mut images,
                );
                bark_textures.push((sp.bark_pattern, c, n));
                (c, n)
            }
        };
        let [r, g, bl] = sp.bark;
        materials.push(json!({
            "name": format!("{} bark", sp.name),
            "pbrMetallicRoughness": {"baseColorFactor": [r, g, bl, 1.0], "baseColorTexture": {"index": colour}, "metallicFactor": 0.0, "roughnessFactor": 0.9},
            "normalTexture": {"index": normal},
        }));
        let [r, g, bl] = sp.leaf;
        materials.push(json!({
            "name": format!("{} leaves", sp.name),
            "pbrMetallicRoughness": {"baseColorFactor": [r, g, bl, 1.0], "baseColorTexture": {"index": leaf}, "metallicFactor": 0.0, "roughnessFactor": 0.9},
            "alphaMode": "MASK", "alphaCutoff": 0.5, "doubleSided": true,
        }));
        species_materials[s] = (materials.len() - 2, materials.len() - 1);
    }
    for (k, (s, mesh)) in stand.meshes(species).iter().enumerate() {
        let (bark, leaves) = species_materials[*s];
        let primitives = b.tree(mesh, bark, leaves);
        if primitives.is_empty() {
            continue;
        }
        meshes.push(json!({"name": format!("{} {k}", species[*s].name), "primitives": primitives}));
        nodes.push(json!({"name": format!("{} {k}", species[*s].name), "mesh": meshes.len() - 1}));
    }
    let image_views: Vec<Value> = images
        .iter()
        .map(|png| json!({"bufferView": b.view(png, None, None), "mimeType": "image/png"}))
        .collect();
    let mut doc = b.document(nodes, meshes, materials);
    if !image_views.is_empty() {
        doc["images"] = json!(image_views);
        doc["textures"] = json!(textures);
        doc["samplers"] = json!([
            {"magFilter": 9729, "minFilter": 9987, "wrapS": 33071, "wrapT": 33071},
            {"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 10497},
        ]);
    }
    write_glb_file(&doc, &b.bin, path)
}
