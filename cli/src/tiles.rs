//! `sylva tiles`: a world as an OGC 3D Tiles 1.1 tileset, whole, one tile at a time (as a job
//! on many machines) or the root alone.

use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use serde::Serialize;
use sylva::export::{
    Level, TileId, TileScheme, TileStats, TilesetOptions, check_tileset_folder, tile_path,
    write_tile, write_tileset,
};

use crate::Failure;
use crate::progress::{bar, ms, peak_rss_mb, print_stats};
use crate::world::{WorldArgs, parse_pair};

/// `sylva tiles`'s flags.
#[derive(Debug, Args)]
#[command(
    after_help = "The folder gets tileset.json, shared.bin (every variant's geometry and \
    the textures, once) and tiles/c_X_Y.glb (coarse: whole-tree proxies) and tiles/f_X_Y.glb \
    (fine: branch instances). A tile is a pure function of the flags and its id: tiles written \
    by separate processes are the same bytes as a whole run's."
)]
pub(crate) struct TilesArgs {
    #[command(flatten)]
    world: WorldArgs,
    /// The tileset's folder (empty, new, or an earlier tileset's).
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    /// Side of a fine tile in metres.
    #[arg(long, value_name = "M", default_value_t = sylva::world::limits::DEFAULT_TILE_SIZE)]
    tile_size: f32,
    /// Fine tiles along each side of a coarse tile (1 to 64): smaller coarse tiles refine to
    /// branches over a smaller area near the camera.
    #[arg(long, value_name = "N", default_value_t = sylva::world::limits::DEFAULT_GROUP)]
    group: u32,
    /// Write this tile alone (c_X_Y or f_X_Y).
    #[arg(long, value_name = "ID", conflicts_with = "tileset_only")]
    tile: Option<String>,
    /// Write the root files alone (tileset.json and shared.bin).
    #[arg(long)]
    tileset_only: bool,
    /// Where the world's origin stands on the globe.
    #[arg(long, value_name = "LON,LAT", default_value = "8.54,47.37", value_parser = parse_origin)]
    origin: (f64, f64),
    /// Fine tiles carry their trees' levels of detail and 64 m cells, as `sylva forest`'s
    /// file does (for sylva-three and Babylon.js to draw a tile within a frame budget), with
    /// their own geometry and textures: larger tiles, and no shared.bin.
    #[arg(long)]
    levels: bool,
    /// Print one JSON line of figures instead of the summary.
    #[arg(long)]
    stats: bool,
    /// Print nothing but errors.
    #[arg(long, short)]
    quiet: bool,
}

impl TilesArgs {
    /// The whole tileset of `world` into `out` (`sylva forest --whole`), every other flag at
    /// its default.
    pub(crate) fn of_world(world: WorldArgs, out: PathBuf, stats: bool, quiet: bool) -> TilesArgs {
        TilesArgs {
            world,
            out,
            tile_size: sylva::world::limits::DEFAULT_TILE_SIZE,
            group: sylva::world::limits::DEFAULT_GROUP,
            tile: None,
            tileset_only: false,
            levels: false,
            origin: (
                sylva::world::limits::DEFAULT_ORIGIN[0],
                sylva::world::limits::DEFAULT_ORIGIN[1],
            ),
            stats,
            quiet,
        }
    }
}

fn parse_origin(v: &str) -> Result<(f64, f64), String> {
    parse_pair::<f64>(v)
        .ok()
        .filter(|&(lo, la)| lo.abs() <= 180.0 && la.abs() <= 90.0)
        .ok_or_else(|| format!("'{v}': expected LONGITUDE,LATITUDE degrees"))
}

/// The figures `--stats` prints.
#[derive(Debug, Serialize)]
struct TilesFigures {
    tiles: usize,
    coarse_tiles: usize,
    fine_tiles: usize,
    coarse_triangles: u64,
    fine_triangles: u64,
    coarse_bytes: usize,
    fine_bytes: usize,
    shared_and_root_bytes: usize,
    ms: f64,
    peak_rss_mb: f64,
}

pub(crate) fn run(args: TilesArgs) -> Result<(), Failure> {
    let hidden = args.quiet || args.stats;
    let dir = args.out.as_path();
    // The folder and the tile id are checked before the world is built.
    check_tileset_folder(dir)?;
    let tile: Option<TileId> = args.tile.as_deref().map(str::parse).transpose()?;
    // A world whose side the flags give is cut into tiles now: a scheme of too many tiles is
    // refused before seconds of hero trees, with what it would cost.
    if let Some(region) = args.world.known_region() {
        TileScheme::new(region, args.tile_size, args.group)?;
    }
    // A tileset streams: it takes a model whole, up to the largest world.
    let world = args
        .world
        .world(hidden, args.quiet, sylva::world::Fit::WHOLE)?;
    let (builder, map) = (&world.builder, &world.map);
    let scheme =
        TileScheme::new(world.region, args.tile_size, args.group)?.with_fine_levels(args.levels);
    let mut options = TilesetOptions::default();
    options.origin = args.origin;
    let start = Instant::now();
    if let Some(id) = tile {
        let s = write_tile(builder, map, &scheme, id, dir)?;
        if !args.quiet {
            println!(
                "wrote {} ({} trees, {:.2} MB) in {:.0} ms",
                tile_path(dir, id).display(),
                s.trees,
                s.bytes as f64 / 1e6,
                ms(start.elapsed())
            );
        }
        return Ok(());
    }
    let root = write_tileset(builder, map, &scheme, dir, &options)?;
    if args.tileset_only {
        if !args.quiet {
            println!(
                "wrote {}/tileset.json and shared.bin ({:.1} MB)",
                dir.display(),
                root as f64 / 1e6
            );
        }
        return Ok(());
    }
    let ids = scheme.ids();
    let progress = bar(hidden, ids.len() as u64, "tiles");
    let mut total = TileStats::default();
    let mut counts = [0usize; 2];
    for id in ids {
        let s = write_tile(builder, map, &scheme, id, dir)?;
        counts[usize::from(id.level == Level::Fine)] += 1;
        total.tiles += 1;
        total.trees += s.trees;
        total.bytes += s.bytes;
        for k in 0..2 {
            total.triangles[k] += s.triangles[k];
            total.level_bytes[k] += s.level_bytes[k];
        }
        progress.inc(1);
    }
    progress.finish_and_clear();
    let elapsed = ms(start.elapsed());
    if args.stats {
        return print_stats(&TilesFigures {
            tiles: total.tiles,
            coarse_tiles: counts[0],
            fine_tiles: counts[1],
            coarse_triangles: total.triangles[0],
            fine_triangles: total.triangles[1],
            coarse_bytes: total.level_bytes[0],
            fine_bytes: total.level_bytes[1],
            shared_and_root_bytes: root,
            ms: elapsed,
            peak_rss_mb: peak_rss_mb(),
        });
    }
    if !args.quiet {
        println!(
            "wrote {} tiles to {} ({} coarse: {} triangles, {:.1} MB; {} fine: {} triangles, {:.1} MB; shared geometry and root {:.1} MB) in {elapsed:.0} ms",
            total.tiles,
            dir.display(),
            counts[0],
            total.triangles[0],
            total.level_bytes[0] as f64 / 1e6,
            counts[1],
            total.triangles[1],
            total.level_bytes[1] as f64 / 1e6,
            root as f64 / 1e6
        );
    }
    Ok(())
}
