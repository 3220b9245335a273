//! `sylva paint`: painting a forest headless. A scripted session of brush strokes on the
//! default world, timed, with undo and redo, the masks saved for `sylva forest --paint` and
//! the viewer.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use clap::Args;
use serde::Serialize;
use sylva::base::hash::{mix, unit_f32};
use sylva::forest::{ForestBuilder, ForestConfig, Rect};
use sylva::paint::{Brush, BrushAction, ForestPainter, PaintLayer, save_masks};
use sylva::terrain::HeightField;
use sylva::terrain::glam::Vec2;

use crate::Failure;
use crate::progress::{bar, ms, phase, print_stats};

/// `sylva paint`'s flags.
#[derive(Debug, Args)]
#[command(
    after_help = "It grows the five bundled species over the default terrain (1,100 m a \
    side: about 100,000 trees), from a layer that grows the generated forest everywhere (or \
    from bare ground with --empty), then paints the strokes dragged like a mouse (a point every \
    2 m along 60 m): clearings erased, stands added, stands turned into another species; then \
    undoes and redoes the last five, and saves the masks. Each stroke regenerates only the \
    trees within the density model's reach of the cells it changed."
)]
pub(crate) struct PaintArgs {
    /// Side of the square world in metres.
    #[arg(long, value_name = "METRES", default_value_t = 1100.0)]
    area: f32,
    /// Strokes to paint.
    #[arg(long, value_name = "N", default_value_t = 40)]
    strokes: usize,
    /// Brush radius in metres.
    #[arg(long, value_name = "M", default_value_t = 15.0)]
    radius: f32,
    /// Seed of the world and the session.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Side of a paint cell in metres.
    #[arg(long, value_name = "M", default_value_t = 1.0)]
    cell: f32,
    /// The folder the masks are saved to (replaced whole).
    #[arg(long, value_name = "DIR", default_value = "paint_masks")]
    out: PathBuf,
    /// Start from bare ground instead of the generated forest.
    #[arg(long)]
    empty: bool,
    /// Print one JSON line of figures instead of the summary.
    #[arg(long)]
    stats: bool,
    /// Print nothing but errors.
    #[arg(long, short)]
    quiet: bool,
}

/// The figures `--stats` prints.
#[derive(Debug, Serialize)]
struct PaintFigures {
    area_m: f32,
    trees_at_start: usize,
    trees_painted: usize,
    strokes: usize,
    moves: usize,
    move_ms_median: f64,
    move_ms_max: f64,
    stroke_ms_median: f64,
    stroke_ms_max: f64,
    undo_redo_ms_median: f64,
    tiles_per_move: f64,
    initial_growth_ms: f64,
    threads: usize,
}

/// A uniform value in [0, 1) from a counter (the session is a pure function of the seed).
fn unit(seed: u64, k: u64) -> f32 {
    unit_f32(mix(
        seed ^ k.wrapping_add(1).wrapping_mul(0x9e37_79b9_7f4a_7c15)
    ))
}

/// The median of `v`, in milliseconds.
fn median(v: &mut [Duration]) -> f64 {
    v.sort();
    v.get(v.len() / 2).copied().map_or(0.0, ms)
}

