//! Grows a stand of trees together around an obstacle, with light and collision (the voxel
//! growth paper), and writes it as a binary glTF.
//!
//! ```text
//! cargo run --release --example grow -- [--trees N] [--spacing M] [--generations G]
//!     [--species FILE] [--voxel M] [--obstacle FILE.obj] [--seed S] [--out stand.glb] [--stats]
//! ```
//!
//! Without `--obstacle` a boulder (a rough icosphere 3 m across) sits in the middle of the
//! stand; trees grow around it and lean away from it and from each other.

mod common;

use std::time::Instant;

use sylva::forest::{Planting, Species, StandOptions, grow_stand, write_stand_glb};
use sylva::growth::{Response, read_obj};
use sylva::terrain::glam::{Vec2, Vec3};
use sylva::terrain::{DiamondSquare, EdgeMode, HeightField};

const USAGE: &str = "usage: grow [--trees N] [--spacing M] [--generations G] [--species FILE] [--voxel M] \
                     [--obstacle FILE.obj] [--seed S] [--out stand.glb] [--stats]";

struct Args {
    trees: u32,
    spacing: f32,
    generations: Option<u32>,
    species: Option<String>,
    voxel: f32,
    obstacle: Option<String>,
    seed: u64,
    out: String,
    stats: bool,
}

fn parse() -> Result<Args, String> {
    let mut a = Args {
        trees: 25,
        spacing: 3.5,
        generations: None,
        species: None,
        voxel: 0.1,
        obstacle: None,
        seed: 1,
        out: "stand.glb".into(),
        stats: false,
    };
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        match flag.as_str() {
            "--trees" => a.trees = common::parse_value("--trees", it.next())?,
            "--spacing" => a.spacing = common::parse_value("--spacing", it.next())?,
            "--generations" => {
                a.generations = Some(common::parse_value("--generations", it.next())?)
            }
            "--species" => a.species = Some(common::parse_value("--species", it.next())?),
            "--voxel" => a.voxel = common::parse_value("--voxel", it.next())?,
            "--obstacle" => a.obstacle = Some(common::parse_value("--obstacle", it.next())?),
            "--seed" => a.seed = common::parse_value("--seed", it.next())?,
            "--out" => a.out = common::parse_value("--out", it.next())?,
            "--stats" => a.stats = true,
            "--help" | "-h" => common::print_help(USAGE),
            other => return Err(format!("unknown argument {other}\n{USAGE}")),
        }
    }
    if !(1..=400).contains(&a.trees) {
        return Err(format!("--trees {}: expected 1 to 400", a.trees));
    }
    if !(a.spacing > 0.2 && a.spacing <= 50.0) {
        return Err(format!(
            "--spacing {}: expected 0.2 to 50 metres",
            a.spacing
        ));
    }
    Ok(a)
}

/// A boulder: an icosahedron subdivided twice, its vertices pushed in and out by a hash so
/// that it reads as rock, `radius` metres, sitting on the ground at `centre`.
fn boulder(centre: Vec3, radius: f32, seed: u64) -> (Vec<Vec3>, Vec<u32>) {
    let t = (1.0 + 5f32.sqrt()) / 2.0;
    let mut p: Vec<Vec3> = [
        (-1.0, t, 0.0),
        (1.0, t, 0.0),
        (-1.0, -t, 0.0),
        (1.0, -t, 0.0),
        (0.0, -1.0, t),
        (0.0, 1.0, t),
        (0.0, -1.0, -t),
        (0.0, 1.0, -t),
        (t, 0.0, -1.0),
        (t, 0.0, 1.0),
        (-t, 0.0, -1.0),
        (-t, 0.0, 1.0),
    ]
    .iter()
    .map(|&(x, y, z)| Vec3::new(x, y, z).normalize())
    .collect();
    let mut f: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..2 {
        let mut next = Vec::new();
        let mut mid = std::collections::HashMap::new();
        let mut midpoint = |a: u32, b: u32, p: &mut Vec<Vec3>| {
            *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                p.push(((p[a as usize] + p[b as usize]) * 0.5).normalize());
                p.len() as u32 - 1
            })
        };
        for [a, b, c] in f {
            let (ab, bc, ca) = (
                midpoint(a, b, &mut p),
                midpoint(b, c, &mut p),
                midpoint(c, a, &mut p),
            );
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        f = next;
    }
    let rough: Vec<Vec3> = p
        .iter()
        .enumerate()
        .map(|(i, &d)| {
            let n = sylva_hash(seed, i as u64);
            // Flattened a little, as boulders settle.
            centre + Vec3::new(d.x, d.y * 0.7, d.z) * radius * (0.85 + 0.3 * n)
        })
        .collect();
    (rough, f.into_iter().flatten().collect())
}

