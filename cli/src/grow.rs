//! `sylva grow`: a stand of trees grown together around an obstacle, with light and collision
//! (the voxel growth paper), written as a binary glTF.

use std::path::{Path, PathBuf};
use std::time::Instant;

use clap::Args;
use serde::Serialize;
use sylva::base::hash::{mix, unit_f32};
use sylva::export::write_stand_glb;
use sylva::forest::{Planting, Species, StandOptions, grow_stand};
use sylva::growth::{Response, read_obj};
use sylva::terrain::dem::ReadOptions;
use sylva::terrain::glam::{Vec2, Vec3};
use sylva::terrain::{DiamondSquare, EdgeMode, HeightField, Heightmap};

use crate::Failure;
use crate::progress::{ms, peak_rss_mb, phase, print_stats};
use crate::world::{parse_pair, read_model};

/// `sylva grow`'s flags.
#[derive(Debug, Args)]
#[command(
    after_help = "Without --obstacle a boulder (a rough icosphere 3 m across) sits in the \
    middle of the stand; trees grow around it and lean away from it and from each other."
)]
pub(crate) struct GrowArgs {
    /// Trees in the stand (1 to 400).
    #[arg(long, value_name = "N", default_value_t = 25)]
    trees: u32,
    /// Metres between neighbouring trees.
    #[arg(long, value_name = "M", default_value_t = 3.5)]
    spacing: f32,
    /// Growth iterations (default: the species' generations).
    #[arg(long, value_name = "G")]
    generations: Option<u32>,
    /// A species file (default: the bundled oak).
    #[arg(long, value_name = "FILE")]
    species: Option<PathBuf>,
    /// Voxel side in metres.
    #[arg(long, value_name = "M", default_value_t = 0.1)]
    voxel: f32,
    /// An obstacle as a Wavefront OBJ, in the stand's metres.
    #[arg(long, value_name = "FILE.obj")]
    obstacle: Option<PathBuf>,
    /// Grow the stand on real ground: an elevation model in any format `sylva forest
    /// --terrain` reads. The stand stands at its middle, or at --at.
    #[arg(long, value_name = "HEIGHTS")]
    terrain: Option<PathBuf>,
    /// Metres between the model's samples (for --terrain): overrides the file's.
    #[arg(long, value_name = "M")]
    terrain_spacing: Option<f32>,
    /// Where the stand's middle stands on the model (for --terrain): metres east and south
    /// of its north-west sample.
    #[arg(long, value_name = "X,Z", value_parser = parse_pair::<f32>)]
    at: Option<(f32, f32)>,
    /// Seed of the ground, the plantings and the boulder.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// The glTF file to write.
    #[arg(long, value_name = "FILE", default_value = "stand.glb")]
    out: PathBuf,
    /// Print one JSON line of figures instead of the summary.
    #[arg(long)]
    stats: bool,
    /// Print nothing but errors.
    #[arg(long, short)]
    quiet: bool,
}

/// The figures `--stats` prints.
#[derive(Debug, Serialize)]
struct GrowFigures {
    trees: usize,
    voxel_m: f32,
    segments: u64,
    deflected: u64,
    aborted: u64,
    stopped: u64,
    light_samples: u64,
    ray_steps: u64,
    iterations: u32,
    grow_ms: f64,
    steps_per_s: f64,
    glb_bytes: usize,
    total_ms: f64,
    peak_rss_mb: f64,
}

/// A uniform number in [0, 1) from a seed and an index.
fn hash(seed: u64, i: u64) -> f32 {
    unit_f32(mix(seed ^ i.wrapping_mul(0x9e37_79b9_7f4a_7c15)))
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
            let n = hash(seed, i as u64);
            // Flattened a little, as boulders settle.
            centre + Vec3::new(d.x, d.y * 0.7, d.z) * radius * (0.85 + 0.3 * n)
        })
        .collect();
    (rough, f.into_iter().flatten().collect())
}

