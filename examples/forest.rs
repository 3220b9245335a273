//! The main job: a terrain, a few species, a forest of thousands of trees, written as glTF.
//!
//! ```text
//! cargo run --release --example forest -- [--area METRES | --trees N] [--density TREES_PER_HA]
//!     [--species FILE]... [--budget-mb MB] [--seed S] [--out forest.glb]
//!     [--heightmap forest_height.png] [--stats]
//! ```
//!
//! With no arguments it builds an 800 m square of smoothed diamond-square terrain with five
//! species (oak, birch, spruce, pine and hazel, from `examples/species/`) and writes `forest.glb` and
//! `forest_height.png`. `--stats` prints one JSON line of figures instead of the summary.
//!
//! `--terrain FILE` plants the forest on your own heightmap: a 16-bit PNG (range and spacing
//! from its `sylva:heights` chunk, or `--height-range` and `--spacing`) or a square RAW of
//! little-endian 16-bit samples (`.raw`/`.r16`, with both flags).
//!
//! `--no-instancing` writes every placement as a node of its own sharing its mesh, for
//! importers that ignore EXT_mesh_gpu_instancing (small forests: at most 250,000 placements).
//!
//! `--tiles DIR` writes the world as an OGC 3D Tiles 1.1 tileset instead of one GLB:
//! `DIR/tileset.json`, `DIR/shared.bin` and one GLB per tile (coarse tiles of whole-tree
//! proxies, fine tiles of branch instances). `--tile c_X_Y` or `--tile f_X_Y` writes that tile
//! alone (the same bytes as the whole run writes for it) and `--tileset-only` the root files
//! alone, so that tiles can be jobs on many machines.
//!
//! `--paint DIR` grows a painted forest: the 16-bit PNG masks in DIR (one per species, named
//! after it, as the paint example and the viewer's painting tool save them) decide where each
//! species grows; everything else (spacing, seedlings, export) is as for a generated forest.

mod common;

use std::path::Path;
use std::process::ExitCode;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressStyle};
use sylva::forest::{
    ForestBuilder, ForestConfig, GltfOptions, Level, PlacementBlock, Rect, Species, TileId,
    TileScheme, TileStats, TilesetOptions, tile_path, write_glb, write_tile, write_tileset,
};
use sylva::instancing::Assembler;
use sylva::terrain::glam::Vec2;
use sylva::terrain::{HeightRange, Heightmap};

const USAGE: &str = "usage: forest [--area METRES | --trees N | --terrain HEIGHTS.png|.raw [--spacing M] [--height-range LO,HI]] \
                     [--density TREES_PER_HA] [--species FILE]... [--budget-mb MB] [--seed S] [--out forest.glb] \
                     [--heightmap forest_height.png] [--tiles DIR [--tile-size M] [--tile c_X_Y|f_X_Y | --tileset-only] \
                     [--origin LON,LAT]] [--no-instancing] [--paint MASKS_DIR] [--stats]";

struct Args {
    area: Option<f32>,
    trees: Option<usize>,
    density: Option<f32>,
    species: Vec<String>,
    budget_mb: usize,
    seed: u64,
    out: String,
    heightmap: String,
    stats: bool,
    terrain: Option<String>,
    spacing: Option<f32>,
    height_range: Option<(f32, f32)>,
    tiles: Option<String>,
    tile_size: f32,
    tile: Option<String>,
    tileset_only: bool,
    origin: (f64, f64),
    no_instancing: bool,
    paint: Option<String>,
}

