//! `sylva forest`: the main job. A terrain, a few species, a forest of thousands of trees,
//! written as one binary glTF (or USD, or both) and the heightmap as a 16-bit PNG.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use clap::Args;
use serde::Serialize;
use sylva::export::{GltfOptions, UsdOptions, write_glb, write_usda};
use sylva::forest::{ForestBuilder, ForestError, PlacementBlock, Rect};
use sylva::instancing::Assembler;
use sylva::terrain::Heightmap;

use sylva::world::Fit;
use sylva::world::limits::{CELL_SIZE_RANGE, DEFAULT_REGION_SIDE, TERRAIN_MESH_SPACING};

use crate::Failure;
use crate::progress::{ms, peak_rss_mb, phase, print_stats};
use crate::tiles::TilesArgs;
use crate::world::WorldArgs;

/// `sylva forest`'s flags.
#[derive(Debug, Args)]
#[command(
    after_help = "With no flags: an 800 m square of smoothed diamond-square terrain with \
    the five bundled species (oak, birch, spruce, pine, hazel), written to forest.glb and \
    forest_height.png. With --usd forest.usda: the same forest as a USD point instancer (its \
    textures in forest_textures/ beside it) instead of the glTF; add --out for both."
)]
pub(crate) struct ForestArgs {
    #[command(flatten)]
    world: WorldArgs,
    /// The glTF file to write (default forest.glb; with --usd, only when given). With
    /// --whole, the tileset's folder (default forest_tiles).
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    /// Write the whole elevation model (--terrain), up to 20 km a side, as a 3D Tiles world
    /// (as `sylva tiles` does) instead of one GLB of its middle 1000 m.
    #[arg(long, requires = "terrain", conflicts_with_all = ["usd", "no_instancing"])]
    whole: bool,
    /// Also or instead write the forest as USD text (.usda): one point instancer whose
    /// prototypes are the branch instances, for Blender, Houdini, Omniverse, Maya and Unreal.
    #[arg(long, value_name = "FILE")]
    usd: Option<PathBuf>,
    /// The heightmap to write, a 16-bit PNG.
    #[arg(long, value_name = "FILE", default_value = "forest_height.png")]
    heightmap: PathBuf,
    /// Write every placement as a node of its own sharing its mesh, for importers without
    /// EXT_mesh_gpu_instancing (at most 250,000 placements).
    #[arg(long)]
    no_instancing: bool,
    /// Side of the square cells the glTF groups its trees in, metres: a node per cell, so
    /// that engines cull by cell (0: no cells, one instanced node per branch shape for the
    /// whole forest).
    #[arg(long, value_name = "METRES", default_value_t = sylva::export::limits::CELL_SIZE, value_parser = cell_size)]
    cell_size: f32,
    /// Write no levels of detail (the coarser levels and impostors each cell's variant node
    /// declares with MSFT_lod): a smaller file for clients that draw full detail anyway.
    #[arg(long)]
    no_levels: bool,
    /// Print one JSON line of figures instead of the summary (and measure placement alone).
    #[arg(long)]
    stats: bool,
    /// Print nothing but errors.
    #[arg(long, short)]
    quiet: bool,
}

/// `--cell-size`: 0 (no cells), or within [`CELL_SIZE_RANGE`].
fn cell_size(text: &str) -> Result<f32, String> {
    let metres: f32 = text
        .parse()
        .map_err(|_| format!("`{text}` is not a number of metres"))?;
    let (small, large) = CELL_SIZE_RANGE;
    if metres == 0.0 || (small..=large).contains(&metres) {
        Ok(metres)
    } else {
        Err(format!(
            "{metres} m: a cell is {small} m to {large} m wide (or 0 for none)"
        ))
    }
}