/// The ground of a stand `side` metres square from an elevation model: its heights under
/// the square about `--at` (the model's middle by default), sampled bilinearly onto 65 x 65.
fn real_ground(args: &GrowArgs, file: &Path, side: f32, quiet: bool) -> Result<Heightmap, Failure> {
    let options = ReadOptions {
        spacing: args.terrain_spacing,
        ..ReadOptions::default()
    };
    let model = read_model(file, &options, "--terrain-spacing", quiet)?;
    let [ex, ez] = model.extent();
    let (x, z) = args.at.unwrap_or((ex / 2.0, ez / 2.0));
    let half = side / 2.0;
    if !(x >= half && z >= half && x <= ex - half && z <= ez - half) {
        return Err(Failure::usage(format!(
            "--at {x},{z}: the stand's {side:.0} m square must lie inside the model's {ex:.0} x {ez:.0} m"
        )));
    }
    const SAMPLES: usize = 65;
    let step = side / (SAMPLES - 1) as f32;
    let heights = (0..SAMPLES * SAMPLES)
        .map(|i| {
            let (col, row) = ((i % SAMPLES) as f32, (i / SAMPLES) as f32);
            model.height_at(x - half + col * step, z - half + row * step)
        })
        .collect();
    Ok(Heightmap::from_heights(SAMPLES, step, heights)?)
}

pub(crate) fn run(args: GrowArgs) -> Result<(), Failure> {
    if !(1..=400).contains(&args.trees) {
        return Err(Failure::usage(format!(
            "--trees {}: expected 1 to 400",
            args.trees
        )));
    }
    if !(args.spacing > 0.2 && args.spacing <= 50.0) {
        return Err(Failure::usage(format!(
            "--spacing {}: expected 0.2 to 50 metres",
            args.spacing
        )));
    }
    let hidden = args.quiet || args.stats;
    let total = Instant::now();
    let mut species = match &args.species {
        Some(f) => Species::from_file(f)?,
        None => Species::parse_file(
            include_str!("../../world/species/oak/oak.species"),
            Path::new("world/species/oak/oak.species"),
        )?,
    };
    if let Some(g) = args.generations {
        species.generations = g;
    }
    let side = args.spacing * (args.trees as f32).sqrt().ceil() + 16.0;
    let ground = match &args.terrain {
        Some(file) => real_ground(&args, file, side, hidden)?,
        None => {
            // A stand on gently rolling ground.
            let mut ground = DiamondSquare::new(65)
                .with_seed(args.seed)
                .with_spacing(side / 64.0)
                .with_amplitude(side * 0.03)
                .generate()?;
            ground.smooth(2.0, EdgeMode::Mirror)?;
            ground
        }
    };
    let terrain_mesh = ground.mesh(1)?;
    let middle = Vec2::splat(side * 0.5);
    let obstacle = match &args.obstacle {
        Some(path) => read_obj(path)?,
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
        let jitter = Vec2::new(hash(args.seed, 2 * k), hash(args.seed, 2 * k + 1)) - 0.5;
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
            start: (hash(args.seed ^ 0x5747, k) * 4.0) as u32,
            response: Response::default(),
        });
    }
    let mut options = StandOptions::default();
    options.voxel = args.voxel;
    options.obstacles = vec![obstacle];
    let (stand, grow_time) = phase(hidden, "growing the stand", || {
        grow_stand(
            std::slice::from_ref(&species),
            &plantings,
            &ground,
            &options,
        )
    });
    let stand = stand?;
    let grow_ms = ms(grow_time);
    let path = args.out.as_path();
    let bytes = write_stand_glb(
        &stand,
        std::slice::from_ref(&species),
        Some(&terrain_mesh),
        path,
    )?;
    let s = stand.stats;
    if args.stats {
        return print_stats(&GrowFigures {
            trees: plantings.len(),
            voxel_m: args.voxel,
            segments: s.segments,
            deflected: s.deflected,
            aborted: s.aborted,
            stopped: s.stopped,
            light_samples: s.samples,
            ray_steps: s.ray_steps,
            iterations: s.iterations,
            grow_ms,
            steps_per_s: s.ray_steps as f64 / (grow_ms / 1e3).max(1e-9),
            glb_bytes: bytes,
            total_ms: ms(total.elapsed()),
            peak_rss_mb: peak_rss_mb(),
        });
    }
    if !args.quiet {
        println!(
            "grew {} trees ({} segments; {} deflected, {} aborted, {} stopped by shade) in {grow_ms:.0} ms; wrote {} ({:.1} MB)",
            plantings.len(),
            s.segments,
            s.deflected,
            s.aborted,
            s.stopped,
            args.out.display(),
            bytes as f64 / 1e6
        );
    }
    Ok(())
}
