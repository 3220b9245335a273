//! A whole tree of a forest's variant as one mesh: a compact tree assembled from the
//! variant's instance cache, every placed instance's triangles moved to where it stands.

use glam::Vec3;
use sylva_forest::Variant;
use sylva_instancing::{Assembler, CompactTree, InstancingError};
use sylva_turtle::{Mesh, Vertex};

/// The tree of `variant` assembled with `seed`, at the origin, unrotated and unscaled.
///
/// ```
/// use sylva_export::lod::variant_tree;
/// use sylva_forest::{ForestBuilder, ForestConfig, Species};
/// let config = ForestConfig::new(vec![Species::from_preset("sylva-hazel", 3)?])
///     .with_budget(1 << 20);
/// let builder = ForestBuilder::new(config)?;
/// let tree = variant_tree(&builder.variants()[0], 1)?;
/// assert!(tree.triangle_count() > 100);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn variant_tree(variant: &Variant, seed: u32) -> Result<Mesh, InstancingError> {
    let cache = &variant.cache;
    let tree = CompactTree {
        scale: 1.0,
        seed,
        ..CompactTree::default()
    };
    let mut mesh = Mesh::default();
    let mut assembler = Assembler::new();
    assembler.expand_with(cache, &tree, |k, t| {
        let Some(instance) = cache.instances.get(k as usize) else {
            return;
        };
        let rotation = t.rotation;
        let place = |p: [f32; 3]| (t.translation + rotation * (Vec3::from(p) * t.scale)).to_array();
        // The instance's vertices as one run, in the cache's order (coarser levels find the
        // turtle's rings by their layout).
        let bark = cache.bark.get(instance.bark.range()).unwrap_or(&[]);
        let leaves = cache.leaves.get(instance.leaves.range()).unwrap_or(&[]);
        let used = bark.iter().chain(leaves);
        let (Some(&lo), Some(&hi)) = (used.clone().min(), used.max()) else {
            return;
        };
        let Some(run) = cache.vertices.get(lo as usize..=hi as usize) else {
            return;
        };
        let first = mesh.vertices.len() as u32;
        mesh.vertices.extend(run.iter().map(|v| {
            let [x, y, z] = place([v.wind[0], v.wind[1], v.wind[2]]);
            Vertex {
                position: place(v.position),
                normal: (rotation * Vec3::from(v.normal)).to_array(),
                uv: v.uv,
                wind: [x, y, z, v.wind[3]],
            }
        }));
        mesh.bark.extend(bark.iter().map(|&i| i - lo + first));
        mesh.leaves.extend(leaves.iter().map(|&i| i - lo + first));
    })?;
    Ok(mesh)
}
