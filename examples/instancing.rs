//! Builds an instance cache from hero trees and assembles many trees from it.
//!
//! ```text
//! cargo run --release --example instancing -- [--preset kenwood-leafy] [--generations 6]
//!     [--trees 1000000] [--budget-mb 128] [--seed S] [--naive N] [--choices K] [--max-exits E] [--stats]
//! ```
//!
//! `--stats` prints one JSON line of figures. `--naive N` also builds N trees the naive way
//! (derive and mesh each in full) and reports the speedup in trees per second.

mod common;

use std::process::ExitCode;
use std::time::Instant;

use sylva::instancing::{Assembler, CompactTree, HeroOptions, build_cache};
use sylva::lsys::preset;
use sylva::turtle::{MeshBuilder, TurtleOptions, interpret};

struct Args {
    preset: String,
    generations: Option<u32>,
    trees: usize,
    budget_mb: usize,
    seed: u64,
    naive: usize,
    choices: u32,
    max_exits: u32,
    stats: bool,
}

const USAGE: &str = "usage: instancing [--preset NAME] [--generations N] [--trees N] [--budget-mb MB] [--seed S] [--naive N] [--choices K] [--max-exits E] [--stats]";

fn parse() -> Result<Args, String> {
    let mut a = Args {
        preset: "kenwood-leafy".into(),
        generations: None,
        trees: 100_000,
        budget_mb: 128,
        seed: 1,
        naive: 0,
        choices: 2,
        max_exits: 12,
        stats: false,
    };
    let mut it = std::env::args().skip(1);
    while let Some(arg) = it.next() {
        match arg.as_str() {
            "--preset" => a.preset = common::parse_value::<String>("--preset", it.next())?,
            "--generations" => {
                a.generations = Some(common::parse_value("--generations", it.next())?)
            }
            "--trees" => a.trees = common::parse_value("--trees", it.next())?,
            "--budget-mb" => a.budget_mb = common::parse_value("--budget-mb", it.next())?,
            "--seed" => a.seed = common::parse_value("--seed", it.next())?,
            "--naive" => a.naive = common::parse_value("--naive", it.next())?,
            "--choices" => a.choices = common::parse_value("--choices", it.next())?,
            "--max-exits" => a.max_exits = common::parse_value("--max-exits", it.next())?,
            "--stats" => a.stats = true,
            "--help" | "-h" => common::print_help(USAGE),
            s => return Err(format!("unknown argument {s}\n{USAGE}")),
        }
    }
    Ok(a)
}

fn trees(n: usize, seed: u64) -> Vec<CompactTree> {
    let side = (n as f64).sqrt().ceil() as usize;
    (0..n)
        .map(|i| {
            let h = (i as u64 ^ seed).wrapping_mul(0x9e37_79b9_7f4a_7c15);
            CompactTree {
                position: [(i % side) as f32 * 12.0, 0.0, (i / side) as f32 * 12.0],
                yaw: (h >> 40) as f32 / (1u64 << 24) as f32 * std::f32::consts::TAU,
                scale: 0.9 + 0.2 * ((h >> 16) & 0xffff) as f32 / 65535.0,
                seed: (h >> 32) as u32,
                variant: 0,
                crown_class: 0,
                crown_classes: 0,
            }
        })
        .collect()
}

