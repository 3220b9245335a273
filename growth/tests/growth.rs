//! How grown trees answer their environment: walls, neighbours, shade, obstacles, and the
//! grammar's own questions; each as a measured number.

use std::sync::Arc;

use proptest::prelude::*;
use sylva_growth::glam::Vec3;
use sylva_growth::{
    GrownTree, GrowthOptions, Response, Stand, TreeSpec, VoxelGrid, voxelise_triangles,
};
use sylva_turtle::{Command, MeshBuilder, TurtleOptions};

/// A broadleaf of spreading sympodial limbs (`fixtures/broadleaf.lsys`, the bundled oak of
/// before issue 31: these tests measure growth's response, so their tree stays fixed) at
/// `generations`, leaves on `L`.
fn oak(base: Vec3, generations: u32, seed: u64, response: Response) -> TreeSpec {
    let mut turtle = TurtleOptions::default()
        .with_angle(30.0)
        .with_tropism(Vec3::NEG_Y, 0.05);
    turtle.symbols.set('L', Command::Leaf);
    turtle.leaf_size = [0.6, 0.5];
    let grammar = sylva_lsys::LSystem::parse(include_str!("fixtures/broadleaf.lsys")).unwrap();
    TreeSpec {
        base,
        grammar: Arc::new(grammar),
        generations,
        seed,
        start: 0,
        turtle,
        response,
    }
}

fn space() -> VoxelGrid {
    VoxelGrid::new(Vec3::new(-8.0, 0.0, -8.0), Vec3::new(8.0, 12.0, 8.0), 0.1).unwrap()
}

fn grow(grid: VoxelGrid, trees: Vec<TreeSpec>) -> Vec<GrownTree> {
    let mut stand = Stand::new(grid, GrowthOptions::default());
    for t in trees {
        stand.add(t);
    }
    stand.grow().unwrap().0
}

fn quad(grid: &mut VoxelGrid, corners: [Vec3; 4]) {
    voxelise_triangles(grid, &corners, &[0, 1, 2, 0, 2, 3]);
}

/// The space with a plate over all of it at height `y`.
fn under_plate(y: f32) -> VoxelGrid {
    let mut g = space();
    quad(
        &mut g,
        [
            Vec3::new(-8.0, y, -8.0),
            Vec3::new(8.0, y, -8.0),
            Vec3::new(8.0, y, 8.0),
            Vec3::new(-8.0, y, 8.0),
        ],
    );
    g
}

fn end(s: &sylva_growth::GrownSegment) -> Vec3 {
    s.frame.position + s.frame.heading() * s.length
}

#[test]
fn a_tree_beside_a_wall_grows_away_from_it() {
    let alone = grow(space(), vec![oak(Vec3::ZERO, 8, 4, Response::default())]);
    let mut walled = space();
    quad(
        &mut walled,
        [
            Vec3::new(1.2, 0.0, -8.0),
            Vec3::new(1.2, 12.0, -8.0),
            Vec3::new(1.2, 12.0, 8.0),
            Vec3::new(1.2, 0.0, 8.0),
        ],
    );
    let beside = grow(walled, vec![oak(Vec3::ZERO, 8, 4, Response::default())]);
    let (a, b) = (alone[0].centre().unwrap(), beside[0].centre().unwrap());
    eprintln!(
        "crown centre x: alone {:.2}, beside a wall at x = 1.2: {:.2}",
        a.x, b.x
    );
    assert!(b.x < a.x - 0.3, "alone {a}, beside the wall {b}");
    assert!(beside[0].segments.iter().all(|s| end(s).x < 1.2));
}

#[test]
fn trees_planted_close_grow_apart() {
    // The same seed for both: grown alone, their crowns are the same shape 2 m apart.
    let (left, right) = (Vec3::new(-1.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0));
    let l = grow(space(), vec![oak(left, 8, 5, Response::default())]);
    let r = grow(space(), vec![oak(right, 8, 5, Response::default())]);
    let apart = l[0].centre().unwrap().distance(r[0].centre().unwrap());
    let both = grow(
        space(),
        vec![
            oak(left, 8, 5, Response::default()),
            oak(right, 8, 5, Response::default()),
        ],
    );
    let together = both[0]
        .centre()
        .unwrap()
        .distance(both[1].centre().unwrap());
    eprintln!("crown centres {apart:.2} m apart grown alone, {together:.2} m grown together");
    assert!(together > apart + 0.1, "{apart} alone, {together} together");
}

