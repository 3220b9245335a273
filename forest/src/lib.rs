//! Forests: species, patch-based density management, placement on any terrain, forests
//! streamed block by block on every core, variant extents, stands grown in their
//! environment and the guided walk. Files are written by `sylva-export`, painting is
//! `sylva-paint`.
//!
//! ```
//! use sylva_forest::{ForestBuilder, ForestConfig, PlacementBlock, Rect, Species};
//! use sylva_terrain::{FlatPlane, glam::Vec2};
//!
//! let mut leafy = Species::from_preset("kenwood-leafy", 4)?;
//! leafy.turtle.step = 0.5;
//! let config = ForestConfig::new(vec![leafy]).with_budget(4 << 20);
//! let builder = ForestBuilder::new(config)?;
//! let ground = FlatPlane { height: 0.0, min: Vec2::ZERO, max: Vec2::splat(200.0) };
//! let region = Rect::new(Vec2::ZERO, Vec2::splat(200.0));
//! // Block by block: each block's trees and every instance transform, in order.
//! let mut placed = 0;
//! let stats = builder.stream(&ground, region, &mut |block: &PlacementBlock| {
//!     placed += block.placements.len();
//!     Ok(())
//! })?;
//! assert!(stats.trees > 0 && placed >= stats.trees);
//! // Or all at once, for small forests.
//! let forest = builder.build(&ground, region);
//! assert_eq!(forest.trees.len(), stats.trees);
//! # Ok::<(), sylva_forest::ForestError>(())
//! ```
//!
//! The density model follows the Garden of Eden thesis (5.2.3, 5.3.3, 7.10): patches the size
//! of a canopy, one canopy tree per patch, placement errors between neighbouring patches fixed
//! through a grid, seedlings thinned with an inverse-square elimination probability. Trees are
//! stored compactly (28 bytes) and expanded through the instance caches of `sylva-instancing`.
//!
//! # Conventions
//!
//! +Y up, metres, colours in linear RGB. A forest of a region is a pure function of (seed,
//! region): regions generated apart join without seams.

mod appearance;
mod census;
mod composition;
mod config;
mod crown_cover;
mod density;
mod error;
mod extent;
mod floor;
mod forest;
mod form;
mod ground;
mod life;
mod patch;
mod phenology;
mod siting;
mod siting_report;
mod species;
mod species_file;
mod stand;
mod stream;
pub mod succession;
mod variants;
mod variety;
mod walk;
mod years;

pub use appearance::{BarkPattern, LeafShape};
pub use census::{BinCounts, BinnedCounts, InstanceCounts};
pub use composition::ComposedDensity;
pub use config::{Constraints, ForestConfig};
pub use density::{Candidate, DensityModel, Rect, distance_to_segment};
pub use error::ForestError;
pub use extent::Extent;
pub use floor::{FloorItem, FloorOptions, ForestFloor, MAX_FLOOR_ITEMS};
pub use forest::{Forest, ForestBuilder, ForestStats, VariantPlacements};
pub use form::TreeForm;
pub use ground::{GroundCover, GroundKind, GroundLook};
pub use life::{BREAST_HEIGHT, Life, SEEDLING_HEIGHT};
pub use patch::{Composition, PatchDensity, PatchSpecies};
pub use phenology::{
    FALL_DAYS, FLUSH_DAYS, GREEN_DAYS, LeafSeason, Phenology, SEASON_DAYS, TREE_DAYS, TURN_DAYS,
    parse_day, snow, tree_day, vertex_phenology,
};
pub use siting_report::{Refusal, SitingReport};
pub use species::{Canopy, Species};
pub use stand::{GrownStand, Planting, StandOptions, grow_stand};
pub use stream::{KeepTrees, Placement, PlacementBlock, PlacementSink, StreamStats, TreesOf};
pub use succession::{Snapshot, Succession, SuccessionOptions};
pub use variants::{Variant, tree_at_age};
pub use variety::{CLUSTER_SHADE_MEAN, cluster_shade, tree_tint, tree_wind};
pub use walk::{ForestTrunks, GuidedWalk, TrunkGrid, Trunks, WalkOptions, WalkStep};

/// The limits and tuning constants of forest generation.
pub mod limits {
    pub use crate::species_file::{MAX_SPECIES_FILE_BYTES, MAX_SPECIES_NAME_CHARS};
    pub use crate::stream::{BLOCK_PATCHES, MAX_BLOCKS};
    /// Most pieces of geometry one tree may draw (the turtle's default budget).
    pub use sylva_turtle::MAX_PIECES as MAX_TREE_PIECES;
}