/// The figures `--stats` prints.
#[derive(Debug, Serialize)]
struct ForestFigures {
    trees: usize,
    canopy_trees: usize,
    seedlings: usize,
    species: usize,
    area_m: f32,
    patch_m: f32,
    heroes: u32,
    cache_bytes: usize,
    placements: usize,
    placements_per_tree: f64,
    /// Share of the first 10,000 trees whose composition no other of them has.
    distinct_compositions: f64,
    /// Spots the density model proposed, and those the terrain's constraints refused.
    candidate_spots: u64,
    refused_spots: u64,
    empty_placements: usize,
    instance_nodes: usize,
    /// Cells the glTF groups its trees in, and a canopy cell's side.
    cells: usize,
    cell_m: f32,
    /// Levels of detail of a canopy tree in the glTF (full detail and impostor included), and
    /// the impostors' placements (one per tree).
    levels: usize,
    impostor_placements: usize,
    hero_ms: f64,
    placement_ms: f64,
    placements_per_s: f64,
    export_ms: f64,
    export_passes: usize,
    glb_bytes: usize,
    /// Time writing the USD file (0 without --usd).
    usd_ms: f64,
    usd_bytes: u64,
    peak_rss_mb: f64,
    threads: usize,
}

/// What the files written hold: the same forest whichever format.
#[derive(Debug, Default)]
struct Written {
    trees: usize,
    seedlings: usize,
    placements: usize,
    empty_placements: usize,
    /// Instanced meshes (glTF nodes, USD prototypes).
    instances: usize,
    passes: usize,
    glb_bytes: usize,
    usd_bytes: u64,
    usd_images: usize,
    cells: usize,
    cell_m: f32,
    levels: usize,
    impostor_placements: usize,
}

