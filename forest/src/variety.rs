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

/// The mean of [`cluster_shade`]'s lightness: a species' leaf colour divided by it, times the
/// shade, keeps the species' colour on average.
pub const CLUSTER_SHADE_MEAN: f32 = 0.875;

/// A leaf cluster's shade: each leaf card a little lighter or darker, warmer or cooler than
/// its tree's colour, a pure function of the card's wind phase (the fraction of
/// [`sylva_turtle::Vertex::wind`]'s w, distinct per card), so no two neighbouring clusters
/// match. Every channel is in `0.7..=1` (so it fits a normalized colour attribute), the
/// lightness uniform in `0.75..=1` with mean [`CLUSTER_SHADE_MEAN`]; warm clusters lose blue,
/// cool ones red. Exports write it as the leaves' `COLOR_0`, the viewer's shader computes the
/// same.
///
/// ```
/// use sylva_forest::cluster_shade;
/// let shade = cluster_shade(0.3);
/// assert_eq!(shade, cluster_shade(0.3));
/// assert_ne!(shade, cluster_shade(0.31));
/// assert!(shade.iter().all(|c| (0.7..=1.0).contains(c)));
/// ```
pub fn cluster_shade(phase: f32) -> [f32; 3] {
    let fract = |x: f32| x - x.floor();
    let light = 1.0 - 0.25 * fract(phase * 7.31);
    let warm = fract(phase * 13.7);
    [
        light * (0.92 + 0.08 * warm),
        light,
        light * (1.0 - 0.12 * warm),
    ]
}

/// A tree's wind data, the per-placement half of the wind attributes (the per-vertex half is
/// [`sylva_turtle::Vertex::wind`]): the tree's base (xyz, world space) and a phase in
/// `[0, 1)` (w) drawn from its seed, so neighbours do not sway in step. Every placement of a
/// tree carries the same values, so a wind shader bends the whole tree about its base
/// whichever instances it was assembled from; glTF writes it as the `_WIND_TREE` instance
/// attribute (the base as an offset from each placement, `sylva_export::WIND_TREE_REACH`).
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Over many cards the shade's lightness averages [`CLUSTER_SHADE_MEAN`], and it spreads
    /// over its whole range.
    #[test]
    fn cluster_shades_average_their_mean_and_spread() {
        let n = 10_000;
        let greens: Vec<f32> = (0..n)
            .map(|k| cluster_shade(unit_f32(mix(k))))
            .map(|s| s[1])
            .collect();
        let mean = greens.iter().sum::<f32>() / n as f32;
        assert!((mean - CLUSTER_SHADE_MEAN).abs() < 0.01, "{mean}");
        let lo = greens.iter().copied().fold(1.0, f32::min);
        let hi = greens.iter().copied().fold(0.0, f32::max);
        assert!(lo < 0.77 && hi > 0.98, "{lo} {hi}");
    }
}
