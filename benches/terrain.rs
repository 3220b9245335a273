//! Terrain throughput in samples per second at 4097 x 4097: diamond-square, Gaussian
//! smoothing with sigma 4, and meshing.

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use sylva::terrain::{DiamondSquare, EdgeMode};

fn terrain(c: &mut Criterion) {
    let size = 4097usize;
    let mut group = c.benchmark_group("terrain_4097");
    group.sample_size(10);
    group.throughput(Throughput::Elements((size * size) as u64));
    group.bench_function("diamond_square", |b| {
        b.iter(|| {
            DiamondSquare::new(black_box(size))
                .with_seed(7)
                .generate()
                .expect("valid")
        })
    });
    let map = DiamondSquare::new(size)
        .with_seed(7)
        .generate()
        .expect("valid");
    group.bench_function("smooth_sigma_4", |b| {
        b.iter_batched_ref(
            || map.clone(),
            |m| m.smooth(black_box(4.0), EdgeMode::Mirror).expect("valid"),
            criterion::BatchSize::LargeInput,
        )
    });
    group.bench_function("mesh_stride_1", |b| {
        b.iter(|| map.mesh(black_box(1)).expect("valid"))
    });
    group.finish();
}

criterion_group!(benches, terrain);
criterion_main!(benches);