pub(crate) fn run(args: ForestArgs) -> Result<(), Failure> {
    let hidden = args.quiet || args.stats;
    if args.whole {
        let out = args.out.unwrap_or_else(|| PathBuf::from("forest_tiles"));
        return crate::tiles::run(TilesArgs::of_world(args.world, out, args.stats, args.quiet));
    }
    // Every output its own file, checked before any work.
    let glb = match (&args.out, &args.usd) {
        (Some(out), _) => Some(out.clone()),
        (None, None) => Some(PathBuf::from("forest.glb")),
        (None, Some(_)) => None,
    };
    let mut outputs = vec![("--heightmap", args.heightmap.as_path())];
    if let Some(glb) = &glb {
        outputs.push(("--out", glb.as_path()));
    }
    if let Some(usd) = &args.usd {
        outputs.push(("--usd", usd.as_path()));
    }
    crate::outputs::check_outputs(&outputs)?;
    // One file holds a region a desktop viewer opens; a larger model says what it took.
    let world = args.world.world(
        hidden,
        args.quiet,
        Fit::Middle {
            side: DEFAULT_REGION_SIDE,
        },
    )?;
    let (builder, map, region) = (&world.builder, &world.map, world.region);
    let stride = map.stride_for_spacing(TERRAIN_MESH_SPACING);
    let (terrain_mesh, _) = phase(hidden, "meshing terrain", || map.mesh(stride));
    let terrain_mesh = terrain_mesh?;
    // With --stats, one pass that only places every tree and computes every instance
    // transform, keeping nothing: the figure to compare with Kenwood's 4.5 s per million.
    let measured = if args.stats {
        let (measured, time) = phase(true, "placing trees", || measure(builder, map, region));
        Some((measured?, time))
    } else {
        None
    };
    let mut written = Written::default();
    let (glb_written, export_time) = phase(hidden, "placing trees and writing glTF", || {
        let Some(glb) = &glb else {
            return Ok::<_, Failure>(());
        };
        let mut options =
            GltfOptions::default().with_cell_size((args.cell_size > 0.0).then_some(args.cell_size));
        if args.no_levels {
            options = options.with_levels(None);
        }
        options.one_node_per_placement = args.no_instancing;
        let stats = write_glb(builder, map, region, Some(&terrain_mesh), &options, glb)?;
        written = Written {
            trees: stats.trees,
            seedlings: stats.seedlings,
            placements: stats.placements,
            empty_placements: stats.empty_placements,
            instances: stats.instance_nodes,
            passes: stats.passes,
            glb_bytes: stats.bytes,
            cells: stats.cells,
            cell_m: stats.cell_size,
            levels: stats.levels,
            impostor_placements: stats.impostor_placements,
            ..Written::default()
        };
        Ok(())
    });
    glb_written?;
    let (usd_written, usd_time) = phase(hidden, "placing trees and writing USD", || {
        let Some(usd) = &args.usd else {
            return Ok::<_, Failure>(());
        };
        let options = UsdOptions::default();
        let stats = write_usda(builder, map, region, Some(&terrain_mesh), &options, usd)?;
        written = Written {
            trees: stats.trees,
            seedlings: stats.seedlings,
            placements: stats.placements,
            empty_placements: stats.empty_placements,
            instances: stats.prototypes,
            passes: stats.passes,
            usd_bytes: stats.bytes,
            usd_images: stats.images,
            ..written
        };
        Ok(())
    });
    usd_written?;
    write_heightmap(map, &args.heightmap)?;
    let built = builder.stats();
    let side = world.side;
    if let Some((m, placement_time)) = measured {
        let trees = written.trees.max(1) as f64;
        return print_stats(&ForestFigures {
            trees: written.trees,
            canopy_trees: written.trees - written.seedlings,
            seedlings: written.seedlings,
            species: builder.config().species.len(),
            area_m: side,
            patch_m: builder.density().patch,
            heroes: built.heroes,
            cache_bytes: built.cache_bytes,
            placements: written.placements,
            placements_per_tree: m.placements as f64 / trees,
            distinct_compositions: m.distinct,
            candidate_spots: world.siting.candidates,
            refused_spots: world.siting.refused(),
            empty_placements: written.empty_placements,
            instance_nodes: written.instances,
            cells: written.cells,
            cell_m: written.cell_m,
            levels: written.levels,
            impostor_placements: written.impostor_placements,
            hero_ms: ms(world.hero_time),
            placement_ms: ms(placement_time),
            placements_per_s: m.placements as f64 / placement_time.as_secs_f64().max(1e-9),
            export_ms: ms(export_time),
            export_passes: written.passes,
            glb_bytes: written.glb_bytes,
            usd_ms: ms(usd_time),
            usd_bytes: written.usd_bytes,
            peak_rss_mb: peak_rss_mb(),
            threads: rayon::current_num_threads(),
        });
    }
    if args.quiet {
        return Ok(());
    }
    let size = world.region.max - world.region.min;
    println!(
        "sylva forest: {:.0} m x {:.0} m, seed {}",
        size.x, size.y, world.seed
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
        ms(world.hero_time)
    );
    println!("  terrain: {}", world.siting);
    println!(
        "  {} instance placements in {} instanced nodes ({} more of branches with no geometry yet)",
        written.placements, written.instances, written.empty_placements
    );
    if written.cells > 1 || written.levels > 1 {
        println!(
            "  {} cells of {} m; {} levels a tree, down to {} impostors (one a tree)",
            written.cells, written.cell_m, written.levels, written.impostor_placements
        );
    }
    let mb = |bytes: f64| bytes / (1 << 20) as f64;
    if let Some(glb) = &glb {
        println!(
            "wrote {} ({:.1} MB) in {:.0} ms",
            glb.display(),
            mb(written.glb_bytes as f64),
            ms(export_time)
        );
    }
    if let Some(usd) = &args.usd {
        println!(
            "wrote {} ({:.1} MB, a point instancer; {} textures beside it) in {:.0} ms",
            usd.display(),
            mb(written.usd_bytes as f64),
            written.usd_images,
            ms(usd_time)
        );
    }
    println!("wrote {}", args.heightmap.display());
    Ok(())
}

/// Writes `map` as a 16-bit PNG at `path`, whole or not at all.
pub(crate) fn write_heightmap(map: &Heightmap, path: &Path) -> Result<(), Failure> {
    sylva::base::file::write(path, |w| {
        map.write_png16(w)
            .map(|_| ())
            .map_err(std::io::Error::other)
    })?;
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
) -> Result<Measured, ForestError> {
    let mut compositions: HashMap<(u16, u64), u32> = HashMap::new();
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
