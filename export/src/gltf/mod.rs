//! glTF 2.0 binary (.glb) export, streamed: the terrain, one mesh per used cached instance,
//! and each instance's placements through EXT_mesh_gpu_instancing.
//!
//! A forest of a million trees has millions of placements, more than should sit in memory at
//! once. The writer streams the forest twice: a first pass counts the placements of every
//! instance, which fixes the whole layout (JSON and binary offsets), and keeps each block's
//! trees in a scratch file; the second expands those trees and puts every placement where
//! the layout says, buffering at most about [`CHUNK_BYTES`] of them. Memory holds the
//! caches, the JSON text, the buffers and a couple of waves of blocks.
//! The file is written beside its destination under a temporary name and renamed when
//! complete ([`sylva_base::file::AtomicFile`]), so an error (a bad path, a full disk) never
//! leaves a half-written file.

mod builder;
mod cells;
mod coarse;
mod document;
mod extras;
mod file;
mod groups;
mod in_memory;
mod indices;
mod layer;
mod levels;
mod lod;
mod placement_words;
mod schema;
mod season;
mod shared;
mod stand;
mod subset;
mod tangent;

pub use cells::{CELL_SIZE, MAX_CELLS_PER_SIDE, SEEDLING_CELL_FACTOR};
pub(crate) use coarse::{CoarseImpostor, write_coarse_glb};
pub use levels::SEEDLING_MIN_PIXELS;
pub(crate) use lod::{LodCards, LodMesh, write_lod_glb};
pub use placement_words::WIND_TREE_REACH;
pub use shared::write_shared_geometry;
pub use stand::{tree_glb, write_stand_glb, write_tree_glb};

use std::path::Path;

use sylva_terrain::{HeightField, TerrainMesh};

use sylva_forest::{ForestBuilder, PlacementBlock, Rect, StreamStats};

use crate::census::{
    Drawn, Node, check_geometry, check_transform, count_placements, drawn_instances,
};
use crate::error::ExportError;
use crate::lod::LodChain;
use crate::spill::TreeSpill;
use cells::{CellGrid, CellNodes};
use document::Document;
use file::{write_file, write_geometry, write_placements};
use groups::Grouping;
use levels::ForestLevels;

/// Export settings. Like every options struct of sylva: public fields, [`Default`], and a
/// `with_*` method per field for chaining.
///
/// ```
/// use sylva_export::GltfOptions;
/// let options = GltfOptions::default().with_roughness(0.8).with_one_node_per_placement(true);
/// assert_eq!((options.roughness, options.one_node_per_placement), (0.8, true));
/// assert_eq!(options.chunk_bytes, GltfOptions::default().chunk_bytes);
/// ```
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct GltfOptions {
    /// Terrain tint, linear RGB, multiplied with the ground colours by slope and altitude
    /// ([`sylva_terrain::ground`]) that the terrain's vertices carry.
    /// Default: [1, 1, 1] (no tint).
    pub terrain_colour: [f32; 3],
    /// Roughness of every material (all are dielectric: metallic 0). Default: 0.9.
    pub roughness: f32,
    /// Most bytes of placements buffered in memory while writing, shared among the instances
    /// (at least one placement each): a buffer is written at its place in the file when it
    /// holds its share. Smaller means less memory and more, smaller writes; the file is the
    /// same. Default [`CHUNK_BYTES`].
    pub chunk_bytes: usize,
    /// The URI (relative to the GLB) of a file written by [`write_shared_geometry`] for the
    /// same builder: when set, the GLB refers to that file's cache buffers and textures as an
    /// external buffer instead of embedding them, as the tiles of one world do.
    /// Default: none (embedded).
    pub shared_geometry: Option<String>,
    /// Write each placement as a node of its own that shares its instance's mesh, instead
    /// of EXT_mesh_gpu_instancing: for importers that ignore the extension (Blender before
    /// 3.6, some Unity and Godot importers). Forests over [`MAX_NODE_PLACEMENTS`] placements
    /// are refused in this mode. Default: false.
    pub one_node_per_placement: bool,
    /// Side of the square cells an instanced file groups its trees in, metres: a node per
    /// cell, under it a node per variant, under that an instanced node per prototype, so
    /// that engines cull by cell. A forest wider than [`MAX_CELLS_PER_SIDE`] cells gets
    /// wider ones; seedlings go in cells [`SEEDLING_CELL_FACTOR`] times as wide. `None`: one
    /// instanced node per prototype for the whole forest. Ignored with
    /// [`GltfOptions::one_node_per_placement`] and [`GltfOptions::shared_geometry`].
    /// Default: [`CELL_SIZE`] (64 m).
    pub cell_size: Option<f32>,
    /// Levels of detail in the file: each cell's variant node declares `MSFT_lod` (not
    /// required) with the chain's coarser levels of every prototype, and names in
    /// `extras.sylva_levels` its impostor (the cards placed once per tree), with the switch
    /// distances and screen coverages. A client without `MSFT_lod` draws full detail. Ignored
    /// with [`GltfOptions::one_node_per_placement`] and [`GltfOptions::shared_geometry`].
    /// Default: [`LodChain::default`] (the viewer's chain).
    pub levels: Option<LodChain>,
}