fn parse() -> Result<Args, String> {
    let mut a = Args {
        area: None,
        trees: None,
        density: None,
        species: Vec::new(),
        budget_mb: 32,
        seed: 1,
        out: "forest.glb".into(),
        heightmap: "forest_height.png".into(),
        stats: false,
        terrain: None,
        spacing: None,
        height_range: None,
        tiles: None,
        tile_size: 250.0,
        tile: None,
        tileset_only: false,
        origin: (8.54, 47.37),
        no_instancing: false,
        paint: None,
    };
    let mut it = std::env::args().skip(1);
    while let Some(arg) = it.next() {
        match arg.as_str() {
            "--area" => a.area = Some(common::parse_value("--area", it.next())?),
            "--trees" => a.trees = Some(common::parse_value("--trees", it.next())?),
            "--density" => a.density = Some(common::parse_value("--density", it.next())?),
            "--species" => a.species.push(common::parse_value("--species", it.next())?),
            "--budget-mb" => a.budget_mb = common::parse_value("--budget-mb", it.next())?,
            "--seed" => a.seed = common::parse_value("--seed", it.next())?,
            "--out" => a.out = common::parse_value("--out", it.next())?,
            "--heightmap" => a.heightmap = common::parse_value("--heightmap", it.next())?,
            "--stats" => a.stats = true,
            "--terrain" => a.terrain = Some(common::parse_value("--terrain", it.next())?),
            "--spacing" => a.spacing = Some(common::parse_value("--spacing", it.next())?),
            "--height-range" => {
                let v: String = common::parse_value("--height-range", it.next())?;
                let pair = v
                    .split_once(',')
                    .and_then(|(lo, hi)| Some((lo.trim().parse().ok()?, hi.trim().parse().ok()?)));
                a.height_range =
                    Some(pair.ok_or(format!("--height-range '{v}': expected LO,HI metres"))?);
            }
            "--tiles" => a.tiles = Some(common::parse_value("--tiles", it.next())?),
            "--tile-size" => a.tile_size = common::parse_value("--tile-size", it.next())?,
            "--tile" => a.tile = Some(common::parse_value("--tile", it.next())?),
            "--tileset-only" => a.tileset_only = true,
            "--no-instancing" => a.no_instancing = true,
            "--paint" => a.paint = Some(common::parse_value("--paint", it.next())?),
            "--origin" => {
                let v: String = common::parse_value("--origin", it.next())?;
                let pair = v
                    .split_once(',')
                    .and_then(|(lo, la)| Some((lo.trim().parse().ok()?, la.trim().parse().ok()?)))
                    .filter(|&(lo, la): &(f64, f64)| lo.abs() <= 180.0 && la.abs() <= 90.0);
                a.origin = pair.ok_or(format!(
                    "--origin '{v}': expected LONGITUDE,LATITUDE degrees"
                ))?;
            }
            "--help" | "-h" => common::print_help(USAGE),
            s => return Err(format!("unknown argument {s}\n{USAGE}")),
        }
    }
    if a.area.is_some() && a.trees.is_some() {
        return Err(format!("give --area or --trees, not both\n{USAGE}"));
    }
    if a.terrain.is_some() && (a.area.is_some() || a.trees.is_some()) {
        return Err(format!(
            "--terrain sets the world's size: leave out --area and --trees\n{USAGE}"
        ));
    }
    if (a.tile.is_some() || a.tileset_only) && a.tiles.is_none() {
        return Err(format!(
            "--tile and --tileset-only need --tiles DIR\n{USAGE}"
        ));
    }
    Ok(a)
}

/// Runs `work` under a spinner that shows only if the phase lasts more than a second.
fn phase<T>(quiet: bool, message: &str, work: impl FnOnce() -> T) -> (T, Duration) {
    let bar = if quiet {
        ProgressBar::hidden()
    } else {
        ProgressBar::new_spinner()
    };
    bar.set_style(
        ProgressStyle::with_template("{spinner} {msg} {elapsed}")
            .unwrap_or_else(|_| ProgressStyle::default_spinner()),
    );
    bar.set_message(message.to_string());
    // The first tick comes after a second, so quick phases never draw.
    bar.enable_steady_tick(Duration::from_millis(1000));
    let start = Instant::now();
    let out = work();
    bar.finish_and_clear();
    (out, start.elapsed())
}