pub(crate) fn run(args: PaintArgs) -> Result<(), Failure> {
    if !(args.area > 50.0 && args.area <= 20_000.0) {
        return Err(Failure::usage(format!(
            "--area {}: expected 50 to 20000 metres",
            args.area
        )));
    }
    if args.strokes == 0 || args.strokes > 100_000 {
        return Err(Failure::usage(format!(
            "--strokes {}: expected 1 to 100000",
            args.strokes
        )));
    }
    let hidden = args.quiet || args.stats;
    let start = Instant::now();
    let mut config = ForestConfig::new(sylva::presets::species()?);
    config.seed = args.seed;
    config.budget = 32 << 20;
    let builder = ForestBuilder::new(config)?;
    let map = sylva::presets::terrain(args.seed, args.area)?;
    let (lo, hi) = map.bounds();
    let bounds = Rect::new(lo, hi);
    let species = &builder.config().species;
    let names: Vec<String> = species.iter().map(|s| s.name.clone()).collect();
    let layer = if args.empty {
        PaintLayer::new(bounds, args.cell, species.len())
    } else {
        let weights: Vec<f32> = species.iter().map(|s| s.weight).collect();
        PaintLayer::filled(bounds, args.cell, &weights)
    }?;
    let setup = start.elapsed();
    let (painter, grown) = phase(hidden, "growing the forest through the paint layer", || {
        ForestPainter::new(builder, map, layer)
    });
    let mut painter = painter?;
    let trees_at_start = painter.tree_count();
    if !hidden {
        println!(
            "{:.0} m x {:.0} m, {} trees grown through the paint layer ({} x {} cells) in {:.0} ms (caches and terrain {:.0} ms)",
            args.area,
            args.area,
            trees_at_start,
            painter.layer().width(),
            painter.layer().depth(),
            ms(grown),
            ms(setup)
        );
    }

    // The session: strokes dragged over 60 m, a point every 2 m, as mouse moves arrive.
    let mut moves = Vec::new();
    let mut strokes = Vec::new();
    let mut regenerated_tiles = 0;
    let progress = bar(hidden, args.strokes as u64, "strokes");
    for k in 0..args.strokes as u64 {
        let action = match k % 3 {
            0 => BrushAction::Erase,
            1 => BrushAction::Add {
                species: (unit(args.seed, 5 * k) * names.len() as f32) as usize % names.len(),
            },
            _ => BrushAction::Species {
                species: (unit(args.seed, 5 * k + 1) * names.len() as f32) as usize % names.len(),
            },
        };
        let mut brush = Brush::new(action, args.radius);
        brush.strength = 0.5 + 0.5 * unit(args.seed, 5 * k + 2);
        let from = Vec2::new(unit(args.seed, 5 * k + 3), unit(args.seed, 5 * k + 4))
            * (hi - lo - 80.0)
            + lo
            + 40.0;
        let heading = Vec2::from_angle(unit(args.seed, 7 * k) * std::f32::consts::TAU);
        let t = Instant::now();
        painter.begin_stroke(brush)?;
        for step in 0..=30 {
            let report = painter.stroke_to(from + heading * (2.0 * step as f32))?;
            moves.push(report.elapsed);
            regenerated_tiles += report.tiles;
        }
        painter.end_stroke();
        strokes.push(t.elapsed());
        progress.inc(1);
    }
    progress.finish_and_clear();
    let trees_painted = painter.tree_count();
    let mut undo = Vec::new();
    for _ in 0..5.min(args.strokes) {
        undo.push(painter.undo().map_or(Duration::ZERO, |r| r.elapsed));
    }
    for _ in 0..5.min(args.strokes) {
        undo.push(painter.redo().map_or(Duration::ZERO, |r| r.elapsed));
    }
    if painter.tree_count() != trees_painted {
        return Err(Failure::job(
            "undo and redo did not give back the painted forest",
        ));
    }
    let out = args.out.as_path();
    let names: Vec<&str> = names.iter().map(String::as_str).collect();
    save_masks(painter.layer(), &names, out)?;
    let slowest = |v: &[Duration]| v.iter().max().copied().map_or(0.0, ms);
    let (most_move, most_stroke) = (slowest(&moves), slowest(&strokes));
    let mean_tiles = regenerated_tiles as f64 / moves.len().max(1) as f64;
    let (move_ms, stroke_ms, undo_ms) =
        (median(&mut moves), median(&mut strokes), median(&mut undo));
    if args.stats {
        return print_stats(&PaintFigures {
            area_m: args.area,
            trees_at_start,
            trees_painted,
            strokes: args.strokes,
            moves: moves.len(),
            move_ms_median: move_ms,
            move_ms_max: most_move,
            stroke_ms_median: stroke_ms,
            stroke_ms_max: most_stroke,
            undo_redo_ms_median: undo_ms,
            tiles_per_move: mean_tiles,
            initial_growth_ms: ms(grown),
            threads: rayon::current_num_threads(),
        });
    }
    if !args.quiet {
        println!(
            "{} strokes of 31 mouse moves (radius {} m): {move_ms:.2} ms per move (median, {most_move:.1} ms at most, {mean_tiles:.1} tiles regenerated), {stroke_ms:.1} ms per stroke (median, {most_stroke:.1} at most); undo/redo {undo_ms:.1} ms",
            args.strokes, args.radius
        );
        println!(
            "{trees_at_start} trees before, {trees_painted} after; masks written to {}/ (export: sylva forest --area {:.0} --paint {})",
            out.display(),
            args.area,
            out.display()
        );
    }
    Ok(())
}