/// Most placements [`GltfOptions::one_node_per_placement`] writes: a node each is text in the
/// JSON chunk, gathered in memory, and importers slow down long before this.
pub const MAX_NODE_PLACEMENTS: usize = 250_000;

impl Default for GltfOptions {
    fn default() -> Self {
        GltfOptions {
            terrain_colour: [1.0, 1.0, 1.0],
            roughness: 0.9,
            chunk_bytes: CHUNK_BYTES,
            shared_geometry: None,
            one_node_per_placement: false,
            cell_size: Some(CELL_SIZE),
            levels: Some(LodChain::default()),
        }
    }
}

impl GltfOptions {
    /// Sets [`GltfOptions::terrain_colour`].
    #[must_use]
    pub fn with_terrain_colour(mut self, terrain_colour: [f32; 3]) -> Self {
        self.terrain_colour = terrain_colour;
        self
    }

    /// Sets [`GltfOptions::roughness`].
    #[must_use]
    pub fn with_roughness(mut self, roughness: f32) -> Self {
        self.roughness = roughness;
        self
    }

    /// Sets [`GltfOptions::chunk_bytes`].
    #[must_use]
    pub fn with_chunk_bytes(mut self, chunk_bytes: usize) -> Self {
        self.chunk_bytes = chunk_bytes;
        self
    }

    /// Sets [`GltfOptions::shared_geometry`].
    #[must_use]
    pub fn with_shared_geometry(mut self, shared_geometry: Option<String>) -> Self {
        self.shared_geometry = shared_geometry;
        self
    }

    /// Sets [`GltfOptions::one_node_per_placement`].
    #[must_use]
    pub fn with_one_node_per_placement(mut self, one_node_per_placement: bool) -> Self {
        self.one_node_per_placement = one_node_per_placement;
        self
    }

    /// Sets [`GltfOptions::cell_size`].
    #[must_use]
    pub fn with_cell_size(mut self, cell_size: Option<f32>) -> Self {
        self.cell_size = cell_size;
        self
    }

    /// Sets [`GltfOptions::levels`].
    #[must_use]
    pub fn with_levels(mut self, levels: Option<LodChain>) -> Self {
        self.levels = levels;
        self
    }
}

/// What was written.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[non_exhaustive]
pub struct GlbStats {
    /// File size in bytes.
    pub bytes: usize,
    /// Trees in the forest.
    pub trees: usize,
    /// Of which seedlings.
    pub seedlings: usize,
    /// Instance meshes written (one node each).
    pub instance_nodes: usize,
    /// Instance placements written.
    pub placements: usize,
    /// Placements of instances with no geometry (a branch introduced at the last generation
    /// of a species without leaf symbols), left out of the file.
    pub empty_placements: usize,
    /// Times the forest was streamed: once to count the placements, once to write them (two;
    /// one with no placements to write).
    pub passes: usize,
    /// Branch triangles drawn by the placements at full detail (the terrain not included).
    pub triangles: u64,
    /// Cells the trees are grouped in (canopy and seedling cells that hold a tree; 1 in a
    /// file without cells).
    pub cells: usize,
    /// Side of a canopy cell, metres (the forest's side in a file without cells).
    pub cell_size: f32,
    /// Levels of detail of each tree, its full detail and impostor included (1 in a file
    /// without levels).
    pub levels: usize,
    /// Placements of impostors, one per tree (0 in a file without levels).
    pub impostor_placements: usize,
}

/// Default of [`GltfOptions::chunk_bytes`]: 64 MiB, about 1.3 million placements of 52 bytes.
pub const CHUNK_BYTES: usize = 64 << 20;

const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;
const FLOAT: u32 = 5126;
const BYTE: u32 = 5120;
const UNSIGNED_BYTE: u32 = 5121;
const SHORT: u32 = 5122;
const UNSIGNED_SHORT: u32 = 5123;
const UNSIGNED_INT: u32 = 5125;

