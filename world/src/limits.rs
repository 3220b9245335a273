//! Every limit and default of a world, in one place: the CLI's flags, the viewer's, the
//! server's descriptions and uploads check against these, and their messages quote them.

/// Shortest side of a world, metres.
pub const MIN_SIDE: f32 = 10.0;
/// Longest side of a world, metres: 20 km, 400 km² (a forest of 20 million canopy trees).
pub const MAX_SIDE: f32 = 20_000.0;
/// Side of the generated world when none is asked for, metres.
pub const DEFAULT_SIDE: f32 = 800.0;
/// Side of the region of an elevation model larger than this that a single-file forest
/// takes by default (its middle), metres: a forest of this side is a GLB of about 70 MB,
/// which desktop viewers open; the whole model goes to 3D Tiles (`--whole`).
pub const DEFAULT_REGION_SIDE: f32 = 1_000.0;
/// Least distance between the vertices of a forest file's terrain mesh, metres: a 100 m
/// world's 257 samples a side would be 0.4 m apart, a quarter of its file.
pub const TERRAIN_MESH_SPACING: f32 = 1.5;

/// Sides a forest file's cells may be asked for (`sylva forest --cell-size`), metres; 0 asks
/// for none. A cell under 8 m holds a tree or two; the writer makes at most 32 cells a side
/// whatever is asked (`sylva_export::limits::MAX_CELLS_PER_SIDE`), which bounds the file's
/// node count before any tree is placed.
pub const CELL_SIZE_RANGE: (f32, f32) = (8.0, 10_000.0);

/// Most canopy trees per hectare a density may ask for.
pub const MAX_DENSITY: f32 = 10_000.0;
/// Most canopy trees a world may be sized for (`--trees`).
pub const MAX_TREES: usize = 10_000_000;
/// Most years one forest over time simulates.
pub const MAX_YEARS: u32 = 10_000;

/// Instance-cache budget when none is asked for, MiB: the most a budget sized to the forest
/// gives ([`BUDGET_BYTES_PER_CANOPY_TREE`]), reached by the default forest.
pub const DEFAULT_BUDGET_MB: u32 = 32;
/// Instance-cache bytes each canopy tree adds to a budget sized to the forest, from
/// [`MIN_SIZED_BUDGET_MB`] up to [`DEFAULT_BUDGET_MB`]: the default forest's 18,400 canopy
/// trees reach the cap; a forest of 3,072 canopy trees (10 ha at the bundled species'
/// spacing) or fewer gets the floor.
pub const BUDGET_BYTES_PER_CANOPY_TREE: usize = 2 << 10;
/// The least instance-cache budget sized to a forest, MiB: a few heroes per species and form
/// (a species' share too small for one hero is raised to it), so even a 100 m forest's
/// trees are assembled from branches of several heroes and differ (37% of its canopy
/// trees' compositions distinct), and its GLB stays under 8 MB (6.6 MB).
pub const MIN_SIZED_BUDGET_MB: u32 = 6;
/// Canopy trees a hectare holds at the bundled species' own spacing (287 in the default
/// forest): how a budget is sized before the forest is placed, when no density is given.
pub const CANOPY_TREES_PER_HECTARE: f32 = 290.0;
/// Largest instance-cache budget a description may ask for, MiB.
pub const MAX_BUDGET_MB: u32 = 128;

/// Checks an instance-cache budget in MiB against [`MAX_BUDGET_MB`], the one check every
/// front end makes (the CLI took 100,000 and aborted at 6 GB); the error is the value and
/// the range, for the caller to put its setting's name before.
///
/// ```
/// use sylva_world::limits::check_budget_mb;
/// assert!(check_budget_mb(32).is_ok());
/// assert_eq!(check_budget_mb(0).unwrap_err(), "0: expected 1 to 128");
/// ```
pub fn check_budget_mb(mb: u64) -> Result<(), String> {
    if (1..=u64::from(MAX_BUDGET_MB)).contains(&mb) {
        Ok(())
    } else {
        Err(format!("{mb}: expected 1 to {MAX_BUDGET_MB}"))
    }
}

/// Most species a world may have.
pub const MAX_SPECIES: usize = 16;
/// Most bytes of a species file.
pub use sylva_forest::limits::MAX_SPECIES_FILE_BYTES;
/// Most characters of a species' name (a species file's `name:`).
pub use sylva_forest::limits::MAX_SPECIES_NAME_CHARS;
/// Most pieces of geometry (segments, leaves, polygons) one tree may draw: a grammar past it
/// is refused before its tree is meshed.
pub use sylva_forest::limits::MAX_TREE_PIECES;
/// Most bytes a world description may have (inline species files included).
pub const MAX_DESCRIPTION_BYTES: usize = 256 << 10;
/// Most hydraulic-erosion droplets per sample of generated terrain.
pub const MAX_EROSION: f32 = 4.0;

/// Most bytes an elevation model may have, read from a project or uploaded.
pub const MAX_MODEL_BYTES: usize = 64 << 20;
/// Most samples along a side of an uploaded elevation model.
pub const MAX_MODEL_SIDE: u32 = 4097;
/// Largest spacing between an elevation model's samples a description may give, metres.
pub const MAX_SPACING: f32 = 1_000.0;
/// Largest height range of a 16-bit model a description may give, metres.
pub const MAX_HEIGHT_RANGE: f32 = 20_000.0;

/// Side of a fine tile when none is asked for, metres.
pub const DEFAULT_TILE_SIZE: f32 = 250.0;
/// Fine tiles along each side of a coarse tile when none is asked for.
pub const DEFAULT_GROUP: u32 = 4;
/// Smallest and largest side of a fine tile, metres.
pub const TILE_SIZE_RANGE: (f32, f32) = (10.0, 5_000.0);
/// Most fine tiles along each side of a coarse tile.
pub const MAX_GROUP: u32 = 64;
/// Longitude and latitude (degrees) of a world's low corner when none is given: Zürich.
pub const DEFAULT_ORIGIN: [f64; 2] = [8.54, 47.37];
