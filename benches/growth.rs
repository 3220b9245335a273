//! Growth's figures: voxel steps per second of light rays with and without the brick
//! hierarchy (in the voxels of a grown stand, where rays really go), and a stand of 25 oaks,
//! the default broadleaf, grown together at 0.1 m voxels with light and collision.

use std::hint::black_box;
use std::path::Path;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use sylva::forest::{Planting, Species, StandOptions, grow_stand};
use sylva::growth::glam::{Vec2, Vec3};
use sylva::growth::{Response, Sky, SunPath, VoxelGrid, march, voxelise_capsule};
use sylva::terrain::FlatPlane;

fn oak() -> Species {
    Species::parse_file(
        include_str!("../world/species/oak/oak.species"),
        Path::new("oak.species"),
    )
    .expect("bundled species parse")
}

/// 25 oaks on a 5 x 5 grid 3.5 m apart.
fn plantings() -> Vec<Planting> {
    (0..25)
        .map(|k| Planting {
            species: 0,
            position: Vec2::new((k % 5) as f32, (k / 5) as f32) * 3.5,
            seed: k,
            start: (k % 3) as u32,
            response: Response::default(),
        })
        .collect()
}

fn ground() -> FlatPlane {
    FlatPlane {
        height: 0.0,
        min: Vec2::splat(-20.0),
        max: Vec2::splat(40.0),
    }
}

fn stand(c: &mut Criterion) {
    let species = [oak()];
    let trees = plantings();
    let mut group = c.benchmark_group("growth");
    group.sample_size(10);
    group.bench_function("stand of 25 oaks at 0.1 m voxels", |b| {
        b.iter(|| {
            grow_stand(
                &species,
                black_box(&trees),
                &ground(),
                &StandOptions::default(),
            )
            .expect("stand grows")
        })
    });
    group.finish();
}

fn rays(c: &mut Criterion) {
    // The voxels of a grown stand: its segments as capsules.
    let species = [oak()];
    let grown = grow_stand(&species, &plantings(), &ground(), &StandOptions::default())
        .expect("stand grows");
    let (lo, hi) = grown.bounds;
    let mut grid = VoxelGrid::new(lo, hi, 0.1).expect("grid");
    for (_, tree) in &grown.trees {
        for s in &tree.segments {
            let end = s.frame.position + s.frame.heading() * s.length;
            voxelise_capsule(&mut grid, s.frame.position, end, s.end_radius);
        }
    }
    let sky = Sky::new(
        SunPath::Arc {
            positions: 9,
            tilt_degrees: 30.0,
        },
        256,
        1,
    );
    // Rays from points in and under the crowns.
    let points: Vec<Vec3> = (0..64)
        .map(|k| {
            Vec3::new(
                (k % 8) as f32 * 2.0,
                1.0 + (k / 8) as f32,
                (k * 5 % 8) as f32 * 2.0,
            )
        })
        .collect();
    let mut group = c.benchmark_group("light rays");
    for (name, hierarchy) in [("with bricks", true), ("voxel by voxel", false)] {
        let steps: u64 = points
            .iter()
            .flat_map(|&p| sky.hemisphere.iter().map(move |&d| (p, d)))
            .map(|(p, d)| u64::from(march(&grid, p, d, hierarchy).steps))
            .sum();
        group.throughput(Throughput::Elements(steps));
        group.bench_function(format!("{name}: 64 points x 256 rays"), |b| {
            b.iter(|| {
                let mut escaped = 0u32;
                for &p in &points {
                    for &d in &sky.hemisphere {
                        escaped += u32::from(march(&grid, p, d, hierarchy).escaped);
                    }
                }
                black_box(escaped)
            })
        });
    }
    group.finish();
}

criterion_group!(benches, stand, rays);
criterion_main!(benches);