fn run() -> Result<(), String> {
    let args = parse()?;
    let species = if args.species.is_empty() {
        sylva::presets::species().map_err(|e| e.to_string())?
    } else {
        args.species
            .iter()
            .map(Species::from_file)
            .collect::<Result<Vec<_>, _>>()
            .map_err(|e| e.to_string())?
    };
    let mut config = ForestConfig::new(species);
    config.seed = args.seed;
    config.budget = args
        .budget_mb
        .checked_mul(1 << 20)
        .filter(|&b| b > 0)
        .ok_or("--budget-mb must be positive")?;
    let (builder, hero_time) = phase(
        args.stats,
        "building instance caches from hero trees",
        || ForestBuilder::new(config),
    );
    let mut builder = builder.map_err(|e| e.to_string())?;
    if let Some(d) = args.density {
        if !(d > 0.0 && d <= 10_000.0) {
            return Err(format!(
                "--density {d}: expected 0 < trees per hectare <= 10000"
            ));
        }
        builder.density_mut().patch = (10_000.0 / d).sqrt();
    }
    let patch = builder.density().patch;
    let side = match (args.area, args.trees) {
        (Some(a), _) if a > 0.0 && a <= 20_000.0 => a,
        (Some(a), _) => {
            return Err(format!(
                "--area {a}: expected a side length from 0 to 20000 metres"
            ));
        }
        (None, Some(n)) if n == 0 || n > 10_000_000 => {
            return Err(format!("--trees {n}: expected 1 to 10000000"));
        }
        (None, Some(n)) => (n as f32).sqrt() * patch,
        (None, None) => 800.0,
    };

    let (terrain, _) = phase(args.stats, "generating terrain", || -> Result<_, String> {
        if let Some(file) = &args.terrain {
            let map = read_terrain(file, args.spacing, args.height_range)?;
            let mesh = map.mesh(1).map_err(|e| e.to_string())?;
            return Ok((map, mesh));
        }
        let map = sylva::presets::terrain(args.seed, side).map_err(|e| e.to_string())?;
        let mesh = map.mesh(1).map_err(|e| e.to_string())?;
        Ok((map, mesh))
    });
    let (map, terrain_mesh) = terrain?;
    let side = if args.terrain.is_some() {
        map.spacing() * (map.size() - 1) as f32
    } else {
        side
    };

    let region = Rect::new(Vec2::ZERO, Vec2::splat(side));
    // A painted forest: the masks stretch over the terrain and decide where each species grows.
    if let Some(dir) = &args.paint {
        builder = builder
            .with_masks(Path::new(dir), &map)
            .map_err(|e| e.to_string())?;
    }
    if let Some(dir) = &args.tiles {
        return write_tiles(&args, &builder, &map, region, Path::new(dir));
    }
    // With --stats, one pass that only places every tree and computes every instance
    // transform, keeping nothing: the figure to compare with Kenwood's 4.5 s per million.
    let measured = if args.stats {
        let (measured, time) = phase(true, "placing trees", || measure(&builder, &map, region));
        Some((measured.map_err(|e| e.to_string())?, time))
    } else {
        None
    };
    let (written, export_time) = phase(
        args.stats,
        "placing trees and writing glTF",
        || -> Result<_, String> {
            let mut options = GltfOptions::default();
            options.one_node_per_placement = args.no_instancing;
            let stats = write_glb(
                &builder,
                &map,
                region,
                Some(&terrain_mesh),
                &options,
                Path::new(&args.out),
            )
            .map_err(|e| e.to_string())?;
            let png = std::fs::File::create(&args.heightmap)
                .map_err(|e| format!("{}: {e}", args.heightmap))?;
            map.write_png16(std::io::BufWriter::new(png))
                .map_err(|e| format!("{}: {e}", args.heightmap))?;
            Ok(stats)
        },
    );
    let written = written?;
    let built = builder.stats();
    let ms = |d: Duration| d.as_secs_f64() * 1e3;
    if let Some((m, placement_time)) = measured {
        let trees = written.trees.max(1) as f64;
        println!(
            "{{\"trees\":{},\"canopy_trees\":{},\"seedlings\":{},\"species\":{},\"area_m\":{side:.1},\"patch_m\":{patch:.2},\"heroes\":{},\"cache_bytes\":{},\"placements\":{},\"placements_per_tree\":{:.2},\"distinct_compositions\":{:.4},\"empty_placements\":{},\"instance_nodes\":{},\"hero_ms\":{:.1},\"placement_ms\":{:.1},\"placements_per_s\":{:.0},\"export_ms\":{:.1},\"export_passes\":{},\"glb_bytes\":{},\"peak_rss_mb\":{:.1},\"kept_bytes_per_tree\":0,\"threads\":{}}}",
            written.trees,
            written.trees - written.seedlings,
            written.seedlings,
            builder.config().species.len(),
            built.heroes,
            built.cache_bytes,
            written.placements,
            m.placements as f64 / trees,
            m.distinct,
            written.empty_placements,
            written.instance_nodes,
            ms(hero_time),
            ms(placement_time),
            m.placements as f64 / placement_time.as_secs_f64(),
            ms(export_time),
            written.passes,
            written.bytes,
            common::peak_rss() as f64 / (1 << 20) as f64,
            rayon_threads(),
        );
    } else {
        println!(
            "sylva forest: {side:.0} m x {side:.0} m, seed {}",
            args.seed
        );
        for (s, c) in builder.config().species.iter().zip(builder.canopies()) {
            println!(
                "  species {:<8} canopy {:.1} m (bound {:.1} m, measured {:.1} m)",
                s.name,
                c.diameter(),
                c.bound,
                c.measured
            );
        }
        println!(
            "  {} trees ({} canopy, {} seedlings); {} heroes, {:.1} MB of instance cache in {:.0} ms",
            written.trees,
            written.trees - written.seedlings,
            written.seedlings,
            built.heroes,
            built.cache_bytes as f64 / (1 << 20) as f64,
            ms(hero_time)
        );
        println!(
            "  {} instance placements in {} instanced meshes ({} more of branches with no geometry yet)",
            written.placements, written.instance_nodes, written.empty_placements
        );
        println!(
            "wrote {} ({:.1} MB) and {} in {:.0} ms",
            args.out,
            written.bytes as f64 / (1 << 20) as f64,
            args.heightmap,
            ms(export_time)
        );
    }
    Ok(())
}