/// Writes the forest of `region` on `terrain`, and optionally a terrain mesh, as a binary glTF
/// at `path`. The file declares EXT_mesh_gpu_instancing; every node of an instance mesh
/// carries TRANSLATION, ROTATION and SCALE accessors of equal count, float components and unit
/// quaternions. The output is a pure function of its inputs, at any thread count.
///
/// ```
/// use sylva_export::{GltfOptions, write_glb};
/// use sylva_forest::{ForestBuilder, ForestConfig, Rect, Species};
/// use sylva_terrain::{FlatPlane, glam::Vec2};
///
/// let mut leafy = Species::from_preset("kenwood-leafy", 4)?;
/// leafy.turtle.step = 0.5;
/// let config = ForestConfig::new(vec![leafy]).with_budget(4 << 20);
/// let builder = ForestBuilder::new(config)?;
/// let ground = FlatPlane { height: 0.0, min: Vec2::ZERO, max: Vec2::splat(200.0) };
/// let path = std::env::temp_dir().join("sylva-doctest-forest.glb");
/// let region = Rect::new(Vec2::ZERO, Vec2::splat(200.0));
/// let stats = write_glb(&builder, &ground, region, None, &GltfOptions::default(), &path)?;
/// assert_eq!(std::fs::metadata(&path).unwrap().len() as usize, stats.bytes);
/// assert!(stats.placements >= stats.trees);
/// # std::fs::remove_file(&path).ok();
/// # Ok::<(), sylva_export::ExportError>(())
/// ```
pub fn write_glb(
    builder: &ForestBuilder,
    terrain: &(dyn HeightField + Sync),
    region: Rect,
    terrain_mesh: Option<&TerrainMesh>,
    options: &GltfOptions,
    path: &Path,
) -> Result<GlbStats, ExportError> {
    let variants = builder.variants();
    let terrain_mesh = terrain_mesh.filter(|t| !t.indices.is_empty());
    check_geometry(variants, terrain_mesh)?;
    let spill = TreeSpill::create(path, builder.blocks(region)?.len())?;
    let grouped = !options.one_node_per_placement
        && options.shared_geometry.is_none()
        && (options.cell_size.is_some() || options.levels.is_some());
    if grouped {
        write_grouped(
            builder,
            (terrain, region, &spill),
            terrain_mesh,
            options,
            path,
        )
    } else {
        write_flat(
            builder,
            (terrain, region, &spill),
            terrain_mesh,
            options,
            path,
        )
    }
}

/// A forest file with a node per used instance for the whole forest (or a node per
/// placement), as tiles and importers without instancing take it.
fn write_flat(
    builder: &ForestBuilder,
    (terrain, region, spill): (&(dyn HeightField + Sync), Rect, &TreeSpill),
    terrain_mesh: Option<&TerrainMesh>,
    options: &GltfOptions,
    path: &Path,
) -> Result<GlbStats, ExportError> {
    let variants = builder.variants();
    // Pass 1: count the placements of every instance, keeping each block's trees.
    let (counts, counted) = count_placements(builder, terrain, region, spill)?;
    // The layout: which instances become nodes, and where every byte goes.
    let Drawn {
        nodes,
        node_of,
        placements,
        empty_placements,
        triangles,
    } = drawn_instances(variants, &counts);
    drop(counts);
    // The fallback: every placement's transform, gathered per node for the JSON.
    let each = if options.one_node_per_placement {
        if placements > MAX_NODE_PLACEMENTS {
            return Err(ExportError::TooManyNodes {
                placements,
                limit: MAX_NODE_PLACEMENTS,
            });
        }
        let mut each: Vec<Vec<sylva_instancing::Similarity>> = vec![Vec::new(); nodes.len()];
        let gather = &mut |block: &PlacementBlock| -> Result<(), ExportError> {
            for p in &block.placements {
                let node = node_of[p.variant as usize][p.instance as usize];
                if let Some(list) = each.get_mut(node as usize) {
                    check_transform(&p.transform)?;
                    list.push(p.transform);
                }
            }
            Ok(())
        };
        builder.stream_with(terrain, region, &|_| true, gather)?;
        Some(each)
    } else {
        None
    };
    let document = Document::lay_out(
        builder,
        terrain_mesh,
        options,
        (&nodes, placements),
        each.as_deref(),
        None,
    )?;
    let written = write_file(path, &document, |file| {
        write_geometry(file, terrain_mesh, &document)?;
        if each.is_some() {
            return Ok(1);
        }
        write_placements(
            file,
            builder,
            (terrain, region, spill),
            (&nodes, NodeLookup::Flat(&node_of)),
            document.bin_start() + document.placement_base,
            placements,
            options.chunk_bytes,
        )
    });
    let passes = written?;
    let StreamStats {
        trees, seedlings, ..
    } = counted;
    let side = (region.max - region.min).max_element();
    Ok(GlbStats {
        bytes: document.total,
        trees,
        seedlings,
        instance_nodes: nodes.len(),
        placements,
        empty_placements,
        passes: 1 + passes,
        triangles,
        cells: 1,
        cell_size: side,
        levels: 1,
        impostor_placements: 0,
    })
}

