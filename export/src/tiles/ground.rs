//! The terrain of one tile: a grid mesh over the tile's rectangle, sampled from the world's
//! height field, so that neighbouring tiles meet edge to edge.

use glam::Vec2;
use sylva_forest::Rect;
use sylva_terrain::{HeightField, TerrainMesh, TerrainVertex};

/// A mesh of `cells` x `cells` quads over `rect`, heights and normals from `terrain`, uv
/// across `world`.
pub(crate) fn tile_terrain(
    terrain: &dyn HeightField,
    rect: Rect,
    cells: u32,
    world: Rect,
) -> TerrainMesh {
    let n = cells.max(1);
    let size = rect.max - rect.min;
    let world_size = (world.max - world.min).max(Vec2::splat(1e-3));
    let mut vertices = Vec::with_capacity(((n + 1) * (n + 1)) as usize);
    for j in 0..=n {
        for i in 0..=n {
            let p = rect.min + size * Vec2::new(i as f32, j as f32) / n as f32;
            let uv = (p - world.min) / world_size;
            vertices.push(TerrainVertex {
                position: [p.x, terrain.height(p.x, p.y), p.y],
                normal: terrain.normal(p.x, p.y).to_array(),
                uv: uv.to_array(),
            });
        }
    }
    let mut indices = Vec::with_capacity((n * n * 6) as usize);
    for j in 0..n {
        for i in 0..n {
            let a = j * (n + 1) + i;
            let (b, c, d) = (a + 1, a + n + 1, a + n + 2);
            // Counter-clockwise seen from above (+y).
            indices.extend_from_slice(&[a, c, b, b, c, d]);
        }
    }
    TerrainMesh { vertices, indices }
}

/// The lowest and highest ground over `rect`, sampled on a 17 x 17 lattice.
pub(crate) fn height_range(terrain: &dyn HeightField, rect: Rect) -> (f32, f32) {
    let mut range = (f32::INFINITY, f32::NEG_INFINITY);
    for j in 0..=16 {
        for i in 0..=16 {
            let p = rect.min + (rect.max - rect.min) * Vec2::new(i as f32, j as f32) / 16.0;
            let h = terrain.height(p.x, p.y);
            if h.is_finite() {
                range = (range.0.min(h), range.1.max(h));
            }
        }
    }
    if range.0 > range.1 { (0.0, 0.0) } else { range }
}