/// Reads a user's heightmap: a 16-bit PNG, or a square RAW of little-endian 16-bit samples.
fn read_terrain(
    file: &str,
    spacing: Option<f32>,
    range: Option<(f32, f32)>,
) -> Result<Heightmap, String> {
    // A 8193 x 8193 map of 16-bit samples is 134 MB; refuse files well beyond any map.
    const MAX_BYTES: u64 = 512 << 20;
    let size = std::fs::metadata(file)
        .map_err(|e| format!("{file}: {e}"))?
        .len();
    if size > MAX_BYTES {
        return Err(format!(
            "{file}: {size} bytes is more than the limit of {MAX_BYTES}"
        ));
    }
    let fallback = match (range, spacing) {
        (Some((min, max)), Some(s)) => Some((HeightRange { min, max }, s)),
        _ => None,
    };
    let raw = file.ends_with(".raw") || file.ends_with(".r16");
    let map = if raw {
        let (range, spacing) = fallback.ok_or(format!(
            "{file}: a RAW heightmap needs --height-range LO,HI and --spacing M"
        ))?;
        let bytes = std::fs::read(file).map_err(|e| format!("{file}: {e}"))?;
        Heightmap::from_raw16(&bytes, range, spacing)
    } else {
        let f = std::fs::File::open(file).map_err(|e| format!("{file}: {e}"))?;
        Heightmap::read_png16(std::io::BufReader::new(f), fallback)
    };
    let map = map.map_err(|e| format!("{file}: {e}"))?;
    let side = map.spacing() * (map.size() - 1) as f32;
    if !(side > 10.0 && side <= 20_000.0) {
        return Err(format!(
            "{file}: a {} x {} map at {} m spacing is {side} m across; expected 10 to 20000 m",
            map.size(),
            map.size(),
            map.spacing()
        ));
    }
    Ok(map)
}

