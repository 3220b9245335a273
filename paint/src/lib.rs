//! Painting forests (Carey's painting tool, report section 4.8): a paint layer of species
//! densities over the terrain, brushes that edit it stroke by stroke with undo, a painter
//! that regenerates only the trees near each stroke, and masks saved as 16-bit PNG files.
//!
//! A [`PaintLayer`] is a [`Composition`](sylva_forest::Composition): handed to a forest, it
//! decides where each species grows, and everything else (spacing, seedlings, streaming,
//! export) is as for a generated forest.
//!
//! ```
//! use std::sync::Arc;
//! use sylva_forest::{Composition, ForestBuilder, ForestConfig, Rect, Species};
//! use sylva_paint::{Brush, BrushAction, PaintCanvas, PaintLayer};
//! use sylva_terrain::{FlatPlane, glam::Vec2};
//!
//! let mut leafy = Species::from_preset("kenwood-leafy", 3)?;
//! leafy.turtle.step = 0.5;
//! let config = ForestConfig::new(vec![leafy]).with_budget(1 << 20);
//! let builder = ForestBuilder::new(config)?;
//! let ground = FlatPlane { height: 0.0, min: Vec2::ZERO, max: Vec2::splat(100.0) };
//! let area = Rect::new(Vec2::ZERO, Vec2::splat(100.0));
//!
//! // An empty layer grows nothing; one stroke of species 0 grows trees under the brush.
//! let mut canvas = PaintCanvas::for_forest(&builder, PaintLayer::new(area, 1.0, 1)?)?;
//! let brush = Brush::new(BrushAction::Add { species: 0 }, 20.0);
//! canvas.stroke(brush, &[Vec2::new(30.0, 50.0), Vec2::new(70.0, 50.0)])?;
//! let layer: Arc<dyn Composition> = canvas.shared_layer();
//! let painted = builder.with_composition(Some(layer))?;
//! let trees = painted.trees(&ground, area);
//! assert!(!trees.is_empty());
//! assert!(trees.iter().all(|t| (t.position[2] - 50.0).abs() < 25.0));
//! # Ok::<(), sylva_paint::PaintError>(())
//! ```
//!
//! # Feature flags
//!
//! None.
//!
//! # Conventions
//!
//! +Y up, metres; layers lie in the x-z plane, a mask's first row at the lowest z.

mod brush;
mod canvas;
mod error;
mod file;
mod layer;
mod painter;

use std::path::Path;
use std::sync::Arc;

pub use brush::{Brush, BrushAction, MAX_BRUSH_RADIUS};
pub use canvas::{Change, MAX_UNDO, PaintCanvas};
pub use error::{MaskProblem, PaintError};
pub use file::{MASK_TEXT_KEY, load_masks, mask_file_name, save_masks};
pub use layer::{FULL, MAX_PAINT_VALUES, PaintLayer};
pub use painter::{ForestPainter, PAINT_TILE_PATCHES, StrokeReport};

use sylva_forest::{ForestBuilder, Rect};
use sylva_terrain::HeightField;

/// The masks saved in `dir` (see [`load_masks`]) for `builder`'s species, stretched over
/// `terrain`: one mask per species, named after it.
pub fn load_masks_for(
    builder: &ForestBuilder,
    dir: &Path,
    terrain: &dyn HeightField,
) -> Result<PaintLayer, PaintError> {
    let names: Vec<&str> = builder
        .config()
        .species
        .iter()
        .map(|s| s.name.as_str())
        .collect();
    let (lo, hi) = terrain.bounds();
    load_masks(dir, &names, Rect::new(lo, hi))
}

/// `builder` painted with the masks saved in `dir` for its species, stretched over
/// `terrain` (see [`load_masks_for`]).
pub fn with_masks(
    builder: &ForestBuilder,
    dir: &Path,
    terrain: &dyn HeightField,
) -> Result<ForestBuilder, PaintError> {
    let layer = load_masks_for(builder, dir, terrain)?;
    Ok(builder.with_composition(Some(Arc::new(layer)))?)
}
