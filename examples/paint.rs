//! Painting a forest headless: a scripted session of brush strokes on the forest example's
//! world, timed, with undo and redo, the masks saved for the forest example and the viewer.
//!
//! ```text
//! cargo run --release --example paint -- [--area METRES] [--strokes N] [--radius M]
//!     [--seed S] [--cell M] [--out DIR] [--empty] [--stats]
//! ```
//!
//! It grows the forest example's five species over its terrain (1,100 m a side by default:
//! about 100,000 trees), starting from a layer that grows the generated forest everywhere
//! (or from bare ground with `--empty`), then paints N strokes dragged like a mouse (a point
//! every 2 m along 60 m): clearings erased, new stands added, stands turned into another
//! species; then undoes and redoes the last five. Each stroke regenerates only the tiles of
//! trees within the density model's reach of the cells it changed. It prints the time per
//! mouse move and per stroke (median and slowest) and writes the masks to DIR
//! (`paint_masks/` by default): grow and export that forest with
//! `cargo run --release --example forest -- --area 1100 --paint paint_masks`.

mod common;

use std::path::Path;
use std::process::ExitCode;
use std::time::{Duration, Instant};

use sylva::base::hash::{mix, unit_f32};
use sylva::forest::{
    Brush, BrushAction, ForestBuilder, ForestConfig, ForestPainter, PaintLayer, Rect, save_masks,
};
use sylva::terrain::HeightField;
use sylva::terrain::glam::Vec2;

const USAGE: &str = "usage: paint [--area METRES] [--strokes N] [--radius M] [--seed S] [--cell M] [--out DIR] [--empty] [--stats]";

struct Args {
    area: f32,
    strokes: usize,
    radius: f32,
    seed: u64,
    cell: f32,
    out: String,
    empty: bool,
    stats: bool,
}

fn parse() -> Result<Args, String> {
    let mut a = Args {
        area: 1100.0,
        strokes: 40,
        radius: 15.0,
        seed: 1,
        cell: 1.0,
        out: "paint_masks".into(),
        empty: false,
        stats: false,
    };
    let mut it = std::env::args().skip(1);
    while let Some(arg) = it.next() {
        match arg.as_str() {
            "--area" => a.area = common::parse_value("--area", it.next())?,
            "--strokes" => a.strokes = common::parse_value("--strokes", it.next())?,
            "--radius" => a.radius = common::parse_value("--radius", it.next())?,
            "--seed" => a.seed = common::parse_value("--seed", it.next())?,
            "--cell" => a.cell = common::parse_value("--cell", it.next())?,
            "--out" => a.out = common::parse_value("--out", it.next())?,
            "--empty" => a.empty = true,
            "--stats" => a.stats = true,
            "--help" | "-h" => common::print_help(USAGE),
            s => return Err(format!("unknown argument {s}\n{USAGE}")),
        }
    }
    if !(a.area > 50.0 && a.area <= 20_000.0) {
        return Err(format!("--area {}: expected 50 to 20000 metres", a.area));
    }
    if a.strokes == 0 || a.strokes > 100_000 {
        return Err(format!("--strokes {}: expected 1 to 100000", a.strokes));
    }
    Ok(a)
}

/// A uniform value in [0, 1) from a counter (the session is a pure function of the seed).
fn unit(seed: u64, k: u64) -> f32 {
    unit_f32(mix(
        seed ^ k.wrapping_add(1).wrapping_mul(0x9e37_79b9_7f4a_7c15)
    ))
}

fn median(v: &mut [Duration]) -> f64 {
    v.sort();
    v.get(v.len() / 2).map_or(0.0, |d| d.as_secs_f64() * 1e3)
}

