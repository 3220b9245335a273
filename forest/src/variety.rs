//! Per-tree colour variation: neighbours of one species differ a little in lightness and
//! warmth, as real trees do, while every placement of one tree shares its tint.

use sylva_base::hash::{mix, unit_f32};
use sylva_instancing::CompactTree;

/// A tree's tint: a linear RGB multiplier near 1, a pure function of the tree's seed.
/// Lightness varies by 12 per cent either way and warmth (red against blue) by 8.
///
/// ```
/// use sylva_forest::tree_tint;
/// use sylva_instancing::CompactTree;
/// let tree = CompactTree { seed: 42, ..Default::default() };
/// let tint = tree_tint(&tree);
/// assert_eq!(tint, tree_tint(&tree));
/// assert!(tint.iter().all(|c| (0.8..1.25).contains(c)));
/// ```
pub fn tree_tint(tree: &CompactTree) -> [f32; 3] {
    let h = mix(u64::from(tree.seed) ^ 0x7e11_7a11);
    let light = 0.88 + 0.24 * unit_f32(h);
    let warm = (unit_f32(mix(h)) - 0.5) * 0.16;
    [light * (1.0 + warm), light, light * (1.0 - warm)]
}

/// A tree's wind data, the per-placement half of the wind attributes (the per-vertex half is
/// [`sylva_turtle::Vertex::wind`]): the tree's base (xyz, world space) and a phase in
/// `[0, 1)` (w) drawn from its seed, so neighbours do not sway in step. Every placement of a
/// tree carries the same values, so a wind shader bends the whole tree about its base
/// whichever instances it was assembled from; exports write it as the `_WIND_TREE` instance
/// attribute.
///
/// ```
/// use sylva_forest::tree_wind;
/// use sylva_instancing::CompactTree;
/// let tree = CompactTree { position: [3.0, 1.0, 4.0], seed: 7, ..Default::default() };
/// let wind = tree_wind(&tree);
/// assert_eq!(&wind[..3], &[3.0, 1.0, 4.0]);
/// assert!((0.0..1.0).contains(&wind[3]));
/// ```
pub fn tree_wind(tree: &CompactTree) -> [f32; 4] {
    let [x, y, z] = tree.position;
    [x, y, z, unit_f32(mix(u64::from(tree.seed) ^ 0x3147_d000))]
}
