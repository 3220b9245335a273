//! Every file format of sylva: binary glTF (instanced with `EXT_mesh_gpu_instancing`, or a
//! node per placement), USD (a point instancer, as text), the geometry a world's tiles share,
//! OGC 3D Tiles 1.1 worlds with two levels of detail, grown stands, and the procedural leaf
//! and bark textures as images.
//!
//! Every file is written whole or not at all: beside its destination under a temporary name,
//! flushed to disk and renamed into place, so a full disk or an interrupted run leaves the
//! previous file (see [`sylva_base::file`]).
//!
//! ```
//! use sylva_export::{GltfOptions, write_glb};
//! use sylva_forest::{ForestBuilder, ForestConfig, Rect, Species};
//! use sylva_terrain::{FlatPlane, glam::Vec2};
//!
//! let config = ForestConfig::new(vec![Species::from_preset("sylva-hazel", 3)?])
//!     .with_budget(1 << 20);
//! let builder = ForestBuilder::new(config)?;
//! let ground = FlatPlane { height: 0.0, min: Vec2::ZERO, max: Vec2::splat(40.0) };
//! let path = std::env::temp_dir().join(format!("sylva-export-doc-{}.glb", std::process::id()));
//! let stats = write_glb(&builder, &ground, Rect::new(Vec2::ZERO, Vec2::splat(40.0)), None, &GltfOptions::default(), &path)?;
//! assert_eq!(std::fs::metadata(&path).unwrap().len() as usize, stats.bytes);
//! assert!(stats.trees > 0);
//! # std::fs::remove_file(&path).ok();
//! # Ok::<(), sylva_export::ExportError>(())
//! ```
//!
//! # Feature flags
//!
//! None.
//!
//! # Conventions
//!
//! glTF's: right-handed, +Y up, metres; colours in linear RGB. Tiles are placed on the globe
//! by an east-north-up frame at [`TilesetOptions::origin`].

mod census;
mod error;
mod gltf;
pub mod lod;
mod pack;
mod phenology;
mod spill;
mod texture;
mod tiles;
mod usd;

pub use error::{ExportError, Invalid};
pub use gltf::{
    GlbStats, GltfOptions, WIND_TREE_REACH, tree_glb, write_glb, write_shared_geometry,
    write_stand_glb, write_tree_glb,
};
pub use pack::{PackStats, write_asset_pack};
pub use texture::{Texture, linear_to_srgb, srgb_to_linear};
pub use tiles::{
    Level, TileId, TileScheme, TileStats, TilesetOptions, check_tileset_folder, tile_path,
    write_tile, write_tileset,
};
pub use usd::{UsdOptions, UsdStats, write_usda};

/// The limits and tuning constants of export.
pub mod limits {
    pub use crate::gltf::{
        CELL_SIZE, CHUNK_BYTES, MAX_CELLS_PER_SIDE, MAX_NODE_PLACEMENTS, SEEDLING_CELL_FACTOR,
        SEEDLING_MIN_PIXELS,
    };
    pub use crate::texture::{CUTOFF_MIP_LEVEL, TEXTURE_SIZE};
    pub use crate::tiles::{MAX_TILES, TILESET_BYTES_PER_TILE};
}