/// The world as a 3D Tiles tileset in `dir`: every tile and the root, or one tile, or the
/// root alone.
fn write_tiles(
    args: &Args,
    builder: &ForestBuilder,
    map: &Heightmap,
    world: Rect,
    dir: &Path,
) -> Result<(), String> {
    let scheme = TileScheme::new(world, args.tile_size, 4).map_err(|e| e.to_string())?;
    // A folder with anything but a tileset's own files is somebody else's: refuse it.
    if let Ok(entries) = std::fs::read_dir(dir) {
        for entry in entries.flatten() {
            let name = entry.file_name().to_string_lossy().into_owned();
            if !matches!(name.as_str(), "tileset.json" | "shared.bin" | "tiles")
                && !name.starts_with('.')
            {
                return Err(format!(
                    "{}: the folder holds '{name}', which is not part of a tileset; give an empty or new folder",
                    dir.display()
                ));
            }
        }
    }
    let mut options = TilesetOptions::default();
    options.origin = args.origin;
    let start = Instant::now();
    if let Some(id) = &args.tile {
        let id: TileId = id
            .parse()
            .map_err(|e: sylva::forest::ForestError| e.to_string())?;
        let s = write_tile(builder, map, &scheme, id, dir).map_err(|e| e.to_string())?;
        println!(
            "wrote {} ({} trees, {:.2} MB) in {:.0} ms",
            tile_path(dir, id).display(),
            s.trees,
            s.bytes as f64 / 1e6,
            start.elapsed().as_secs_f64() * 1e3
        );
        return Ok(());
    }
    let root = write_tileset(builder, map, &scheme, dir, &options).map_err(|e| e.to_string())?;
    if args.tileset_only {
        println!(
            "wrote {}/tileset.json and shared.bin ({:.1} MB)",
            dir.display(),
            root as f64 / 1e6
        );
        return Ok(());
    }
    let ids = scheme.ids();
    let bar = if args.stats {
        ProgressBar::hidden()
    } else {
        ProgressBar::new(ids.len() as u64)
    };
    bar.set_style(
        ProgressStyle::with_template("{bar:30} {pos}/{len} tiles {elapsed}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let mut total = TileStats::default();
    let mut counts = [0usize; 2];
    for id in ids {
        let s = write_tile(builder, map, &scheme, id, dir).map_err(|e| e.to_string())?;
        let level = usize::from(id.level == Level::Fine);
        counts[level] += 1;
        total.tiles += 1;
        total.trees += s.trees;
        total.bytes += s.bytes;
        for k in 0..2 {
            total.triangles[k] += s.triangles[k];
            total.level_bytes[k] += s.level_bytes[k];
        }
        bar.inc(1);
    }
    bar.finish_and_clear();
    let ms = start.elapsed().as_secs_f64() * 1e3;
    if args.stats {
        println!(
            "{{\"tiles\":{},\"coarse_tiles\":{},\"fine_tiles\":{},\"coarse_triangles\":{},\"fine_triangles\":{},\"coarse_bytes\":{},\"fine_bytes\":{},\"shared_and_root_bytes\":{root},\"ms\":{ms:.0},\"peak_rss_mb\":{:.1}}}",
            total.tiles,
            counts[0],
            counts[1],
            total.triangles[0],
            total.triangles[1],
            total.level_bytes[0],
            total.level_bytes[1],
            common::peak_rss() as f64 / (1 << 20) as f64
        );
    } else {
        println!(
            "wrote {} tiles to {} ({} coarse: {} triangles, {:.1} MB; {} fine: {} triangles, {:.1} MB; shared geometry and root {:.1} MB) in {ms:.0} ms",
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

/// What the measuring pass saw.
struct Measured {
    placements: usize,
    /// Share of the first 10,000 trees whose composition no other of them has.
    distinct: f64,
}

/// Streams the forest once, keeping nothing but counts and the compositions of the first
/// 10,000 trees.
fn measure(
    builder: &ForestBuilder,
    map: &Heightmap,
    region: Rect,
) -> Result<Measured, sylva::forest::ForestError> {
    let mut compositions: std::collections::HashMap<(u16, u64), u32> =
        std::collections::HashMap::new();
    let mut sampled = 0usize;
    let mut assembler = Assembler::new();
    let stats = builder.stream(map, region, &mut |block: &PlacementBlock| {
        for tree in &block.trees {
            if sampled == 10_000 {
                break;
            }
            let cache = &builder.variants()[tree.variant as usize].cache;
            let c = assembler.composition(cache, tree)?;
            *compositions.entry((tree.variant, c)).or_insert(0) += 1;
            sampled += 1;
        }
        Ok(())
    })?;
    let unique = compositions.values().filter(|&&n| n == 1).count();
    Ok(Measured {
        placements: stats.placements,
        distinct: unique as f64 / sampled.max(1) as f64,
    })
}

/// Threads the expansion runs on.
fn rayon_threads() -> usize {
    rayon::current_num_threads()
}

fn main() -> ExitCode {
    common::finish(run())
}
