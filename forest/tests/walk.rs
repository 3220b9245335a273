//! The guided walk through real forests: never through a trunk, always on the terrain, never
//! stalled, the same walk from the same seed, and the same with trunks generated on demand.

use proptest::prelude::*;
use sylva_forest::{ForestTrunks, GuidedWalk, Rect, TrunkGrid, Trunks, WalkOptions, WalkStep};
use sylva_terrain::HeightField;
use sylva_terrain::glam::Vec2;

const SIDE: f32 = 150.0;
const CANOPY: f32 = 0.5;
const SEEDLING: f32 = 0.25;

/// The forest's trunks as a fixed grid, and the walk's bounds.
fn forest() -> (Vec<(Vec2, f32)>, Rect) {
    let builder = sylva_testkit::builder(11);
    let ground = sylva_testkit::plane(SIDE);
    let (lo, hi) = ground.bounds();
    let bounds = Rect::new(lo, hi);
    let variants = builder.variants();
    let trunks = builder
        .trees(&ground, bounds)
        .iter()
        .map(|t| {
            let young = variants[usize::from(t.variant)].seedling;
            (
                Vec2::new(t.position[0], t.position[2]),
                t.scale * if young { SEEDLING } else { CANOPY },
            )
        })
        .collect();
    (trunks, bounds)
}

fn walk(
    trunks: &mut dyn Trunks,
    bounds: Rect,
    seed: u64,
    steps: usize,
    steer: f32,
) -> Vec<WalkStep> {
    walker(trunks, bounds, seed, steps, steer).1
}

fn walker(
    trunks: &mut dyn Trunks,
    bounds: Rect,
    seed: u64,
    steps: usize,
    steer: f32,
) -> (GuidedWalk, Vec<WalkStep>) {
    let mut w = GuidedWalk::new(bounds, trunks, Vec2::ZERO, seed, WalkOptions::default()).unwrap();
    let steps = (0..steps).map(|_| w.step(trunks, steer)).collect();
    (w, steps)
}

/// The smallest gap between the walker and any trunk's clearance over the walk.
fn least_gap(steps: &[WalkStep], trunks: &[(Vec2, f32)]) -> f32 {
    let mut grid = TrunkGrid::new(trunks.iter().copied(), 5.0);
    let mut near = Vec::new();
    let body = WalkOptions::default().body;
    steps
        .iter()
        .map(|s| {
            near.clear();
            grid.near(s.position, 3.0, &mut near);
            near.iter()
                .map(|(t, r)| s.position.distance(*t) - r - body)
                .fold(f32::INFINITY, f32::min)
        })
        .fold(f32::INFINITY, f32::min)
}

#[test]
fn a_long_walk_keeps_clear_of_trunks_on_the_terrain_and_moving() {
    let (trunks, bounds) = forest();
    assert!(trunks.len() > 1000, "{}", trunks.len());
    let mut grid = TrunkGrid::new(trunks.iter().copied(), 10.0);
    let (walker, steps) = walker(&mut grid, bounds, 3, 10_000, 0.0);
    let gap = least_gap(&steps, &trunks);
    assert!(gap >= -1e-4, "came {gap} m inside a trunk's clearance");
    let margin = WalkOptions::default().margin;
    assert!(steps.iter().all(|s| {
        s.position.cmpge(bounds.min + margin - 1e-3).all()
            && s.position.cmple(bounds.max - margin + 1e-3).all()
    }));
    let moved = steps.iter().filter(|s| s.moved).count();
    assert!(moved >= 9_900, "moved in {moved} of 10000 steps");
    // No stall: every stretch of 300 steps (30 m of walking) gets somewhere.
    for w in steps.windows(300).step_by(50) {
        let d = w[0].position.distance(w[299].position);
        assert!(d > 3.0, "stalled: {d} m in 300 steps");
    }
    // Most targets are reached, not given up.
    let (targets, arrivals) = (walker.targets(), walker.arrivals());
    assert!(
        arrivals >= 5 && 2 * arrivals >= targets,
        "{arrivals} of {targets} targets reached"
    );
    println!(
        "10000 steps: least gap {gap:.3} m, {arrivals} of {targets} targets reached, {moved} steps moved"
    );
    // Turning is bounded (no jitter): consecutive headings differ by little.
    let sharpest = steps
        .windows(2)
        .map(|w| w[0].heading.angle_to(w[1].heading).abs())
        .fold(0.0, f32::max);
    assert!(sharpest < 3.2, "{sharpest}");
}

