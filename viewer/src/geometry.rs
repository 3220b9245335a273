//! The geometry every placement refers to, as the GPU takes it: a placement's layout, a
//! variant's shared buffers, the groups drawn instanced per level of detail, the impostor
//! cards, and the spheres culling tests.

use bytemuck::{Pod, Zeroable};
use sylva::export::lod::{Impostor, LodChain};
use sylva::forest::{BarkPattern, LeafShape, Phenology};
use sylva::instancing::Span;
use sylva::terrain::glam::{Quat, Vec3};
use sylva::turtle::Vertex;

/// One placement as the vertex shader reads it: rotation, then translation and scale.
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
pub(crate) struct InstanceRaw {
    pub(crate) rotation: [f32; 4],
    pub(crate) translation_scale: [f32; 4],
    /// The tree's tint (`sylva_forest::tree_tint`), and 1.
    pub(crate) tint: [f32; 4],
    /// The tree's base and wind phase (`sylva_forest::tree_wind`).
    pub(crate) tree: [f32; 4],
}

impl InstanceRaw {
    /// The base of the tree it belongs to, where its level of detail is measured from.
    pub(crate) fn base(&self) -> Vec3 {
        Vec3::new(self.tree[0], self.tree[1], self.tree[2])
    }
}

/// One species variant's shared buffers: the cache's vertices (and its coarser levels' grown
/// leaf cards), and every level's bark and leaf triangles one after another.
#[derive(Clone)]
pub(crate) struct VariantGeometry {
    pub(crate) vertices: Vec<Vertex>,
    pub(crate) bark: Vec<u32>,
    pub(crate) leaves: Vec<u32>,
    pub(crate) bark_colour: [f32; 3],
    pub(crate) leaf_colour: [f32; 3],
    pub(crate) leaf_shape: LeafShape,
    pub(crate) bark_pattern: BarkPattern,
    /// Whether its leaves are textured cards (grass blades are plain triangles).
    pub(crate) textured_leaves: bool,
    /// Its species' year, which the shader plays (`None`: the forest floor's plants, which
    /// keep their look).
    pub(crate) phenology: Option<Phenology>,
}

/// Levels of detail drawn from meshes: the full cache and its two coarser levels.
pub(crate) const MESH_LEVELS: usize = 3;

/// One cached instance drawn with its placements: one instanced draw per level and non-empty
/// index range. Its placements live in the streamed cells.
#[derive(Clone)]
pub(crate) struct Group {
    pub(crate) variant: usize,
    /// Per level of detail, its bark and leaf triangles in the variant's buffers.
    pub(crate) levels: [(Span, Span); MESH_LEVELS],
    /// A sphere around the instance's triangles in its own space (centre, radius), with room
    /// for the wind's sway.
    pub(crate) sphere: (Vec3, f32),
}

/// A variant's impostor card, drawn for trees far from the camera: a quad of corners
/// `(±1, ±1)` that the impostor shader turns to face the camera, whose vertices carry the
/// atlas (normal: the centre of the sphere the views frame; wind: atlas number, views per
/// side, the sphere's radius and the variant's bark material). Empty for variants without an
/// impostor (seedlings, which are not drawn that far).
#[derive(Clone)]
pub(crate) struct Proxy {
    pub(crate) vertices: Vec<Vertex>,
    pub(crate) bark: Vec<u32>,
    pub(crate) leaves: Vec<u32>,
    /// A sphere around it in the tree's own space (centre, radius).
    pub(crate) sphere: (Vec3, f32),
}

/// When a variant's coarser levels are drawn: each level's error in metres (level 1, level 2,
/// the impostor; infinite for a variant without one), turned into distances by the view's
/// pixels per radian.
#[derive(Debug, Clone, Copy)]
pub(crate) struct VariantLod {
    pub(crate) errors: [f32; MESH_LEVELS],
}

/// The levels of detail the viewer draws: `LodChain`'s defaults, with impostors of 8 x 8 views
/// of 96 pixels (the viewer's 720p needs less than 1080p's 128).
pub(crate) fn lod_chain() -> LodChain {
    let mut chain = LodChain::default();
    chain.impostor = chain.impostor.with_view_size(96);
    chain
}

impl Proxy {
    /// Nothing: a variant with no impostor.
    pub(crate) fn none() -> Proxy {
        Proxy {
            vertices: Vec::new(),
            bark: Vec::new(),
            leaves: Vec::new(),
            sphere: (Vec3::ZERO, -1.0),
        }
    }

    /// The card of `impostor`, atlas number `number`; its bark material is filled in by the
    /// renderer, which knows the materials.
    pub(crate) fn card(impostor: &Impostor, number: f32) -> Proxy {
        let vertex = |x: f32, y: f32| Vertex {
            position: [x, y, 0.0],
            normal: impostor.centre,
            uv: [0.5 * x + 0.5, 0.5 - 0.5 * y],
            wind: [number, impostor.grid as f32, impostor.radius, 0.0],
        };
        Proxy {
            vertices: vec![
                vertex(-1.0, -1.0),
                vertex(1.0, -1.0),
                vertex(1.0, 1.0),
                vertex(-1.0, 1.0),
            ],
            bark: Vec::new(),
            leaves: vec![0, 1, 2, 0, 2, 3],
            sphere: (Vec3::from(impostor.centre), impostor.radius),
        }
    }
}

/// A sphere given in an instance's own space, placed in the world by the instance.
pub(crate) fn world_sphere(i: &InstanceRaw, (centre, radius): (Vec3, f32)) -> (Vec3, f32) {
    let [x, y, z, scale] = i.translation_scale;
    let rotation = Quat::from_array(i.rotation);
    (
        Vec3::new(x, y, z) + rotation * (centre * scale),
        radius * scale,
    )
}

/// A bounding sphere in an instance's own space, as (centre, radius).
pub(crate) fn bounding_sphere(points: impl Iterator<Item = Vec3>) -> (Vec3, f32) {
    let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
    let mut all = Vec::new();
    for p in points {
        lo = lo.min(p);
        hi = hi.max(p);
        all.push(p);
    }
    if all.is_empty() {
        return (Vec3::ZERO, 0.0);
    }
    let centre = (lo + hi) * 0.5;
    let radius = all
        .iter()
        .map(|p| p.distance(centre))
        .fold(0.0f32, f32::max);
    (centre, radius)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sphere_holds_every_point() {
        let points = [
            Vec3::ZERO,
            Vec3::new(4.0, 1.0, 0.0),
            Vec3::new(-1.0, 6.0, 2.0),
        ];
        let (c, r) = bounding_sphere(points.into_iter());
        assert!(points.iter().all(|p| p.distance(c) <= r + 1e-5));
    }
}
