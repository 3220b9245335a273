//! A sylva heightmap as a Bevy mesh, with its ground colours by slope and altitude.

use bevy::asset::RenderAssetUsages;
use bevy::mesh::{Indices, PrimitiveTopology};
use bevy::prelude::*;
use sylva::terrain::{Heightmap, TerrainError};

/// `map` as a mesh of every `stride`-th sample (1: every one; it must divide the map's side
/// less one), with normals, texture coordinates and sylva's ground colours as vertex colours:
/// draw it with a `StandardMaterial` to stand the forest on.
pub fn terrain_mesh(map: &Heightmap, stride: usize) -> Result<Mesh, TerrainError> {
    let terrain = map.mesh(stride)?;
    let colours: Vec<[f32; 4]> = terrain
        .ground_colours()
        .into_iter()
        .map(|[r, g, b]| [r, g, b, 1.0])
        .collect();
    Ok(Mesh::new(
        PrimitiveTopology::TriangleList,
        RenderAssetUsages::RENDER_WORLD,
    )
    .with_inserted_attribute(
        Mesh::ATTRIBUTE_POSITION,
        terrain
            .vertices
            .iter()
            .map(|v| v.position)
            .collect::<Vec<_>>(),
    )
    .with_inserted_attribute(
        Mesh::ATTRIBUTE_NORMAL,
        terrain
            .vertices
            .iter()
            .map(|v| v.normal)
            .collect::<Vec<_>>(),
    )
    .with_inserted_attribute(
        Mesh::ATTRIBUTE_UV_0,
        terrain.vertices.iter().map(|v| v.uv).collect::<Vec<_>>(),
    )
    .with_inserted_attribute(Mesh::ATTRIBUTE_COLOR, colours)
    .with_inserted_indices(Indices::U32(terrain.indices)))
}