#[test]
fn walks_are_pure_functions_of_the_seed_and_trunks_on_demand_give_the_same_walk() {
    let (trunks, bounds) = forest();
    let mut grid = TrunkGrid::new(trunks.iter().copied(), 10.0);
    let a = walk(&mut grid, bounds, 8, 3000, 0.0);
    let b = walk(&mut grid, bounds, 8, 3000, 0.0);
    assert!(a == b);
    let c = walk(&mut grid, bounds, 9, 3000, 0.0);
    assert!(a != c);
    let builder = sylva_testkit::builder(11);
    let ground = sylva_testkit::plane(SIDE);
    let mut on_demand = ForestTrunks::by_maturity(&builder, &ground, CANOPY, SEEDLING);
    let d = walk(&mut on_demand, bounds, 8, 3000, 0.0);
    assert!(a == d, "trunks on demand led elsewhere");
}

#[test]
fn steering_bends_the_walk_but_never_through_a_trunk() {
    let (trunks, bounds) = forest();
    let mut grid = TrunkGrid::new(trunks.iter().copied(), 10.0);
    let straight = walk(&mut grid, bounds, 4, 3000, 0.0);
    let left = walk(&mut grid, bounds, 4, 3000, -1.0);
    assert!(straight != left);
    assert!(least_gap(&left, &trunks) >= -1e-4);
}

#[test]
fn bad_options_are_refused() {
    let mut grid = TrunkGrid::new(Vec::new(), 10.0);
    let bounds = Rect::new(Vec2::ZERO, Vec2::splat(100.0));
    let mut o = WalkOptions::default();
    o.step = 0.0;
    assert!(GuidedWalk::new(bounds, &mut grid, Vec2::ZERO, 1, o).is_err());
    let mut o = WalkOptions::default();
    o.margin = 60.0;
    assert!(GuidedWalk::new(bounds, &mut grid, Vec2::ZERO, 1, o).is_err());
    let o = WalkOptions::default();
    assert!(GuidedWalk::new(bounds, &mut grid, Vec2::NAN, 1, o).is_err());
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    /// Over random trunk fields, some dense, the walker never enters a trunk's clearance and
    /// stays inside the walkable area.
    #[test]
    fn never_through_a_trunk(
        trunks in prop::collection::vec((0.0f32..80.0, 0.0f32..80.0, 0.05f32..1.5), 0..400),
        seed in any::<u64>(),
        steer in -1.0f32..1.0,
    ) {
        let trunks: Vec<(Vec2, f32)> = trunks.into_iter().map(|(x, z, r)| (Vec2::new(x, z), r)).collect();
        let mut grid = TrunkGrid::new(trunks.iter().copied(), 7.0);
        let bounds = Rect::new(Vec2::ZERO, Vec2::splat(80.0));
        let steps = walk(&mut grid, bounds, seed, 1500, steer);
        // A start inside a thicket may have no free spot; then nothing is asserted of it.
        let start_gap = least_gap(&steps[..1], &trunks);
        if start_gap >= -1e-4 {
            prop_assert!(least_gap(&steps, &trunks) >= -1e-4);
        }
        let m = WalkOptions::default().margin;
        prop_assert!(steps.iter().all(|s| s.position.cmpge(Vec2::splat(m - 1e-3)).all()
            && s.position.cmple(Vec2::splat(80.0 - m + 1e-3)).all()));
    }
}