fn run() -> Result<(), String> {
    let args = parse()?;
    let p = preset(&args.preset).ok_or_else(|| format!("no preset called '{}'", args.preset))?;
    let grammar = p.lsystem().map_err(|e| e.to_string())?;
    let generations = args.generations.unwrap_or(p.generations.min(7));
    // Instances are rigid: no tropism for instanced species.
    let mut turtle = TurtleOptions::default()
        .with_angle(p.angle as f32)
        .with_width(0.1);
    turtle.radial_segments = 6;
    let options = HeroOptions::default()
        .with_budget(args.budget_mb << 20)
        .with_generations(generations)
        .with_seed(args.seed)
        .with_turtle(turtle.clone())
        .with_granularity(0.5, args.max_exits);

    let t0 = Instant::now();
    let built = build_cache(&grammar, &options).map_err(|e| e.to_string())?;
    let hero_ms = t0.elapsed().as_secs_f64() * 1e3;

    let t1 = Instant::now();
    let forest = trees(args.trees, args.seed);
    let placement_ms = t1.elapsed().as_secs_f64() * 1e3;

    // Full expansion, streamed so that a million trees need no gigabytes of placements.
    let mut assembler = Assembler::new();
    assembler.limits.choices = args.choices;
    let mut uses = vec![0u32; built.cache.instances.len()];
    let mut checksum = 0.0f32;
    let t2 = Instant::now();
    let mut placements = 0usize;
    for tree in &forest {
        placements += assembler
            .expand_with(&built.cache, tree, |i, t| {
                uses[i as usize] += 1;
                checksum += t.translation.x;
            })
            .map_err(|e| e.to_string())?;
    }
    let expand_s = t2.elapsed().as_secs_f64();
    let max_uses = uses.iter().copied().max().unwrap_or(0);
    // Variety: the share of the first 10,000 trees whose composition no other of them has.
    let sample = &forest[..forest.len().min(10_000)];
    let mut compositions = std::collections::HashMap::new();
    for tree in sample {
        let c = assembler
            .composition(&built.cache, tree)
            .map_err(|e| e.to_string())?;
        *compositions.entry(c).or_insert(0u32) += 1;
    }
    let unique = compositions.values().filter(|&&n| n == 1).count();
    let distinct = unique as f64 / sample.len().max(1) as f64;

    let mut naive_rate = None;
    if args.naive > 0 {
        // The baseline: derive and mesh every tree from scratch.
        let sample = &forest[..args.naive.min(forest.len())];
        let t = Instant::now();
        for tree in sample {
            let word = grammar
                .derive(generations, u64::from(tree.seed))
                .map_err(|e| e.to_string())?;
            let mut mesh = MeshBuilder::new(&turtle);
            interpret(&word, &turtle, &mut mesh).map_err(|e| e.to_string())?;
        }
        naive_rate = Some(sample.len() as f64 / t.elapsed().as_secs_f64());
    }
    let instanced_rate = args.trees as f64 / ((hero_ms + placement_ms) / 1e3 + expand_s);
    let s = &built.stats;
    if args.stats {
        println!(
            "{{\"preset\":\"{}\",\"generations\":{generations},\"trees\":{},\"budget_mb\":{},\"heroes\":{},\"rejected_heroes\":{},\"hero_ms\":{hero_ms:.1},\"placement_ms\":{placement_ms:.1},\"expand_ms\":{:.1},\"cache_bytes\":{},\"instances\":{},\"exits\":{},\"placements\":{placements},\"instances_per_tree\":{:.2},\"compact_bytes_per_tree\":{},\"expanded_bytes_per_tree\":{:.0},\"max_uses\":{max_uses},\"distinct_compositions\":{distinct:.4},\"instanced_ages\":{},\"placements_per_s\":{:.0},\"peak_rss_mb\":{:.1},\"instanced_trees_per_s\":{instanced_rate:.0},\"naive_trees_per_s\":{},\"speedup\":{},\"checksum\":{checksum:.1}}}",
            p.name,
            args.trees,
            args.budget_mb,
            s.heroes,
            s.rejected,
            expand_s * 1e3,
            s.bytes,
            s.instances,
            s.exits,
            placements as f64 / args.trees.max(1) as f64,
            size_of::<CompactTree>(),
            placements as f64 * 32.0 / args.trees.max(1) as f64,
            s.instanced_ages,
            placements as f64 / expand_s,
            common::peak_rss() as f64 / (1 << 20) as f64,
            naive_rate.map_or("null".into(), |r| format!("{r:.1}")),
            naive_rate.map_or("null".into(), |r| format!("{:.0}", instanced_rate / r)),
        );
    } else {
        println!(
            "{} heroes ({} instances, {:.1} MB) in {hero_ms:.0} ms; {} trees placed in {placement_ms:.0} ms; \
             {placements} instance placements expanded in {:.0} ms ({:.1} M/s); most uses of one instance: {max_uses}",
            s.heroes,
            s.instances,
            s.bytes as f64 / (1 << 20) as f64,
            args.trees,
            expand_s * 1e3,
            placements as f64 / expand_s / 1e6
        );
        if let Some(r) = naive_rate {
            println!(
                "naive: {r:.1} trees/s; instanced: {instanced_rate:.0} trees/s ({:.0}x)",
                instanced_rate / r
            );
        }
    }
    Ok(())
}

fn main() -> ExitCode {
    common::finish(run())
}
