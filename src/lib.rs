#![doc = include_str!("../README.md")]
//!
//! # Crates
//!
//! - [`base`]: the seeded SplitMix hash every crate draws from, bounded file reading and
//!   atomic file writes.
//! - [`forest`]: species, density management, placement, streaming, proxies, grown stands,
//!   the guided walk.
//! - [`paint`]: paint layers, brushes with undo, the painter, masks.
//! - [`export`]: every file format: glTF, shared geometry, 3D Tiles, textures.
//! - [`growth`]: trees grown into their environment in a voxel space (light, collision).
//! - [`lsys`]: L-system grammars and seeded rewriting.
//! - [`instancing`]: Kenwood's branch-level instance cache and tree assembly.
//! - [`turtle`]: 3D turtle interpretation into meshes and skeletons.
//! - [`terrain`]: diamond-square heightmaps, smoothing, erosion, sampling, export.
//!
//! [`presets`] holds the default forest (five species and a terrain) the examples and the
//! viewer grow.

pub use sylva_base as base;
pub use sylva_export as export;
pub use sylva_forest as forest;
pub use sylva_growth as growth;
pub use sylva_instancing as instancing;
pub use sylva_lsys as lsys;
pub use sylva_paint as paint;
pub use sylva_terrain as terrain;
pub use sylva_turtle as turtle;
pub use sylva_world as world;
pub use sylva_world::presets;
