//! Painting forests (Carey's painting tool, report section 4.8): a paint layer of species
//! densities over the terrain, brushes that edit it stroke by stroke with undo, a painter
//! that regenerates only the trees near each stroke, and masks saved as 16-bit PNG files.

mod brush;
mod canvas;
mod file;
mod layer;
mod painter;

pub(crate) use brush::distance_to_segment;
pub use brush::{Brush, BrushAction, MAX_BRUSH_RADIUS};
pub use canvas::{Change, MAX_UNDO, PaintCanvas};
pub use file::{MASK_TEXT_KEY, load_masks, mask_file_name, save_masks};
pub use layer::{FULL, MAX_PAINT_VALUES, PaintLayer};
pub use painter::{ForestPainter, PAINT_TILE_PATCHES, StrokeReport};

use crate::density::{Candidate, DensityModel, Rect};
use crate::patch::PatchDensity;

/// The patch density model with each tree's presence and species decided by a paint layer
/// (see [`PaintLayer`]): spacing, moves and seedling thinning as without one.
#[derive(Debug, Clone, Copy)]
pub struct PaintedDensity<'a> {
    density: &'a PatchDensity,
    layer: &'a PaintLayer,
}

impl PatchDensity {
    /// This model, painted by `layer`.
    ///
    /// ```
    /// use sylva_forest::{DensityModel, PaintLayer, PatchDensity, PatchSpecies, Rect};
    /// use sylva_terrain::glam::Vec2;
    ///
    /// let model = PatchDensity::new(vec![PatchSpecies { canopy_radius: 3.0, weight: 1.0 }]);
    /// let area = Rect::new(Vec2::ZERO, Vec2::splat(60.0));
    /// // The layer reaches past the area: trees near it look at patches around it.
    /// let around = Rect::new(Vec2::splat(-30.0), Vec2::splat(90.0));
    /// let empty = PaintLayer::new(around, 1.0, 1)?;
    /// let mut trees = Vec::new();
    /// model.painted(&empty).candidates(area, 7, &mut trees);
    /// assert!(trees.is_empty());
    /// let full = PaintLayer::filled(around, 1.0, &[1.0])?;
    /// model.painted(&full).candidates(area, 7, &mut trees);
    /// let mut unpainted = Vec::new();
    /// model.candidates(area, 7, &mut unpainted);
    /// assert_eq!(trees, unpainted);
    /// # Ok::<(), sylva_forest::ForestError>(())
    /// ```
    pub fn painted<'a>(&'a self, layer: &'a PaintLayer) -> PaintedDensity<'a> {
        PaintedDensity {
            density: self,
            layer,
        }
    }
}

impl DensityModel for PaintedDensity<'_> {
    fn candidates(&self, region: Rect, seed: u64, out: &mut Vec<Candidate>) {
        self.density.candidates_by(self.layer, region, seed, out);
    }
}