fn run() -> Result<(), String> {
    let args = parse()?;
    let start = Instant::now();
    let mut config = ForestConfig::new(sylva::presets::species().map_err(|e| e.to_string())?);
    config.seed = args.seed;
    config.budget = 32 << 20;
    let builder = ForestBuilder::new(config).map_err(|e| e.to_string())?;
    let map = sylva::presets::terrain(args.seed, args.area).map_err(|e| e.to_string())?;
    let (lo, hi) = map.bounds();
    let bounds = Rect::new(lo, hi);
    let species = &builder.config().species;
    let names: Vec<String> = species.iter().map(|s| s.name.clone()).collect();
    let layer = if args.empty {
        PaintLayer::new(bounds, args.cell, species.len())
    } else {
        let weights: Vec<f32> = species.iter().map(|s| s.weight).collect();
        PaintLayer::filled(bounds, args.cell, &weights)
    }
    .map_err(|e| e.to_string())?;
    let setup = start.elapsed();
    let t = Instant::now();
    let mut painter = ForestPainter::new(builder, map, layer).map_err(|e| e.to_string())?;
    let grown = t.elapsed();
    let trees_at_start = painter.tree_count();
    if !args.stats {
        println!(
            "{:.0} m x {:.0} m, {} trees grown through the paint layer ({} x {} cells) in {:.0} ms (caches and terrain {:.0} ms)",
            args.area,
            args.area,
            trees_at_start,
            painter.layer().width(),
            painter.layer().depth(),
            grown.as_secs_f64() * 1e3,
            setup.as_secs_f64() * 1e3
        );
    }

    // The session: strokes dragged over 60 m, a point every 2 m, as mouse moves arrive.
    let mut moves = Vec::new();
    let mut strokes = Vec::new();
    let mut regenerated_tiles = 0;
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
        painter.begin_stroke(brush).map_err(|e| e.to_string())?;
        for step in 0..=30 {
            let report = painter
                .stroke_to(from + heading * (2.0 * step as f32))
                .map_err(|e| e.to_string())?;
            moves.push(report.elapsed);
            regenerated_tiles += report.tiles;
        }
        painter.end_stroke();
        strokes.push(t.elapsed());
    }
    let trees_painted = painter.tree_count();
    let mut undo = Vec::new();
    for _ in 0..5.min(args.strokes) {
        undo.push(painter.undo().map_or(Duration::ZERO, |r| r.elapsed));
    }
    for _ in 0..5.min(args.strokes) {
        undo.push(painter.redo().map_or(Duration::ZERO, |r| r.elapsed));
    }
    if painter.tree_count() != trees_painted {
        return Err("undo and redo did not give back the painted forest".into());
    }
    let out = Path::new(&args.out);
    let names: Vec<&str> = names.iter().map(String::as_str).collect();
    save_masks(painter.layer(), &names, out).map_err(|e| e.to_string())?;
    let slowest = |v: &[Duration]| v.iter().max().map_or(0.0, |d| d.as_secs_f64() * 1e3);
    let (most_move, most_stroke) = (slowest(&moves), slowest(&strokes));
    let mean_tiles = regenerated_tiles as f64 / moves.len().max(1) as f64;
    let (move_ms, stroke_ms, undo_ms) =
        (median(&mut moves), median(&mut strokes), median(&mut undo));
    if args.stats {
        println!(
            "{{\"area_m\":{:.0},\"trees_at_start\":{trees_at_start},\"trees_painted\":{trees_painted},\"strokes\":{},\"moves\":{},\"move_ms_median\":{move_ms:.3},\"move_ms_max\":{most_move:.3},\"stroke_ms_median\":{stroke_ms:.2},\"stroke_ms_max\":{most_stroke:.2},\"undo_redo_ms_median\":{undo_ms:.2},\"tiles_per_move\":{mean_tiles:.1},\"initial_growth_ms\":{:.0},\"threads\":{}}}",
            args.area,
            args.strokes,
            moves.len(),
            grown.as_secs_f64() * 1e3,
            rayon::current_num_threads()
        );
    } else {
        println!(
            "{} strokes of 31 mouse moves (radius {} m): {move_ms:.2} ms per move (median, {most_move:.1} ms at most, {mean_tiles:.1} tiles regenerated), {stroke_ms:.1} ms per stroke (median, {most_stroke:.1} at most); undo/redo {undo_ms:.1} ms",
            args.strokes, args.radius
        );
        println!(
            "{trees_at_start} trees before, {trees_painted} after; masks written to {}/ (export: cargo run --release --example forest -- --area {:.0} --paint {})",
            out.display(),
            args.area,
            out.display()
        );
    }
    Ok(())
}

fn main() -> ExitCode {
    common::finish(run())
}
