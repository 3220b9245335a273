//! Terrain throughput in samples per second at 4097 x 4097: diamond-square, Gaussian
//! smoothing with sigma 4, and meshing, each beside the bandwidth bound of its bytes: a copy
//! of as many bytes as it writes (`copy_heights`: a heightmap's 67 MB; `copy_mesh`: a full
//! mesh's 940 MB of vertices and indices, into fresh memory; `copy_mesh_into`: into memory
//! in use, the bound of `mesh_stride_1_into`), measured in the same run.

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use sylva::terrain::{DiamondSquare, EdgeMode, TerrainVertex};

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
    // Meshing again into a mesh in use, as a streamer re-meshing tiles does: no fresh pages.
    let mut reused = map.mesh(1).expect("valid");
    group.bench_function("mesh_stride_1_into", |b| {
        b.iter(|| map.mesh_into(black_box(1), &mut reused).expect("valid"))
    });
    // The bandwidth bounds: the same bytes copied into fresh memory, as the loops above
    // write theirs.
    let heights = map.heights().to_vec();
    group.bench_function("copy_heights", |b| b.iter(|| black_box(&heights).clone()));
    let cells = (size - 1) * (size - 1);
    let mesh_bytes = size * size * size_of::<TerrainVertex>() + cells * 6 * size_of::<u32>();
    let mesh_like = vec![1u8; mesh_bytes];
    group.bench_function("copy_mesh", |b| b.iter(|| black_box(&mesh_like).clone()));
    let mut into = vec![0u8; mesh_bytes];
    group.bench_function("copy_mesh_into", |b| {
        b.iter(|| into.copy_from_slice(black_box(&mesh_like)))
    });
    group.finish();
}

criterion_group!(benches, terrain);
criterion_main!(benches);
