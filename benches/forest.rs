//! The main job's figures: creating and placing every instance transform of a streamed
//! forest of 10^4, 10^5 and 10^6 trees (the default species, a 128 MB cache, every core),
//! beside the bandwidth bound of the 10^6 trees' placements (a copy of their bytes), and
//! glTF export of 10^4 trees. Hero creation is measured on its own. Painting: one 60 m
//! stroke dragged as 31 mouse moves over a 10^5-tree forest, each move regenerating the trees
//! within reach, then undone.

use std::hint::black_box;
use std::path::Path;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use sylva::export::{GltfOptions, write_glb};
use sylva::forest::{ForestBuilder, ForestConfig, PlacementBlock, Rect, Species};
use sylva::paint::{Brush, BrushAction, ForestPainter, PaintLayer};
use sylva::terrain::glam::Vec2;
use sylva::terrain::{DiamondSquare, EdgeMode, Heightmap};

fn config() -> ForestConfig {
    let species = [
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
    .collect();
    let mut config = ForestConfig::new(species);
    config.budget = 128 << 20;
    config
}

/// A terrain and region holding about `trees` trees (canopy trees and seedlings).
fn ground(builder: &ForestBuilder, trees: usize) -> (Heightmap, Rect) {
    // About one canopy tree per patch plus 1.7 seedlings: size the square for the target.
    let side = (trees as f32 / 2.7).sqrt() * builder.density().patch;
    let mut map = DiamondSquare::new(257)
        .with_spacing(side / 256.0)
        .with_amplitude(side * 0.06)
        .generate()
        .expect("valid");
    map.smooth(2.0, EdgeMode::Mirror).expect("valid");
    (map, Rect::new(Vec2::ZERO, Vec2::splat(side)))
}

/// Places every tree and computes every instance transform, keeping nothing.
fn stream(builder: &ForestBuilder, map: &Heightmap, region: Rect) -> usize {
    let mut checksum = 0.0f32;
    let stats = builder
        .stream(map, region, &mut |block: &PlacementBlock| {
            checksum += block
                .placements
                .last()
                .map_or(0.0, |p| p.transform.translation.x);
            Ok(())
        })
        .expect("streams");
    black_box(checksum);
    stats.placements
}

fn forest(c: &mut Criterion) {
    let mut group = c.benchmark_group("forest");
    group.sample_size(10);
    group.bench_function("hero_caches_128mb", |b| {
        b.iter(|| ForestBuilder::new(black_box(config())).expect("caches fit"))
    });
    let builder = ForestBuilder::new(config()).expect("caches fit");
    for n in [10_000usize, 100_000, 1_000_000] {
        let (map, region) = ground(&builder, n);
        let mut trees = 0;
        builder
            .stream(&map, region, &mut |b: &PlacementBlock| {
                trees += b.trees.len();
                Ok(())
            })
            .expect("streams");
        group.throughput(Throughput::Elements(trees as u64));
        group.bench_function(format!("stream_{n}_trees"), |b| {
            b.iter(|| stream(&builder, &map, region))
        });
        if n == 1_000_000 {
            // The bandwidth bound: the same placements' bytes copied into memory in use, as
            // a consumer's buffer would take them.
            let placements = stream(&builder, &map, region);
            let bytes = placements * size_of::<sylva::forest::Placement>();
            let from = vec![1u8; bytes];
            let mut into = vec![0u8; bytes];
            group.bench_function(format!("copy_placements_{n}_trees"), |b| {
                b.iter(|| into.copy_from_slice(black_box(&from)))
            });
        }
    }
    let (map, region) = ground(&builder, 10_000);
    let mesh = map.mesh(1).expect("valid");
    let exported = builder
        .stream(&map, region, &mut |_: &PlacementBlock| Ok(()))
        .expect("streams")
        .trees;
    group.throughput(Throughput::Elements(exported as u64));
    let path = std::env::temp_dir().join(format!("sylva-bench-{}.glb", std::process::id()));
    group.bench_function("export_glb_10000_trees", |b| {
        b.iter(|| {
            write_glb(
                &builder,
                &map,
                region,
                Some(&mesh),
                &GltfOptions::default(),
                &path,
            )
            .expect("writes")
            .bytes
        })
    });
    let _ = std::fs::remove_file(&path);

    // Painting a 10^5-tree forest: a stroke of 31 mouse moves, then its undo (so every
    // iteration paints the same forest).
    let (map, region) = ground(&builder, 100_000);
    let weights: Vec<f32> = builder.config().species.iter().map(|s| s.weight).collect();
    let layer = PaintLayer::filled(region, 1.0, &weights).expect("layer fits");
    let mut painter = ForestPainter::new(builder.clone(), map, layer).expect("painter");
    let centre = (region.min + region.max) * 0.5;
    let mut brush = Brush::new(BrushAction::Erase, 15.0);
    brush.strength = 0.8;
    group.throughput(Throughput::Elements(painter.tree_count() as u64));
    group.bench_function("paint_stroke_and_undo_100000_trees", |b| {
        b.iter(|| {
            painter.begin_stroke(brush).expect("brush");
            for k in 0..=30 {
                let at = centre + Vec2::new(2.0 * k as f32 - 30.0, 0.0);
                black_box(painter.stroke_to(at).expect("on the terrain"));
            }
            painter.end_stroke();
            painter.undo().expect("undoes")
        })
    });
    group.finish();
}

criterion_group!(benches, forest);
criterion_main!(benches);
