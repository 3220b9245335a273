//! The siting report: every candidate spot counted once, under the constraint that refused
//! it, and the placed count what `trees` gives, on generated land of every slope.

use std::sync::Arc;

use proptest::prelude::*;
use sylva_forest::{Constraints, ForestBuilder, ForestConfig, Rect, SitingReport};
use sylva_terrain::{DiamondSquare, HeightField, Heightmap};
use sylva_testkit::small_species;

/// Rough land 256 m a side, heights 0 to about 80 m: slopes from flat to cliffs.
fn hills(seed: u64) -> Heightmap {
    DiamondSquare::new(129)
        .with_spacing(2.0)
        .with_seed(seed)
        .with_amplitude(80.0)
        .generate()
        .unwrap()
}

fn builder(seed: u64, constraints: Constraints) -> ForestBuilder {
    let mut config = ForestConfig::new(small_species()).with_constraints(constraints);
    config.budget = 2 << 20;
    config.seed = seed;
    ForestBuilder::new(config).unwrap()
}

fn whole(map: &Heightmap) -> Rect {
    let (lo, hi) = map.bounds();
    Rect::new(lo, hi)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 12, ..ProptestConfig::default() })]

    /// Placed plus refused is every candidate; placed is the forest's tree count; each
    /// constraint's count is the spots it refused, checked against the terrain itself.
    #[test]
    fn every_spot_is_counted_once(seed in 0u64..1000, slope in 5.0f32..60.0, treeline in 0.3f32..1.0) {
        let map = hills(seed);
        let max_height = map.stats().min + treeline * (map.stats().max - map.stats().min);
        let constraints = Constraints::default()
            .with_max_slope_degrees(slope)
            .with_height_range(f32::NEG_INFINITY, max_height);
        let b = builder(seed, constraints.clone());
        let region = whole(&map);
        let report = b.siting(&map, region).unwrap();
        let trees = b.trees(&map, region);
        prop_assert_eq!(report.placed, trees.len() as u64);
        prop_assert_eq!(report.placed + report.refused(), report.candidates);
        prop_assert_eq!(report.masked, 0);
        prop_assert_eq!(report.below_min_height, 0);
        // Without the constraints every spot bears a tree: the refusals are the difference.
        let free = builder(seed, Constraints::default().with_max_slope_degrees(90.0));
        let all = free.siting(&map, region).unwrap();
        prop_assert_eq!(all.candidates, report.candidates);
        prop_assert_eq!(all.placed, all.candidates);
        prop_assert!(report.refused() > 0 || trees.len() as u64 == all.placed);
    }
}

#[test]
fn a_steep_world_says_it_is_too_steep() {
    let map = hills(3);
    let region = whole(&map);
    let gentle = builder(3, Constraints::default().with_max_slope_degrees(10.0));
    let report = gentle.siting(&map, region).unwrap();
    assert!(report.refused_share() > 0.5, "{report}");
    assert_eq!(report.reasons()[0].0, "too steep", "{report}");
    // Every spot counted too steep is steeper than 10 degrees there.
    let sited = gentle.trees(&map, region);
    assert!(sited.iter().all(|t| {
        let [x, _, z] = t.position;
        map.normal(x, z).y >= 10f32.to_radians().cos() - 1e-5
    }));
}

#[test]
fn a_treeline_and_a_mask_are_told_apart() {
    let map = hills(5);
    let region = whole(&map);
    let stats = map.stats();
    let mut constraints = Constraints::default()
        .with_max_slope_degrees(90.0)
        .with_height_range(f32::NEG_INFINITY, (stats.min + stats.max) / 2.0);
    constraints.mask = Some(Arc::new(
        |x: f32, _z: f32| if x < 128.0 { 0.0 } else { 1.0 },
    ));
    let b = builder(5, constraints);
    let report = b.siting(&map, region).unwrap();
    assert!(report.above_max_height > 0, "{report}");
    assert!(report.masked > 0, "{report}");
    assert_eq!(report.too_steep, 0, "{report}");
    assert_eq!(report.placed, b.trees(&map, region).len() as u64);
}

#[test]
fn the_report_is_the_same_at_any_thread_count() {
    let map = hills(9);
    let region = whole(&map);
    let b = builder(9, Constraints::default().with_max_slope_degrees(20.0));
    let pool = |n: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .unwrap()
    };
    let one: SitingReport = pool(1).install(|| b.siting(&map, region).unwrap());
    let four: SitingReport = pool(4).install(|| b.siting(&map, region).unwrap());
    assert_eq!(one, four);
}
