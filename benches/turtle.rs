//! Meshing throughput: segments per second and bytes of mesh per second, on the Honda tree and
//! the ternary tree, for both branch shapes.

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use sylva::lsys::{Word, preset};
use sylva::turtle::{BranchShape, MeshBuilder, NullSink, TurtleOptions, interpret};

fn trees() -> Vec<(&'static str, Word, TurtleOptions)> {
    ["abop-honda", "abop-ternary"]
        .into_iter()
        .map(|name| {
            let p = preset(name).expect("bundled");
            let generations = if name == "abop-honda" { 14 } else { 7 };
            let word = p
                .lsystem()
                .expect("parses")
                .derive(generations, 0)
                .expect("derives");
            (name, word, TurtleOptions::for_preset(p))
        })
        .collect()
}

fn meshing(c: &mut Criterion) {
    for (name, word, options) in trees() {
        for shape in [BranchShape::Cylinder, BranchShape::Frustum] {
            let options = options.clone().with_shape(shape);
            let mut probe = MeshBuilder::new(&options);
            let stats = interpret(&word, &options, &mut probe).expect("interprets");
            let bytes = probe.mesh.byte_size() as u64;
            let id = format!("{name}/{shape:?}");
            let mut group = c.benchmark_group("meshing_segments");
            group.throughput(Throughput::Elements(u64::from(stats.segments)));
            group.bench_function(&id, |b| {
                b.iter(|| {
                    let mut builder = MeshBuilder::new(&options);
                    interpret(black_box(&word), &options, &mut builder).expect("interprets");
                    builder.finish()
                })
            });
            group.finish();
            let mut group = c.benchmark_group("meshing_bytes");
            group.throughput(Throughput::Bytes(bytes));
            group.bench_function(&id, |b| {
                let mut builder = MeshBuilder::new(&options);
                b.iter(|| {
                    // Reuses the buffers, as a hero-tree loop does.
                    builder.mesh.vertices.clear();
                    builder.mesh.bark.clear();
                    builder.mesh.leaves.clear();
                    interpret(black_box(&word), &options, &mut builder).expect("interprets");
                    builder.mesh.vertices.len()
                })
            });
            group.finish();
        }
        let mut group = c.benchmark_group("turtle_only");
        group.throughput(Throughput::Elements(word.len() as u64));
        group.bench_function(name, |b| {
            b.iter(|| interpret(black_box(&word), &options, &mut NullSink).expect("interprets"))
        });
        group.finish();
    }
}

criterion_group!(benches, meshing);
criterion_main!(benches);
