//! The whole job for 10,000 and 100,000 trees: instance caches from hero trees, terrain,
//! placement, expansion into instanced placed; and glTF export at 10,000 trees.

use std::hint::black_box;
use std::path::Path;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use sylva::forest::{Forest, ForestBuilder, ForestConfig, GltfOptions, Rect, Species, write_glb};
use sylva::terrain::glam::Vec2;
use sylva::terrain::{DiamondSquare, EdgeMode, Heightmap};

fn species() -> Vec<Species> {
    [
        (
            "leafy.species",
            include_str!("../examples/species/leafy.species"),
        ),
        (
            "ternary.species",
            include_str!("../examples/species/ternary.species"),
        ),
        (
            "honda.species",
            include_str!("../examples/species/honda.species"),
        ),
    ]
    .iter()
    .map(|(name, text)| Species::parse_file(text, Path::new(name)).expect("bundled species parse"))
    .collect()
}

fn job(trees: usize) -> (Forest, Heightmap, usize) {
    let mut config = ForestConfig::new(species());
    config.budget = 16 << 20;
    let builder = ForestBuilder::new(config).expect("caches fit");
    // About one canopy tree per patch plus seedlings: size the square for the target count.
    let side = (trees as f32 / 2.6).sqrt() * builder.density().patch;
    let mut map = DiamondSquare::new(257)
        .with_spacing(side / 256.0)
        .with_amplitude(side * 0.06)
        .generate()
        .expect("valid");
    map.smooth(2.0, EdgeMode::Mirror).expect("valid");
    let forest = builder.build(&map, Rect::new(Vec2::ZERO, Vec2::splat(side)));
    let placed = forest
        .placements()
        .expect("complete")
        .iter()
        .map(|b| b.placements.count)
        .sum();
    (forest, map, placed)
}

fn whole_job(c: &mut Criterion) {
    let mut group = c.benchmark_group("forest_job");
    group.sample_size(10);
    for n in [10_000usize, 100_000] {
        let (forest, _, _) = job(n);
        group.throughput(Throughput::Elements(forest.trees.len() as u64));
        group.bench_function(format!("{n}_trees"), |b| b.iter(|| job(black_box(n))));
    }
    let (forest, map, _) = job(10_000);
    let placed = forest.placements().expect("complete");
    let mesh = map.mesh(1).expect("valid");
    group.throughput(Throughput::Elements(forest.trees.len() as u64));
    group.bench_function("export_glb_10000_trees", |b| {
        b.iter(|| {
            let mut out = Vec::new();
            write_glb(
                &forest,
                &placed,
                Some(&mesh),
                &GltfOptions::default(),
                &mut out,
            )
            .expect("valid");
            out.len()
        })
    });
    group.finish();
}

criterion_group!(benches, whole_job);
criterion_main!(benches);
