//! Errors of export: glTF and USD files, shared geometry and 3D Tiles.

use glam::Vec2;
use sylva_base::file::FileError;
use sylva_base::range::OutOfRange;
use sylva_forest::ForestError;

/// Why a file could not be written. Nothing is left half-written: an error leaves the
/// destination as it was.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ExportError {
    /// Placing the forest failed.
    #[error(transparent)]
    Forest(#[from] ForestError),
    /// Writing a file failed (a bad path, a full disk).
    #[error("{0}")]
    File(#[from] FileError),
    /// The exporter found something that would make an invalid file, and wrote nothing.
    #[error("refusing to write an invalid file: {0}")]
    Invalid(#[from] Invalid),
    /// The file would pass the 4 GiB a GLB can hold: export a smaller region, or tiles.
    #[error("{bytes} bytes is beyond the 4 GiB a GLB can hold (write a smaller region, or tiles)")]
    TooLarge {
        /// The file's size.
        bytes: u64,
    },
    /// Too many placements for a node each
    /// ([`GltfOptions::one_node_per_placement`](crate::GltfOptions::one_node_per_placement)).
    #[error(
        "{placements} placements as nodes of their own is more than the limit of {limit}: write this forest with EXT_mesh_gpu_instancing, or a smaller region"
    )]
    TooManyNodes {
        /// Placements of the forest.
        placements: usize,
        /// The limit ([`MAX_NODE_PLACEMENTS`](crate::limits::MAX_NODE_PLACEMENTS)).
        limit: usize,
    },
    /// A stand's tree names a species the stand was not given.
    #[error("a tree of species {species}, but only {count} species were given")]
    UnknownSpecies {
        /// The species index.
        species: usize,
        /// Species given.
        count: usize,
    },
    /// USD is written as text: the file's name must end in `.usda`.
    #[error("{}: sylva writes USD as text; name the file .usda (for example forest.usda)", path.display())]
    NotUsda {
        /// The name given.
        path: std::path::PathBuf,
    },
    /// A tile id is not `c_X_Y` or `f_X_Y`.
    #[error("tile '{id}': expected c_X_Y (coarse) or f_X_Y (fine), X and Y whole numbers")]
    BadTileId {
        /// The text given.
        id: String,
    },
    /// The world has no area.
    #[error("the world {min} to {max} is empty")]
    EmptyWorld {
        /// Its lower corner.
        min: Vec2,
        /// Its upper corner.
        max: Vec2,
    },
    /// A setting is outside its range: set it within what the message says.
    #[error(transparent)]
    OutOfRange(#[from] OutOfRange),
    /// The world would have more tiles than [`MAX_TILES`](crate::limits::MAX_TILES): use larger
    /// tiles (what it would cost, and the smallest tile side within the limit, are said).
    #[error(
        "{columns} x {rows} tiles (a tileset.json of about {} MB) is more than the limit of {limit} tiles; use tiles of at least {min_tile} m (--tile-size)",
        tileset_bytes / 1_000_000
    )]
    TooManyTiles {
        /// Tiles along x.
        columns: f32,
        /// Tiles along z.
        rows: f32,
        /// The limit.
        limit: u64,
        /// About how many bytes the tileset's `tileset.json` would have been.
        tileset_bytes: u64,
        /// The smallest tile side, whole metres, that keeps the world within the limit.
        min_tile: u32,
    },
    /// A tile id names a tile outside the world.
    #[error("tile {id} is outside the world: {columns} x {rows} tiles on its level")]
    TileOutside {
        /// The tile.
        id: String,
        /// Tiles along x on its level.
        columns: u32,
        /// Tiles along z on its level.
        rows: u32,
    },
    /// A tileset folder holds files that are not part of a tileset: give an empty or new
    /// folder.
    #[error("{}: the folder holds '{entry}', which is not part of a tileset; give an empty or new folder", folder.display())]
    NotTilesetFolder {
        /// The folder.
        folder: std::path::PathBuf,
        /// The first entry that is not the tileset's.
        entry: String,
    },
    /// An asset pack replaces its folder whole; this one holds something that is not a
    /// pack's.
    #[error("{}: holds {entry}, which is not an asset pack's (.glb, .png, .csv, .json); write the pack to a new or empty folder", folder.display())]
    NotPackFolder {
        /// The folder.
        folder: std::path::PathBuf,
        /// The first entry that is not the pack's.
        entry: String,
    },
}

/// What would have made a file invalid (a bug upstream if it ever happens with a built
/// forest; the file is not written).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Invalid {
    /// An instance's index span runs past its cache's indices.
    #[error("an instance spans past its cache's indices")]
    InstanceSpan,
    /// A placement is not a valid translation, rotation and scale.
    #[error("placement {0:?} is not a valid TRS transform")]
    Transform(sylva_instancing::Similarity),
    /// A placement names an instance its variant does not have.
    #[error("a placement of an unknown instance")]
    UnknownInstance,
    /// A vertex position is NaN or infinite.
    #[error("a vertex position is not finite")]
    VertexPosition,
    /// A normal is not of unit length.
    #[error("normal {0:?} is not unit length")]
    Normal([f32; 3]),
    /// An index names no vertex.
    #[error("index out of range")]
    Index,
    /// The bytes written differ from the layout.
    #[error("wrote {written} bytes where the layout has {layout}")]
    Layout {
        /// Bytes written.
        written: u64,
        /// Bytes the layout has.
        layout: u64,
    },
    /// The JSON could not be serialised.
    #[error("JSON: {0}")]
    Json(String),
}