/// A forest file with its trees in cells and, with [`GltfOptions::levels`], each cell's
/// variants at every level of detail.
fn write_grouped(
    builder: &ForestBuilder,
    (terrain, region, spill): (&(dyn HeightField + Sync), Rect, &TreeSpill),
    terrain_mesh: Option<&TerrainMesh>,
    options: &GltfOptions,
    path: &Path,
) -> Result<GlbStats, ExportError> {
    let grid = CellGrid::new(region, options.cell_size);
    // Every variant's chain, impostors included, on every core.
    let levels = match &options.levels {
        Some(chain) => Some(ForestLevels::build(builder, chain)?),
        None => None,
    };
    let impostors = levels.as_ref().map_or_else(
        || vec![false; builder.variants().len()],
        ForestLevels::impostors,
    );
    // Pass 1: count every cell's placements of every instance, and its trees.
    let cells = CellNodes::count(builder, (terrain, region), &grid, &impostors, spill)?;
    let grouping = Grouping {
        grid: &grid,
        levels: levels.as_ref(),
    };
    let document = Document::lay_out(
        builder,
        terrain_mesh,
        options,
        (&cells.nodes, cells.placements),
        None,
        Some(grouping),
    )?;
    let lookup = NodeLookup::Cells(&cells);
    let passes = write_file(path, &document, |file| {
        write_geometry(file, terrain_mesh, &document)?;
        write_placements(
            file,
            builder,
            (terrain, region, spill),
            (&cells.nodes, lookup),
            document.bin_start() + document.placement_base,
            cells.placements,
            options.chunk_bytes,
        )
    })?;
    let used_cells: std::collections::BTreeSet<u32> = cells.nodes.iter().map(|n| n.cell).collect();
    let canopy_levels = levels
        .as_ref()
        .and_then(|l| l.variants.iter().find(|v| v.cards.is_some()))
        .map_or(1, |v| v.mesh_levels() + 1);
    Ok(GlbStats {
        bytes: document.total,
        trees: cells.stats.trees,
        seedlings: cells.stats.seedlings,
        instance_nodes: cells.nodes.iter().filter(|n| !n.impostor).count(),
        placements: cells.instance_placements,
        empty_placements: cells.empty_placements,
        passes: 1 + passes,
        triangles: cells.triangles,
        cells: used_cells.len(),
        cell_size: grid.side(),
        levels: canopy_levels,
        impostor_placements: cells.placements - cells.instance_placements,
    })
}

/// How the writing pass finds a placement's node.
#[derive(Clone, Copy)]
pub(crate) enum NodeLookup<'a> {
    /// By variant and instance (`u32::MAX`: none).
    Flat(&'a [Vec<u32>]),
    /// By the cell of the placement's tree, variant and instance; and each tree of a
    /// variant with an impostor places it once.
    Cells(&'a CellNodes),
}

/// The lowest and highest corner of `positions` (glTF requires them on POSITION accessors)
/// and how many there are.
fn position_bounds(positions: impl IntoIterator<Item = [f32; 3]>) -> ([f32; 3], [f32; 3], usize) {
    let mut lo = [f32::INFINITY; 3];
    let mut hi = [f32::NEG_INFINITY; 3];
    let mut count = 0;
    for p in positions {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
        count += 1;
    }
    (lo, hi, count)
}

/// The GLB header, the JSON chunk (`json`, already padded to a whole number of words) and,
/// with `bin` bytes of binary content, the BIN chunk's header: everything before the binary
/// content of a file of `total` bytes.
fn glb_header(total: usize, json: &str, bin: Option<usize>) -> Result<Vec<u8>, ExportError> {
    let too_large = |_| ExportError::TooLarge {
        bytes: total as u64,
    };
    let total = u32::try_from(total).map_err(too_large)?;
    let mut out = Vec::with_capacity(28 + json.len());
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&total.to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(json.as_bytes());
    if let Some(bin) = bin {
        out.extend_from_slice(&(bin as u32).to_le_bytes());
        out.extend_from_slice(b"BIN\0");
    }
    Ok(out)
}
