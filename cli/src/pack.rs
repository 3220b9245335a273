//! `sylva pack`: the world's species as an asset pack for engines: each variant's levels of
//! detail and impostor, and the world's trees as placements.

use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use serde::Serialize;
use sylva::export::lod::LodChain;
use sylva::export::write_asset_pack;

use crate::Failure;
use crate::progress::{ms, peak_rss_mb, phase, print_stats};
use crate::world::WorldArgs;

/// `sylva pack`'s flags.
#[derive(Debug, Args)]
#[command(
    after_help = "The folder gets NAME.glb per species variant (a node NAME with children \
    NAME_LOD0, full detail, to NAME_LOD3, the impostor's cards; each child's extras give the \
    distance it is drawn from at 1080p), NAME_impostor_{colour,normal,depth}.png (the \
    hemi-octahedral atlas, described in pack.json), placements.csv and placements.json (every \
    tree of the world: variant, position, yaw, scale, seed) and pack.json. The folder is \
    replaced whole or not at all."
)]
pub(crate) struct PackArgs {
    #[command(flatten)]
    world: WorldArgs,
    /// The pack's folder (new, empty, or an earlier pack's).
    #[arg(long, value_name = "DIR", default_value = "pack")]
    out: PathBuf,
    /// Screen-space error the switch distances allow, in pixels at 1080p.
    #[arg(long, value_name = "PX", default_value_t = 2.0)]
    pixel_error: f32,
    /// Pixels across each view of the impostor atlases (8 x 8 views).
    #[arg(long, value_name = "PX", default_value_t = 128)]
    view_size: u32,
    /// Print one JSON line of figures instead of the summary.
    #[arg(long)]
    stats: bool,
    /// Print nothing but errors.
    #[arg(long, short)]
    quiet: bool,
}

/// The figures `--stats` prints.
#[derive(Debug, Serialize)]
struct PackFigures {
    variants: usize,
    levels: usize,
    trees: usize,
    files: usize,
    bytes: u64,
    ms: f64,
    peak_rss_mb: f64,
}

pub(crate) fn run(args: PackArgs) -> Result<(), Failure> {
    let hidden = args.quiet || args.stats;
    if !(args.pixel_error > 0.0 && args.pixel_error <= 64.0) {
        return Err(Failure::usage(format!(
            "--pixel-error {}: expected pixels above 0 and at most 64",
            args.pixel_error
        )));
    }
    if !(8..=1024).contains(&args.view_size) {
        return Err(Failure::usage(format!(
            "--view-size {}: expected 8 to 1024 pixels",
            args.view_size
        )));
    }
    let world = args.world.world(
        hidden,
        args.quiet,
        sylva::world::Fit::Middle {
            side: sylva::world::limits::DEFAULT_REGION_SIDE,
        },
    )?;
    let mut chain = LodChain::default().with_pixel_error(args.pixel_error);
    chain.impostor = chain.impostor.with_view_size(args.view_size);
    let start = Instant::now();
    let (written, _) = phase(hidden, "levels of detail and impostors", || {
        write_asset_pack(&world.builder, &world.map, world.region, &chain, &args.out)
    });
    let s = written?;
    let elapsed = ms(start.elapsed());
    if args.stats {
        return print_stats(&PackFigures {
            variants: s.variants,
            levels: s.levels,
            trees: s.trees,
            files: s.files,
            bytes: s.bytes,
            ms: elapsed,
            peak_rss_mb: peak_rss_mb(),
        });
    }
    if !args.quiet {
        println!(
            "wrote {} variants ({} levels of detail), {} trees' placements, {} files ({:.1} MB) to {} in {elapsed:.0} ms",
            s.variants,
            s.levels,
            s.trees,
            s.files,
            s.bytes as f64 / 1e6,
            args.out.display()
        );
    }
    Ok(())
}