#[test]
fn under_a_canopy_the_shade_tolerant_species_grows_on_and_the_pioneer_stops() {
    let canopy = || under_plate(4.0);
    let size = |grid: VoxelGrid, response: Response| {
        grow(grid, vec![oak(Vec3::ZERO, 8, 7, response)])[0]
            .segments
            .len() as f32
    };
    let pioneer = size(canopy(), Response::pioneer()) / size(space(), Response::pioneer());
    let tolerant =
        size(canopy(), Response::shade_tolerant()) / size(space(), Response::shade_tolerant());
    eprintln!(
        "under the canopy, of their open-sky size: pioneer {pioneer:.2}, shade-tolerant {tolerant:.2}"
    );
    // The canopy also stops both where they reach it; light makes the difference below.
    assert!(pioneer < 0.1, "{pioneer}");
    assert!(tolerant > 0.4 && tolerant > 5.0 * pioneer, "{tolerant}");
}

#[test]
fn growth_is_a_pure_function_of_the_stand() {
    let mesh = || {
        let trees = grow(
            space(),
            vec![
                oak(Vec3::new(-1.0, 0.0, 0.5), 5, 1, Response::default()),
                oak(Vec3::new(1.0, 0.0, -0.5), 5, 2, Response::default()),
            ],
        );
        let mut bytes = Vec::new();
        for t in &trees {
            let mut m = MeshBuilder::new(&TurtleOptions::default());
            t.emit(&mut m);
            let m = m.finish();
            bytes.extend(m.vertices.iter().flat_map(|v| v.position.map(f32::to_bits)));
            bytes.extend(m.bark.iter().copied());
        }
        bytes
    };
    let first = mesh();
    assert!(!first.is_empty());
    assert_eq!(first, mesh());
}

#[test]
fn a_grammar_can_branch_only_where_there_is_light() {
    // A shoot that forks only where the light it reads (E's first parameter) is good.
    let grammar: sylva_lsys::LSystem =
        "axiom: A E(0,0)\nA > E(l,s) : l > 0.6 -> F(0.4)[+(35)A E(0,0)][-(35)A E(0,0)]\nA > E(l,s) : l <= 0.6 -> F(0.4)A\n"
            .parse()
            .unwrap();
    let tree = |base: Vec3| TreeSpec {
        base,
        grammar: Arc::new(grammar.clone()),
        generations: 6,
        seed: 3,
        start: 0,
        turtle: TurtleOptions::default().with_width(0.04),
        response: Response::shade_tolerant(),
    };
    let open = grow(space(), vec![tree(Vec3::ZERO)]);
    let dark = grow(under_plate(1.0), vec![tree(Vec3::ZERO)]);
    let (o, d) = (open[0].segments.len(), dark[0].segments.len());
    eprintln!("segments: {o} in the open, {d} under a plate");
    // In the open every generation forks (up to 2^6 - 1 segments, less any the crowding
    // aborts); in the dark none does.
    assert!((50..=63).contains(&o), "{o}");
    assert!(d <= 6, "{d}");
}

/// Distance from `p` to the box from `lo` to `hi` (0 inside).
fn box_distance(p: Vec3, lo: Vec3, hi: Vec3) -> f32 {
    (lo - p).max(p - hi).max(Vec3::ZERO).length()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    /// No placed segment's swept volume (its capsule) reaches into an obstacle.
    #[test]
    fn no_segment_enters_an_obstacle(
        boxes in prop::collection::vec((-3.0f32..3.0, 0.5f32..5.0, -3.0f32..3.0, 0.2f32..1.5), 1..6),
        seed in 0u64..1000,
    ) {
        let mut grid = space();
        let mut solids = Vec::new();
        for &(x, y, z, half) in &boxes {
            // Keep the trunk's base itself free.
            if x.abs() < half + 0.3 && z.abs() < half + 0.3 && y < half + 0.6 {
                continue;
            }
            let (lo, hi) = (Vec3::new(x, y, z) - half, Vec3::new(x, y, z) + half);
            let c = |i: u32| Vec3::new(
                if i & 1 == 0 { lo.x } else { hi.x },
                if i & 2 == 0 { lo.y } else { hi.y },
                if i & 4 == 0 { lo.z } else { hi.z },
            );
            let corners: Vec<Vec3> = (0..8).map(c).collect();
            let faces = [0, 1, 3, 0, 3, 2, 4, 6, 7, 4, 7, 5, 0, 4, 5, 0, 5, 1, 2, 3, 7, 2, 7, 6, 0, 2, 6, 0, 6, 4, 1, 5, 7, 1, 7, 3];
            voxelise_triangles(&mut grid, &corners, &faces);
            solids.push((lo, hi));
        }
        let trees = grow(grid, vec![oak(Vec3::ZERO, 5, seed, Response::default())]);
        for s in &trees[0].segments {
            let (a, b) = (s.frame.position, end(s));
            for k in 0..=20 {
                let p = a + (b - a) * (k as f32 / 20.0);
                for &(lo, hi) in &solids {
                    prop_assert!(box_distance(p, lo, hi) >= s.end_radius.max(s.start_radius) * 0.999,
                        "segment {a} -> {b} (radius {}) enters the box {lo} .. {hi}", s.end_radius);
                }
            }
        }
    }
}
