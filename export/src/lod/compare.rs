//! How far a coarser mesh's silhouette is from the full one's: both drawn from the same
//! directions, their covered pixels compared.

use glam::Vec3;
use sylva_turtle::Mesh;

use super::raster::{OrthoView, TreeLook, draw};
use super::simplify::LodLevel;

/// One direction's comparison of two silhouettes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SilhouetteMatch {
    /// The direction both were seen from.
    pub toward: Vec3,
    /// Pixels the coarse mesh covers over those the full one covers.
    pub coverage_ratio: f32,
    /// Pixels both cover over pixels either covers (intersection over union).
    pub overlap: f32,
}

/// `coarse` against `full`, seen from each of `directions` in pictures of `size` pixels that
/// frame `full`, with `look`'s textures cutting the cards as a client's alpha test does.
///
/// ```
/// use sylva_export::lod::{LodLevel, TreeLook, compare_silhouettes, simplify_mesh};
/// use glam::Vec3;
/// let mut species = sylva_forest::Species::from_preset("sylva-birch", 5)?;
/// // The species file's leaves: the apices drawn as leaf cards.
/// species.turtle.symbols.set("L", sylva_turtle::Command::Leaf);
/// let full = species.mesh(5, 1)?;
/// let coarse = simplify_mesh(&full, &LodLevel { bark_error: 0.03, leaf_keep: 0.5, leaf_growth: None });
/// for m in compare_silhouettes(&full, &coarse, &TreeLook::of(&species), &[Vec3::X, Vec3::Y], 128) {
///     assert!(m.overlap > 0.5 && m.coverage_ratio > 0.7, "{m:?}");
/// }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn compare_silhouettes(
    full: &Mesh,
    coarse: &Mesh,
    look: &TreeLook,
    directions: &[Vec3],
    size: u32,
) -> Vec<SilhouetteMatch> {
    let Some((lo, hi)) = full.bounds() else {
        return Vec::new();
    };
    directions
        .iter()
        .map(|&d| {
            let view = OrthoView {
                centre: (lo + hi) * 0.5,
                toward: d.normalize_or(Vec3::Z),
                half: 0.5 * (hi - lo).length(),
                size,
            };
            let (a, b) = (draw(full, look, &view), draw(coarse, look, &view));
            let (mut both, mut either) = (0usize, 0usize);
            for (x, y) in a.coverage.iter().zip(&b.coverage) {
                let (x, y) = (*x >= 0.5, *y >= 0.5);
                both += usize::from(x && y);
                either += usize::from(x || y);
            }
            SilhouetteMatch {
                toward: view.toward,
                coverage_ratio: b.covered() as f32 / a.covered().max(1) as f32,
                overlap: both as f32 / either.max(1) as f32,
            }
        })
        .collect()
}

/// `level` with its cards' growth chosen so that `full` drawn at that level covers as much as
/// at full detail, on average from the side (two directions) and from above: the cards
/// left overlap less than the full set, so they need to grow less than their area says.
///
/// ```
/// use sylva_export::lod::{LodLevel, TreeLook, calibrate_leaves};
/// let mut species = sylva_forest::Species::from_preset("sylva-birch", 5)?;
/// species.turtle.symbols.set("L", sylva_turtle::Command::Leaf);
/// let full = species.mesh(5, 1)?;
/// let level = LodLevel { bark_error: 0.03, leaf_keep: 0.5, leaf_growth: None };
/// let tuned = calibrate_leaves(&full, &TreeLook::of(&species), &level);
/// assert!(tuned.growth() <= level.growth() * 1.2);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn calibrate_leaves(full: &Mesh, look: &TreeLook, level: &LodLevel) -> LodLevel {
    let Some((lo, hi)) = full.bounds() else {
        return *level;
    };
    let views: Vec<OrthoView> = [Vec3::X, Vec3::Z, Vec3::Y]
        .into_iter()
        .map(|toward| OrthoView {
            centre: (lo + hi) * 0.5,
            toward,
            half: 0.5 * (hi - lo).length(),
            size: 96,
        })
        .collect();
    // The full tree is drawn once; each trial growth draws the coarse one.
    let covered: usize = views.iter().map(|v| draw(full, look, v).covered()).sum();
    let ratio = |growth: f32| {
        let tuned = LodLevel {
            leaf_growth: Some(growth),
            ..*level
        };
        let coarse = super::simplify::simplify_mesh(full, &tuned);
        let trial: usize = views.iter().map(|v| draw(&coarse, look, v).covered()).sum();
        trial as f32 / covered.max(1) as f32
    };
    let area = LodLevel {
        leaf_growth: None,
        ..*level
    }
    .growth();
    // Coverage grows with the cards: bisect between unchanged cards and 1.2 x the area's.
    let (mut lo, mut hi) = (1.0f32, area * 1.2);
    for _ in 0..7 {
        let mid = 0.5 * (lo + hi);
        if ratio(mid) < 1.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    LodLevel {
        leaf_growth: Some(0.5 * (lo + hi)),
        ..*level
    }
}
