//! The forest floor in the viewer: each kind of ground cover as a variant of its own with one
//! group (its whole mesh at three levels of detail), and each fine cell's items as that
//! group's placements. Items are drawn while they span a few pixels, then fade out.

use sylva::export::lod::{LodChain, simplify_mesh};
use sylva::forest::{FloorItem, ForestError, GroundKind};
use sylva::instancing::Span;
use sylva::terrain::glam::{Quat, Vec3};
use sylva::turtle::Mesh;

use crate::geometry::{
    Group, InstanceRaw, MESH_LEVELS, Proxy, VariantGeometry, VariantLod, bounding_sphere,
};

/// Floor items smaller on screen than this many pixels are faded out: the error of their
/// last level is their size over this many pixels' worth of the allowed error.
const MIN_FLOOR_PIXELS: f32 = 5.0;

/// The floor's kinds as the viewer draws them: a variant, a group, levels and an empty proxy
/// (no impostor) each.
pub(crate) struct FloorParts {
    pub(crate) variants: Vec<VariantGeometry>,
    pub(crate) groups: Vec<Group>,
    pub(crate) lods: Vec<VariantLod>,
    pub(crate) proxies: Vec<Proxy>,
}

/// Every kind of ground cover at full detail and at `chain`'s levels, numbered after
/// `first_variant` variants.
pub(crate) fn floor_parts(
    chain: &LodChain,
    first_variant: usize,
) -> Result<FloorParts, ForestError> {
    let mut parts = FloorParts {
        variants: Vec::new(),
        groups: Vec::new(),
        lods: Vec::new(),
        proxies: Vec::new(),
    };
    for (k, kind) in GroundKind::ALL.into_iter().enumerate() {
        let full = kind.mesh()?;
        let meshes: Vec<Mesh> = std::iter::once(full.clone())
            .chain(chain.levels.iter().map(|l| simplify_mesh(&full, l)))
            .collect();
        // The levels one after another in one vertex and one index buffer per material.
        let (mut vertices, mut bark, mut leaves) = (Vec::new(), Vec::new(), Vec::new());
        let mut levels = [(Span::default(), Span::default()); MESH_LEVELS];
        for (level, mesh) in meshes.iter().enumerate().take(MESH_LEVELS) {
            let base = vertices.len() as u32;
            vertices.extend_from_slice(&mesh.vertices);
            let b = Span::new(bark.len() as u32, mesh.bark.len() as u32);
            let l = Span::new(leaves.len() as u32, mesh.leaves.len() as u32);
            bark.extend(mesh.bark.iter().map(|i| i + base));
            leaves.extend(mesh.leaves.iter().map(|i| i + base));
            levels[level] = (b, l);
        }
        let look = kind.look();
        let (centre, radius) =
            bounding_sphere(full.vertices.iter().map(|v| Vec3::from(v.position)));
        let card = if look.cards { 0.15 } else { 0.0 };
        let error = |l: usize| {
            chain
                .levels
                .get(l)
                .map_or(0.0, |x| x.bark_error.max(x.leaf_error(card)))
        };
        let fade = kind.size() * chain.pixel_error / MIN_FLOOR_PIXELS;
        parts.lods.push(VariantLod {
            errors: [error(0), error(1).max(error(0)), fade.max(error(1))],
        });
        parts.groups.push(Group {
            variant: first_variant + k,
            levels,
            // Room for the sway and the items' scale.
            sphere: (centre, radius * 1.3 + 0.2),
        });
        parts.variants.push(VariantGeometry {
            vertices,
            bark,
            leaves,
            bark_colour: look.bark,
            leaf_colour: look.leaf,
            leaf_shape: look.leaf_shape,
            bark_pattern: look.bark_pattern,
            textured_leaves: look.cards,
            phenology: None,
        });
        parts.proxies.push(Proxy::none());
    }
    Ok(parts)
}

/// An item as the vertex shader reads a placement: its own base and phase for the wind, a
/// shade of its own.
pub(crate) fn instance(item: &FloorItem) -> InstanceRaw {
    let [x, y, z] = item.position;
    let shade = 0.85 + 0.3 * item.phase;
    InstanceRaw {
        rotation: Quat::from_rotation_y(item.yaw).to_array(),
        translation_scale: [x, y, z, item.scale],
        tint: [shade, shade, 0.9 + 0.2 * item.phase, 0.0],
        tree: [x, y, z, item.phase],
    }
}

#[cfg(test)]
mod tests {
    use crate::cell::{CellKey, Level};
    use crate::world::{SceneOptions, World};

    /// A fine cell carries floor items in the floor's groups, every one standing in the
    /// cell; without the floor there are none.
    #[test]
    fn fine_cells_carry_the_floor() {
        let world = World::build(SceneOptions::small(5, 200.0)).expect("world");
        let first = world.first_floor_group.expect("a floor") as usize;
        let key = CellKey {
            x: 0,
            z: 0,
            level: Level::Fine,
        };
        let cell = world.cell(key).expect("cell");
        let rect = key.rect(world.side);
        let items: Vec<_> = (first..world.groups.len())
            .flat_map(|k| cell.placements.run(k).iter())
            .collect();
        assert!(items.len() > 1000, "{}", items.len());
        for i in &items {
            let [x, _, z, _] = i.translation_scale;
            assert!(rect.contains(sylva::terrain::glam::Vec2::new(x, z)));
        }
        let bare = World::build(SceneOptions {
            floor: false,
            ..SceneOptions::small(5, 200.0)
        })
        .expect("world");
        assert!(bare.first_floor_group.is_none());
        assert_eq!(bare.groups.len(), first);
    }
}
