//! Instancing: hero creation per cache size, expansion in placements per second, and the
//! naive baseline in trees per second, for the Kenwood leafy tree and a stochastic tree.

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use sylva::instancing::{Assembler, CompactTree, HeroOptions, Placements, build_cache};
use sylva::lsys::preset;
use sylva::turtle::{MeshBuilder, TurtleOptions, interpret};

fn trees(n: u32) -> Vec<CompactTree> {
    (0..n)
        .map(|i| CompactTree {
            position: [(i % 1000) as f32 * 10.0, 0.0, (i / 1000) as f32 * 10.0],
            yaw: i as f32 * 0.7,
            scale: 1.0,
            seed: i.wrapping_mul(2_654_435_761),
            ..Default::default()
        })
        .collect()
}

fn instancing(c: &mut Criterion) {
    for (name, generations) in [("kenwood-leafy", 7), ("goe-random", 6)] {
        let p = preset(name).expect("bundled");
        let grammar = p.lsystem().expect("parses");
        let turtle = TurtleOptions::default().with_angle(p.angle as f32);
        let options = |mb: usize| {
            HeroOptions::default()
                .with_budget(mb << 20)
                .with_generations(generations)
                .with_turtle(turtle.clone())
        };

        let mut group = c.benchmark_group(format!("heroes/{name}"));
        group.sample_size(10);
        for mb in [16usize, 32] {
            group.throughput(Throughput::Bytes((mb << 20) as u64));
            group.bench_function(format!("{mb}MB"), |b| {
                b.iter(|| build_cache(&grammar, &options(black_box(mb))).expect("fits"))
            });
        }
        group.finish();

        let built = build_cache(&grammar, &options(32)).expect("fits");
        let forest = trees(10_000);
        let mut assembler = Assembler::new();
        let placements: usize = forest
            .iter()
            .map(|t| {
                assembler
                    .expand_with(&built.cache, t, |_, _| {})
                    .expect("complete")
            })
            .sum();
        let mut group = c.benchmark_group(format!("expansion/{name}"));
        group.sample_size(10);
        group.throughput(Throughput::Elements(placements as u64));
        group.bench_function("10k_trees_streamed", |b| {
            b.iter(|| {
                let mut sum = 0.0f32;
                for t in &forest {
                    assembler
                        .expand_with(&built.cache, t, |_, s| sum += s.translation.x)
                        .expect("complete");
                }
                sum
            })
        });
        group.finish();

        let mut group = c.benchmark_group(format!("trees_per_second/{name}"));
        group.sample_size(10);
        group.throughput(Throughput::Elements(10_000));
        group.bench_function("instanced_expanded", |b| {
            b.iter(|| {
                let mut placements = Placements::for_cache(&built.cache);
                assembler
                    .expand(&built.cache, &forest, &mut placements)
                    .expect("complete")
            })
        });
        group.throughput(Throughput::Elements(4));
        // The baseline: derive and mesh every tree from scratch.
        group.bench_function("naive", |b| {
            b.iter(|| {
                forest[..4]
                    .iter()
                    .map(|tree| {
                        let word = grammar
                            .derive(generations, u64::from(tree.seed))
                            .expect("derives");
                        let mut mesh = MeshBuilder::new(&turtle);
                        interpret(&word, &turtle, &mut mesh).expect("meshes");
                        mesh.mesh.vertices.len()
                    })
                    .sum::<usize>()
            })
        });
        group.finish();
    }
}

criterion_group!(benches, instancing);
criterion_main!(benches);
