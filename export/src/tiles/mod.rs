//! Worlds as tiles: an OGC 3D Tiles 1.1 tileset of GLB tiles with two levels of detail,
//! every tile a pure function of (seed, tile id), so that tiles are generated one at a time,
//! by separate processes or machines, and joined by a last step that writes the root.
//!
//! Layout of a tile folder: `tileset.json`, `shared.bin` (every variant's branch geometry and
//! the textures, written once and referenced by every fine tile as an external glTF buffer),
//! `impostors/variant_K.png` (each canopy variant's impostor atlas, written once and referenced
//! by every coarse tile), `tiles/c_X_Y.glb` (coarse: each canopy tree as its impostor's cards
//! over a coarse terrain) and `tiles/f_X_Y.glb` (fine: every tree's branch instances over the
//! full terrain).

mod ground;
mod scheme;
mod tileset;

use std::io::Write;
use std::path::{Path, PathBuf};

use rayon::prelude::*;
use serde_json::json;
use sylva_base::file::{FileError, foreign_entry};
use sylva_forest::{Extent, ForestBuilder, ForestError, Rect};

use crate::gltf::CoarseImpostor;
use crate::lod::{CARD_ALPHA_CUTOFF, Impostor, LodChain, TreeLook, cards, variant_tree};
use sylva_terrain::HeightField;

use crate::error::{ExportError, Invalid};
use crate::gltf::{GltfOptions, write_coarse_glb, write_glb, write_shared_geometry};
use ground::{height_range, tile_terrain};
use tileset::{bounding_box, east_north_up};

pub use scheme::{Level, MAX_TILES, TILESET_BYTES_PER_TILE, TileId, TileScheme};

/// What writing tiles produced.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct TileStats {
    /// Tiles written.
    pub tiles: usize,
    /// Trees in them (each tree once per level it appears on).
    pub trees: usize,
    /// Bytes written.
    pub bytes: usize,
    /// Triangles drawn if every tile of the level were shown: coarse and fine.
    pub triangles: [u64; 2],
    /// Bytes per level: coarse and fine (the shared geometry not included).
    pub level_bytes: [usize; 2],
}

/// An error unless `dir` is missing, empty or holds only a tileset's own files
/// (`tileset.json`, `shared.bin`, `tiles/`, `impostors/` and hidden files): a folder with anything else is
/// somebody else's, and writing a world into it would mix the two.
pub fn check_tileset_folder(dir: &Path) -> Result<(), ExportError> {
    let ours = |name: &str| {
        matches!(name, "tileset.json" | "shared.bin" | "tiles" | "impostors")
            || name.starts_with('.')
    };
    match foreign_entry(dir, ours) {
        Some(entry) => Err(ExportError::NotTilesetFolder {
            folder: dir.to_path_buf(),
            entry,
        }),
        None => Ok(()),
    }
}

/// The path of a tile's GLB in a tile folder.
pub fn tile_path(dir: &Path, id: TileId) -> PathBuf {
    dir.join("tiles").join(format!("{id}.glb"))
}

/// Cells of a fine tile's terrain mesh (the coarse tile's is a quarter as dense per side).
const FINE_TERRAIN_CELLS: u32 = 32;

