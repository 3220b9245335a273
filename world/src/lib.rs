//! A sylva world, assembled once. A world is species on ground: this crate holds its
//! description (the JSON the server takes and a project folder keeps), its ground (generated,
//! or any elevation model cropped to a window or a default region and resampled), the builder
//! that turns both into a forest ready for any writer, and the limits of all of it in one
//! place ([`limits`]). The `sylva` command, the viewer and the server each build their
//! worlds here; none of them assembles one itself.
//!
//! ```
//! use sylva_world::{Quiet, WorldDescription};
//!
//! let description = WorldDescription::parse(br#"{"area": 150, "species": ["birch"], "budget_mb": 4}"#)?;
//! let ground = description.ground(|_| unreachable!("generated ground reads no model"))?;
//! let world = description.world_builder()?.build(ground, &Quiet)?;
//! assert_eq!(world.side(), 150.0);
//! assert!(world.forest.trees(&world.ground.map, world.region()).len() > 10);
//! # Ok::<(), sylva_world::WorldError>(())
//! ```
//!
//! Real land: a model larger than the region asked for gives its middle, and says so.
//!
//! ```
//! use sylva_terrain::dem::ReadOptions;
//! use sylva_world::{Fit, Ground, limits::DEFAULT_REGION_SIDE};
//!
//! let model = concat!(env!("CARGO_MANIFEST_DIR"), "/../terrain/tests/data/dems/N44W072.hgt");
//! let fit = Fit::Middle { side: DEFAULT_REGION_SIDE };
//! let ground = Ground::read(model.as_ref(), &ReadOptions::default(), None, fit, "--spacing M")?;
//! assert!(ground.side() <= DEFAULT_REGION_SIDE);
//! assert!(ground.notes("N44W072.hgt")[0].contains("took the middle"));
//! # Ok::<(), sylva_world::WorldError>(())
//! ```

mod builder;
mod description;
mod error;
mod ground;
mod id;
pub mod limits;
mod model;
pub mod presets;
mod progress;
mod project;
mod recipe;

pub use builder::{World, WorldBuilder, density_patch};
pub use description::{SpeciesEntry, TerrainDescription, WorldDescription};
pub use error::WorldError;
pub use ground::{Chosen, Fit, Ground, crop_flag};
pub use id::{WorldId, model_id};
pub use model::{check_model, model_format};
pub use progress::{Progress, Quiet, Stage};
pub use project::{MASKS_FOLDER, Project, WORLD_FILE, read_model_bytes};
pub use sylva_terrain::dem::Window;
