//! Forests over time: a 400 m square of the five bundled species grown from bare ground for
//! 100 years, and one more year of it (its trees at their densest, about 60,000 with the
//! halo's), each on every core.

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use sylva::forest::Rect;
use sylva::forest::succession::{Succession, SuccessionOptions};
use sylva::terrain::glam::Vec2;

fn bare_ground() -> Succession {
    let region = Rect::new(Vec2::ZERO, Vec2::splat(400.0));
    Succession::new(
        sylva::presets::species().expect("bundled species"),
        region,
        SuccessionOptions::default(),
    )
    .expect("valid")
}

fn succession(c: &mut Criterion) {
    let mut group = c.benchmark_group("succession");
    group.sample_size(10);
    group.throughput(Throughput::Elements(100));
    group.bench_function("400m_100_years_from_bare_ground", |b| {
        b.iter(|| {
            let mut forest = bare_ground();
            forest.run(100, |_| Ok(())).expect("runs");
            black_box(forest.stems().len())
        })
    });
    let mut grown = bare_ground();
    grown.run(100, |_| Ok(())).expect("runs");
    group.throughput(Throughput::Elements(grown.stems().len() as u64));
    group.bench_function("400m_one_year_at_100", |b| {
        b.iter_batched(
            || grown.clone(),
            |mut forest| {
                forest.step().expect("a year");
                black_box(forest.stems().len())
            },
            criterion::BatchSize::LargeInput,
        )
    });
    group.finish();
}

criterion_group!(benches, succession);
criterion_main!(benches);
