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

mod common;

use std::path::Path;
use std::process::ExitCode;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressStyle};
use sylva::forest::{
    ForestBuilder, ForestConfig, GltfOptions, PlacementBlock, Rect, Species, write_glb,
};
use sylva::instancing::Assembler;
use sylva::terrain::glam::Vec2;
use sylva::terrain::{DiamondSquare, EdgeMode, Heightmap};

const USAGE: &str = "usage: forest [--area METRES | --trees N] [--density TREES_PER_HA] [--species FILE]... \
                     [--budget-mb MB] [--seed S] [--out forest.glb] [--heightmap forest_height.png] [--stats]";

const DEFAULT_SPECIES: [(&str, &str); 5] = [
    (
        "examples/species/oak.species",
        include_str!("species/oak.species"),
    ),
    (
        "examples/species/birch.species",
        include_str!("species/birch.species"),
    ),
    (
        "examples/species/spruce.species",
        include_str!("species/spruce.species"),
    ),
    (
        "examples/species/pine.species",
        include_str!("species/pine.species"),
    ),
    (
        "examples/species/hazel.species",
        include_str!("species/hazel.species"),
    ),
];

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
            "--help" | "-h" => common::print_help(USAGE),
            s => return Err(format!("unknown argument {s}\n{USAGE}")),
        }
    }
    if a.area.is_some() && a.trees.is_some() {
        return Err(format!("give --area or --trees, not both\n{USAGE}"));
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
        DEFAULT_SPECIES
            .iter()
            .map(|(path, text)| Species::parse_file(text, Path::new(path)))
            .collect::<Result<Vec<_>, _>>()
    } else {
        args.species.iter().map(Species::from_file).collect()
    }
    .map_err(|e| e.to_string())?;
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
        let ds = DiamondSquare::new(257)
            .with_seed(args.seed)
            .with_spacing(side / 256.0)
            .with_roughness(0.75)
            .with_amplitude(side * 0.06);
        let mut map = ds.generate().map_err(|e| e.to_string())?;
        map.smooth(2.0, EdgeMode::Mirror)
            .map_err(|e| e.to_string())?;
        let mesh = map.mesh(1).map_err(|e| e.to_string())?;
        Ok((map, mesh))
    });
    let (map, terrain_mesh) = terrain?;

    let region = Rect::new(Vec2::ZERO, Vec2::splat(side));
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
            let stats = write_glb(
                &builder,
                &map,
                region,
                Some(&terrain_mesh),
                &GltfOptions::default(),
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