/// Writes one tile of `builder`'s world on `terrain` into `dir` (creating `dir/tiles`):
/// a pure function of the builder's configuration, the terrain, the scheme and the id, so the
/// same tile written by any process is the same bytes. Returns the file's size and the
/// tile's trees and triangles.
pub fn write_tile(
    builder: &ForestBuilder,
    terrain: &(dyn HeightField + Sync),
    scheme: &TileScheme,
    id: TileId,
    dir: &Path,
) -> Result<TileStats, ExportError> {
    let rect = scheme.rect(id)?;
    let folder = dir.join("tiles");
    std::fs::create_dir_all(&folder).map_err(FileError::at(&folder))?;
    let path = tile_path(dir, id);
    let level = usize::from(id.level == Level::Fine);
    match id.level {
        Level::Fine => {
            let mesh = tile_terrain(terrain, rect, FINE_TERRAIN_CELLS, scheme.world);
            // With levels, a tile is a forest file of its own; otherwise it shares geometry.
            let options = GltfOptions {
                shared_geometry: (!scheme.fine_levels).then(|| "../shared.bin".into()),
                ..GltfOptions::default()
            };
            let written = write_glb(builder, terrain, rect, Some(&mesh), &options, &path)?;
            let triangles = (mesh.indices.len() / 3) as u64 + written.triangles;
            let mut stats = TileStats {
                tiles: 1,
                trees: written.trees,
                bytes: written.bytes,
                ..TileStats::default()
            };
            stats.triangles[level] = triangles;
            stats.level_bytes[level] = written.bytes;
            Ok(stats)
        }
        Level::Coarse => {
            let cells = (FINE_TERRAIN_CELLS * scheme.group / 4).max(4);
            let mesh = tile_terrain(terrain, rect, cells, scheme.world);
            let variants = builder.variants();
            // Proxies stand in for canopy trees; seedlings vanish at this distance.
            let trees: Vec<_> = builder
                .trees(terrain, rect)
                .into_iter()
                .filter(|t| !variants[usize::from(t.variant)].seedling)
                .collect();
            let impostors = coarse_impostors(builder)?;
            let bytes =
                write_coarse_glb(&trees, &impostors, &builder.config().species, &mesh, &path)?;
            let per_tree: u64 = impostors
                .iter()
                .flatten()
                .next()
                .map_or(0, |i| i.cards.triangle_count() as u64);
            let mut stats = TileStats {
                tiles: 1,
                trees: trees.len(),
                bytes,
                ..TileStats::default()
            };
            stats.triangles[level] =
                (mesh.indices.len() / 3) as u64 + per_tree * trees.len() as u64;
            stats.level_bytes[level] = bytes;
            Ok(stats)
        }
    }
}

/// The file of variant `k`'s impostor atlas in a tileset's folder.
fn atlas_name(k: usize) -> String {
    format!("impostors/variant_{k}.png")
}

/// Each variant's impostor in coarse tiles: the cards of its tree (the one its atlas is drawn
/// from, seed 1), referring to the atlas [`write_tileset`] writes; none for seedlings.
fn coarse_impostors(builder: &ForestBuilder) -> Result<Vec<Option<CoarseImpostor>>, ExportError> {
    let options = LodChain::default().impostor;
    builder
        .variants()
        .iter()
        .enumerate()
        .map(|(k, v)| {
            if v.seedling {
                return Ok(None);
            }
            let tree = variant_tree(v, 1).map_err(ForestError::from)?;
            let (centre, radius) = Impostor::frame(&tree);
            Ok(Some(CoarseImpostor {
                cards: cards((options.grid, options.view_size), centre, radius),
                species: v.species,
                atlas: format!("../{}", atlas_name(k)),
                cutoff: CARD_ALPHA_CUTOFF,
            }))
        })
        .collect()
}

/// Draws every canopy variant's impostor cards' texture into `dir/impostors/`. Returns their
/// bytes.
fn write_atlases(builder: &ForestBuilder, dir: &Path) -> Result<usize, ExportError> {
    let folder = dir.join("impostors");
    std::fs::create_dir_all(&folder).map_err(FileError::at(&folder))?;
    let species = &builder.config().species;
    let chain = LodChain::default();
    let pngs: Vec<Option<Vec<u8>>> = builder
        .variants()
        .par_iter()
        .map(|v| {
            if v.seedling {
                return Ok(None);
            }
            let tree = variant_tree(v, 1).map_err(ForestError::from)?;
            let look = TreeLook::of(&species[v.species]);
            Ok(Some(
                Impostor::render(&tree, &look, &chain.impostor)
                    .cards_texture()
                    .png(),
            ))
        })
        .collect::<Result<_, ExportError>>()?;
    let mut bytes = 0;
    for (k, png) in pngs.iter().enumerate() {
        if let Some(png) = png {
            sylva_base::file::write(dir.join(atlas_name(k)), |w| w.write_all(png))?;
            bytes += png.len();
        }
    }
    Ok(bytes)
}

