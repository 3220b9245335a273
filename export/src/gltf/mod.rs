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
mod coarse;
mod document;
mod extras;
mod file;
mod in_memory;
mod indices;
mod lod;
mod placement_words;
mod schema;
mod season;
mod shared;
mod stand;
mod subset;
mod tangent;

pub(crate) use coarse::{CoarseImpostor, write_coarse_glb};
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
use crate::spill::TreeSpill;
use document::Document;
use file::{write_file, write_geometry, write_placements};

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
}

/// What was written.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
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
    /// Branch triangles drawn by the placements (the terrain not included).
    pub triangles: u64,
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

    // Pass 1: count the placements of every instance, keeping each block's trees.
    let spill = TreeSpill::create(path, builder.blocks(region)?.len())?;
    let (counts, counted) = count_placements(builder, terrain, region, &spill)?;
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
        &nodes,
        placements,
        each.as_deref(),
    )?;

    let written = write_file(path, &document, |file| {
        write_geometry(file, terrain_mesh, &document)?;
        if each.is_some() {
            return Ok(1);
        }
        write_placements(
            file,
            builder,
            (terrain, region, &spill),
            &nodes,
            &node_of,
            document.bin_start() + document.placement_base,
            placements,
            options.chunk_bytes,
        )
    });
    let passes = written?;
    let StreamStats {
        trees, seedlings, ..
    } = counted;
    Ok(GlbStats {
        bytes: document.total,
        trees,
        seedlings,
        instance_nodes: nodes.len(),
        placements,
        empty_placements,
        passes: 1 + passes,
        triangles,
    })
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