/// A uniform number in [0, 1) from a seed and an index (SplitMix64's finaliser).
fn sylva_hash(seed: u64, i: u64) -> f32 {
    let mut z = seed ^ i.wrapping_mul(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32
}

fn run() -> Result<(), String> {
    let args = parse()?;
    let total = Instant::now();
    let mut species = match &args.species {
        Some(f) => Species::from_file(f).map_err(|e| e.to_string())?,
        None => Species::parse_file(
            include_str!("species/oak.species"),
            std::path::Path::new("examples/species/oak.species"),
        )
        .map_err(|e| e.to_string())?,
    };
    if let Some(g) = args.generations {
        species.generations = g;
    }
    // A stand on gently rolling ground.
    let side = args.spacing * (args.trees as f32).sqrt().ceil() + 16.0;
    let mut ground = DiamondSquare::new(65)
        .with_seed(args.seed)
        .with_spacing(side / 64.0)
        .with_amplitude(side * 0.03)
        .generate()
        .map_err(|e| e.to_string())?;
    ground
        .smooth(2.0, EdgeMode::Mirror)
        .map_err(|e| e.to_string())?;
    let terrain_mesh = ground.mesh(1).map_err(|e| e.to_string())?;
    let middle = Vec2::splat(side * 0.5);
    let obstacle = match &args.obstacle {
        Some(path) => read_obj(path).map_err(|e| e.to_string())?,
        None => boulder(
            Vec3::new(middle.x, ground.height(middle.x, middle.y), middle.y),
            1.5,
            args.seed,
        ),
    };
    // Trees on a jittered grid, leaving the boulder's ground free.
    let per_row = (args.trees as f32).sqrt().ceil() as u32;
    let mut plantings = Vec::new();
    let mut k = 0u64;
    while plantings.len() < args.trees as usize && k < 4 * u64::from(args.trees) + 16 {
        let (i, j) = (
            (k % u64::from(per_row + 1)) as f32,
            (k / u64::from(per_row + 1)) as f32,
        );
        k += 1;
        let jitter = Vec2::new(
            sylva_hash(args.seed, 2 * k),
            sylva_hash(args.seed, 2 * k + 1),
        ) - 0.5;
        let offset = (Vec2::new(i, j) - per_row as f32 * 0.5) * args.spacing;
        let position = middle + offset + jitter * args.spacing * 0.5;
        if position.distance(middle) < 2.2 {
            continue;
        }
        plantings.push(Planting {
            species: 0,
            position,
            seed: args.seed.wrapping_mul(1000).wrapping_add(k),
            // Staggered starts: some trees come up a little later.
            start: (sylva_hash(args.seed ^ 0x5747, k) * 4.0) as u32,
            response: Response::default(),
        });
    }
    let mut options = StandOptions::default();
    options.voxel = args.voxel;
    options.obstacles = vec![obstacle];
    let t = Instant::now();
    let stand = grow_stand(
        std::slice::from_ref(&species),
        &plantings,
        &ground,
        &options,
    )
    .map_err(|e| e.to_string())?;
    let grow_ms = t.elapsed().as_secs_f64() * 1e3;
    let path = std::path::Path::new(&args.out);
    let bytes = write_stand_glb(
        &stand,
        std::slice::from_ref(&species),
        Some(&terrain_mesh),
        path,
    )
    .map_err(|e| e.to_string())?;
    let s = stand.stats;
    if args.stats {
        println!(
            "{{\"trees\":{},\"voxel_m\":{},\"segments\":{},\"deflected\":{},\"aborted\":{},\"stopped\":{},\"light_samples\":{},\"ray_steps\":{},\"iterations\":{},\"grow_ms\":{grow_ms:.1},\"steps_per_s\":{:.0},\"glb_bytes\":{bytes},\"total_ms\":{:.1},\"peak_rss_mb\":{:.1}}}",
            plantings.len(),
            args.voxel,
            s.segments,
            s.deflected,
            s.aborted,
            s.stopped,
            s.samples,
            s.ray_steps,
            s.iterations,
            s.ray_steps as f64 / (grow_ms / 1e3).max(1e-9),
            total.elapsed().as_secs_f64() * 1e3,
            common::peak_rss() as f64 / (1u64 << 20) as f64
        );
    } else {
        println!(
            "grew {} trees ({} segments; {} deflected, {} aborted, {} stopped by shade) in {grow_ms:.0} ms; wrote {} ({:.1} MB)",
            plantings.len(),
            s.segments,
            s.deflected,
            s.aborted,
            s.stopped,
            args.out,
            bytes as f64 / 1e6
        );
    }
    Ok(())
}

fn main() -> std::process::ExitCode {
    common::finish(run())
}
