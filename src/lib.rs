//! Procedural forests: L-system grammars, turtle geometry, fractal and real terrain,
//! Kenwood's branch-level instance cache, trees grown into their environment, and forests
//! streamed block by block into glTF, USD and 3D Tiles.
//!
//! This crate re-exports the library crates under one name. A forest of the five bundled
//! species on the default terrain, written as a binary glTF:
//!
//! ```
//! use sylva::export::{GltfOptions, write_glb};
//! use sylva::forest::{ForestBuilder, ForestConfig, Rect};
//! use sylva::terrain::HeightField;
//!
//! let terrain = sylva::presets::terrain(7, 120.0)?;
//! let builder = ForestBuilder::new(ForestConfig::new(sylva::presets::species()?))?;
//! let (lo, hi) = terrain.bounds();
//! let path = std::env::temp_dir().join("sylva-crate-docs-forest.glb");
//! let glb = write_glb(&builder, &terrain, Rect::new(lo, hi), None, &GltfOptions::default(), &path)?;
//! assert!(glb.trees > 50);
//! # std::fs::remove_file(&path).ok();
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! A world as the `sylva` command, the viewer and the server make it, from its description
//! (see [`world`]):
//!
//! ```
//! use sylva::world::{Quiet, WorldDescription};
//!
//! let description = WorldDescription::parse(br#"{"area": 120, "species": ["birch", "hazel"], "budget_mb": 8}"#)?;
//! let ground = description.ground(|_| unreachable!("generated ground reads no model"))?;
//! let world = description.world_builder()?.build(ground, &Quiet)?;
//! assert!(world.forest.trees(&world.ground.map, world.region()).len() > 20);
//! # Ok::<(), sylva::world::WorldError>(())
//! ```
//!
//! # Crates
//!
//! - [`world`]: a world assembled once: its description, its ground (generated or any
//!   elevation model), the builder, the limits, the bundled species ([`presets`]).
//! - [`forest`]: species, density management, placement, streaming, proxies, grown stands,
//!   forests over time, the forest floor, the guided walk.
//! - [`export`]: every file format: glTF, USD, shared geometry, 3D Tiles, textures, levels of
//!   detail.
//! - [`lsys`]: L-system grammars (sylva's notation, cpfg, L-Py) and seeded rewriting.
//! - [`turtle`]: 3D turtle interpretation into meshes and skeletons.
//! - [`terrain`]: diamond-square and spectral heightmaps, smoothing, erosion, elevation
//!   models, fractal analysis.
//! - [`instancing`]: Kenwood's branch-level instance cache and tree assembly.
//! - [`growth`]: trees grown into their environment in a voxel space (light, collision).
//! - [`paint`]: paint layers, brushes with undo, the painter, masks.
//! - [`base`]: the seeded SplitMix hash every crate draws from, bounded file reading and
//!   atomic file writes.
//!
//! The README and the guides under `docs/` are the user's manual; their Rust examples are
//! compiled and run as this crate's doctests.

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

/// The README's and the guides' examples, compiled and run as doctests so they stay true;
/// not part of the docs.
#[cfg(doctest)]
mod manual {
    #[doc = include_str!("../README.md")]
    struct Readme;
    #[doc = include_str!("../docs/library.md")]
    struct Library;
    #[doc = include_str!("../docs/engines.md")]
    struct Engines;
}
