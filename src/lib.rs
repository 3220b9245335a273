#![doc = include_str!("../README.md")]
//!
//! # Crates
//!
//! - [`base`]: the seeded SplitMix hash every crate draws from, and bounded file reading.
//! - [`forest`]: species, density management, placement, glTF export, grown stands.
//! - [`growth`]: trees grown into their environment in a voxel space (light, collision).
//! - [`lsys`]: L-system grammars and seeded rewriting.
//! - [`instancing`]: Kenwood's branch-level instance cache and tree assembly.
//! - [`turtle`]: 3D turtle interpretation into meshes and skeletons.
//! - [`terrain`]: diamond-square heightmaps, smoothing, erosion, sampling, export.
//!
//! [`presets`] holds the default forest (five species and a terrain) the examples and the
//! viewer grow.

pub use sylva_base as base;
pub use sylva_forest as forest;
pub use sylva_growth as growth;
pub use sylva_instancing as instancing;
pub use sylva_lsys as lsys;
pub use sylva_terrain as terrain;
pub use sylva_turtle as turtle;

pub mod presets;