/// Where the world sits on the globe and how its levels switch.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct TilesetOptions {
    /// Longitude and latitude (degrees) of the world's origin (its low x, low z corner).
    /// Default: (8.54, 47.37).
    pub origin: (f64, f64),
}

impl Default for TilesetOptions {
    fn default() -> Self {
        TilesetOptions {
            origin: (8.54, 47.37),
        }
    }
}

impl TilesetOptions {
    /// Sets [`TilesetOptions::origin`].
    #[must_use]
    pub fn with_origin(mut self, origin: (f64, f64)) -> Self {
        self.origin = origin;
        self
    }
}

/// The last step: writes `dir/shared.bin` (the geometry every fine tile references, unless
/// the scheme's fine tiles carry their levels and their own geometry), the
/// impostor atlases every coarse tile refers to, and `dir/tileset.json` (3D Tiles 1.1) for the
/// scheme's tiles, which may be written before or after, by any process. Geometric errors: a
/// coarse tile's is the widest crown diameter (what flat cards leave out of a crown seen off
/// their planes), so standard clients (maximum screen-space error 16)
/// switch to fine tiles within about 60 crown diameters; the root's is the coarse tile side.
pub fn write_tileset(
    builder: &ForestBuilder,
    terrain: &(dyn HeightField + Sync),
    scheme: &TileScheme,
    dir: &Path,
    options: &TilesetOptions,
) -> Result<usize, ExportError> {
    std::fs::create_dir_all(dir).map_err(FileError::at(dir))?;
    // Fine tiles with levels hold their own geometry: nothing refers to a shared file.
    let geometry = if scheme.fine_levels {
        0
    } else {
        write_shared_geometry(builder, &dir.join("shared.bin"))?
    };
    let shared = geometry + write_atlases(builder, dir)?;
    let (tallest, widest) = builder
        .variants()
        .iter()
        .map(Extent::of)
        .fold((0.0f32, 0.0f32), |(h, c), e| {
            (h.max(e.height), c.max(e.crown))
        });
    let grown = 1.0 + builder.config().scale_variation.max(0.0);
    let (tallest, widest) = (tallest * grown, widest * grown);
    let volume = |rect: Rect| {
        let (lo, hi) = height_range(terrain, rect);
        bounding_box(
            [rect.min.x - widest, lo - 1.0, rect.min.y - widest],
            [rect.max.x + widest, hi + tallest, rect.max.y + widest],
        )
    };
    let coarse_error = 2.0 * widest;
    let (cx, cy) = scheme.coarse_count();
    let (fx, fy) = scheme.fine_count();
    let mut children = Vec::new();
    for y in 0..cy {
        for x in 0..cx {
            let id = TileId {
                level: Level::Coarse,
                x,
                y,
            };
            let mut fine = Vec::new();
            for j in y * scheme.group..((y + 1) * scheme.group).min(fy) {
                for i in x * scheme.group..((x + 1) * scheme.group).min(fx) {
                    let f = TileId {
                        level: Level::Fine,
                        x: i,
                        y: j,
                    };
                    fine.push(json!({
                        "boundingVolume": volume(scheme.rect(f)?),
                        "geometricError": 0.0,
                        "content": {"uri": format!("tiles/{f}.glb")},
                    }));
                }
            }
            children.push(json!({
                "boundingVolume": volume(scheme.rect(id)?),
                "geometricError": coarse_error,
                "refine": "REPLACE",
                "content": {"uri": format!("tiles/{id}.glb")},
                "children": fine,
            }));
        }
    }
    let side = scheme.tile * scheme.group as f32;
    let tileset = json!({
        "asset": {"version": "1.1", "generator": "sylva"},
        "geometricError": side * 2.0,
        "root": {
            "transform": east_north_up(options.origin.0, options.origin.1),
            "boundingVolume": volume(scheme.world),
            "geometricError": side,
            "refine": "REPLACE",
            "children": children,
        },
    });
    let text = serde_json::to_string_pretty(&tileset).map_err(|e| Invalid::Json(e.to_string()))?;
    sylva_base::file::write(dir.join("tileset.json"), |w| w.write_all(text.as_bytes()))?;
    Ok(shared + text.len())
}
