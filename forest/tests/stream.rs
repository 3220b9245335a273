//! Streamed forests: blocks tile the region, hold the whole forest, keep copies apart, and
//! degenerate regions stream nothing.

use sylva_forest::{ForestBuilder, ForestConfig, ForestError, PlacementBlock, Rect};
use sylva_terrain::glam::Vec2;
use sylva_testkit::{bare_species, builder, export_case, plane, small_species};

/// A streamed forest is the in-memory forest cut into blocks: the same trees and the same
/// placements, in block order.
#[test]
fn streamed_blocks_hold_the_whole_forest() {
    let (b, map, region) = export_case();
    let forest = b.build(&map, region);
    let mut trees = Vec::new();
    let mut placements = 0;
    let stats = b
        .stream(&map, region, &mut |block: &PlacementBlock| {
            trees.extend_from_slice(&block.trees);
            placements += block.placements.len();
            Ok(())
        })
        .unwrap();
    let key = |t: &sylva_instancing::CompactTree| (t.position.map(f32::to_bits), t.seed, t.variant);
    let mut a: Vec<_> = trees.iter().map(key).collect();
    let mut whole: Vec<_> = forest.trees.iter().map(key).collect();
    a.sort_unstable();
    whole.sort_unstable();
    assert_eq!(a, whole);
    let expanded: usize = forest
        .placements()
        .unwrap()
        .iter()
        .map(|v| v.placements.count)
        .sum();
    assert_eq!(placements, expanded);
    assert_eq!(stats.placements, expanded);
    assert!(stats.blocks >= 1 && stats.trees == forest.trees.len());
}

/// No copy beside its copy (Kenwood 7.1): no tree stands within two canopy radii of a tree
/// of the same variant with the same composition.
#[test]
fn no_tree_stands_beside_its_copy() {
    // A cache with at least as many crowns per variant as crown classes (9 for canopy trees,
    // 27 for seedlings): below that the classes cannot all have crowns of their own.
    let mut config = ForestConfig::new(small_species());
    config.budget = 16 << 20;
    config.seed = 3;
    let b = ForestBuilder::new(config).unwrap();
    for v in b.variants().iter() {
        let crowns = v
            .cache
            .lookup(0, 0)
            .iter()
            .filter(|&&i| !v.cache.instances[i as usize].exits.is_empty())
            .count();
        assert!(crowns >= 27, "{crowns} crowns");
    }
    let region = Rect::new(Vec2::splat(-200.0), Vec2::splat(200.0));
    let forest = b.build(&plane(200.0), region);
    let mut assembler = sylva_instancing::Assembler::new();
    let compositions: Vec<u64> = forest
        .trees
        .iter()
        .map(|t| {
            assembler
                .composition(&forest.variants[t.variant as usize].cache, t)
                .unwrap()
        })
        .collect();
    let radius = forest
        .canopies
        .iter()
        .map(|c| c.radius())
        .fold(0.0f32, f32::max);
    let mut near = 0;
    for (i, a) in forest.trees.iter().enumerate() {
        for (j, c) in forest.trees.iter().enumerate().skip(i + 1) {
            let d =
                Vec2::new(a.position[0] - c.position[0], a.position[2] - c.position[2]).length();
            if d < 2.0 * radius && a.variant == c.variant {
                near += 1;
                assert_ne!(
                    compositions[i],
                    compositions[j],
                    "trees {i} and {j} are copies {d} m apart: {a:?} {c:?}, crowns {}",
                    forest.variants[a.variant as usize].cache.lookup(0, 0).len()
                );
            }
        }
    }
    assert!(near > 1_000, "only {near} close pairs checked");
}

/// Regions of no area stream nothing; a patch far too small for the region is refused before
/// anything is allocated; a species whose trees have no geometry is refused.
#[test]
fn degenerate_streams_are_empty_or_errors() {
    let mut b = builder(5);
    let mut blocks = 0;
    let empty = Rect::new(Vec2::splat(10.0), Vec2::splat(10.0));
    let stats = b
        .stream(&plane(100.0), empty, &mut |_: &PlacementBlock| {
            blocks += 1;
            Ok(())
        })
        .unwrap();
    assert_eq!((stats.blocks, stats.trees, blocks), (0, 0, 0));
    let nan = Rect::new(Vec2::splat(f32::NAN), Vec2::splat(10.0));
    assert_eq!(b.blocks(nan).unwrap().len(), 0);
    b.density_mut().patch = 1e-6;
    let huge = Rect::new(Vec2::ZERO, Vec2::splat(20_000.0));
    assert!(matches!(
        b.blocks(huge),
        Err(ForestError::TooManyBlocks { .. })
    ));
    assert!(
        b.stream(&plane(20_000.0), huge, &mut |_: &PlacementBlock| Ok(()))
            .is_err()
    );
    // A species whose trees draw nothing is refused by name.
    let mut config = ForestConfig::new(vec![bare_species()]);
    config.budget = 1 << 20;
    let err = ForestBuilder::new(config).unwrap_err();
    assert!(err.to_string().contains("'bare' draws nothing"), "{err}");
}

/// Blocks tile a region exactly: every tree of the whole region lands in exactly one block,
/// at odd offsets and sizes that do not divide evenly.
#[test]
fn blocks_tile_the_region_without_gaps_or_overlaps() {
    let mut b = builder(11);
    b.density_mut().patch = 3.3; // blocks of 211.2 m
    b.density_mut().seedlings_per_patch = 0;
    let region = Rect::new(Vec2::new(-123.4, 77.7), Vec2::new(401.9, 560.05));
    let blocks = b.blocks(region).unwrap();
    assert_eq!(blocks.len(), 9);
    for pair in blocks.windows(2) {
        if pair[0].min.y == pair[1].min.y {
            assert_eq!(pair[0].max.x, pair[1].min.x);
        }
    }
    assert_eq!(blocks[0].min, region.min);
    assert_eq!(blocks[8].max, region.max);
    let ground = plane(1_000.0);
    let key = |t: &sylva_instancing::CompactTree| (t.position.map(f32::to_bits), t.seed);
    let mut streamed = Vec::new();
    b.stream(&ground, region, &mut |block: &PlacementBlock| {
        streamed.extend(block.trees.iter().map(key));
        Ok(())
    })
    .unwrap();
    let mut whole: Vec<_> = b.trees(&ground, region).iter().map(key).collect();
    streamed.sort_unstable();
    whole.sort_unstable();
    assert!(whole.len() > 1_000, "{} trees", whole.len());
    assert_eq!(streamed, whole);
}
