//! Damaged trees: a broken stem and thinned leaves.

use proptest::prelude::*;
use sylva_lsys::Word;
use sylva_turtle::{InterpretStats, Skeleton, StemBreak, TurtleOptions, interpret};

fn draw(word: &str, options: &TurtleOptions) -> (Skeleton, InterpretStats) {
    let w: Word = word.parse().unwrap();
    let mut s = Skeleton::default();
    let stats = interpret(&w, options, &mut s).unwrap();
    (s, stats)
}

/// A trunk of four unit segments going up (the default heading is +Y), a branch leaving it
/// at height 1 and another at height 3, each with a leaf at its tip.
const TREE: &str = "F[+FJ]FF[-FJ]FJ";

#[test]
fn a_broken_stem_ends_at_the_break_and_drops_what_it_carried_above() {
    let options = TurtleOptions::default().with_angle(60.0);
    let (whole, stats) = draw(TREE, &options);
    assert_eq!((whole.bones.len(), stats.leaves), (6, 3));
    let snap = StemBreak {
        height: 2.5,
        min_radius: 0.0,
    };
    let (broken, stats) = draw(TREE, &options.clone().with_stem_break(Some(snap)));
    // Kept: the first trunk segment, the branch from height 1, the second segment and half
    // of the third (to the break). Gone: the branch from height 3, the top and its leaf.
    assert_eq!(broken.bones.len(), 4, "{:?}", broken.bones);
    assert_eq!(stats.leaves, 1, "only the low branch's leaf");
    let top = broken
        .bones
        .iter()
        .map(|b| b.end.y)
        .fold(f32::MIN, f32::max);
    assert!(
        (top - 2.5).abs() < 1e-4,
        "the trunk ends at the break: {top}"
    );
    assert!(
        broken
            .bones
            .iter()
            .any(|b| b.start.y < 1.01 && b.end.x.abs() > 0.5)
    );
}

#[test]
fn a_trunk_continued_inside_brackets_breaks_too() {
    // The trunk goes on inside a bracket, as a grammar rewritten for instancing writes it;
    // the thin twig at the bottom (a tenth as thick) reaches past the break unbroken.
    let snap = StemBreak {
        height: 2.5,
        min_radius: 0.2,
    };
    let options = TurtleOptions::default()
        .with_angle(10.0)
        .with_stem_break(Some(snap));
    let (broken, _) = draw("!(1)F[!(0.1)+FFFF][!(1)F[!(1)F[-FJ]F]]", &options);
    let trunk_top = broken
        .bones
        .iter()
        .filter(|b| b.start_radius > 0.2)
        .map(|b| b.end.y)
        .fold(f32::MIN, f32::max);
    assert!(
        (trunk_top - 2.5).abs() < 1e-3,
        "the trunk ends at the break: {trunk_top}"
    );
    assert!(
        broken
            .bones
            .iter()
            .any(|b| b.start_radius < 0.2 && b.end.y > 3.0),
        "the twig reaches on"
    );
}

#[test]
fn a_break_above_the_tree_changes_nothing() {
    let options = TurtleOptions::default().with_angle(60.0);
    let (whole, _) = draw(TREE, &options);
    let snap = StemBreak {
        height: 100.0,
        min_radius: 0.0,
    };
    let (same, _) = draw(TREE, &options.with_stem_break(Some(snap)));
    assert_eq!(whole.bones, same.bones);
}

#[test]
fn no_leaves_kept_draws_bare_wood() {
    let options = TurtleOptions::default().with_leaf_keep(0.0);
    let (bare, stats) = draw(TREE, &options);
    assert_eq!((bare.bones.len(), stats.leaves), (6, 0));
}

proptest! {
    /// The share of leaves drawn follows `leaf_keep`, and the same ones each time.
    #[test]
    fn thinned_leaves_follow_their_share(share in 0.0f32..=1.0) {
        let word = "FJ".repeat(2000);
        let options = TurtleOptions::default().with_leaf_keep(share);
        let (_, a) = draw(&word, &options);
        let (_, b) = draw(&word, &options);
        prop_assert_eq!(a.leaves, b.leaves);
        let drawn = a.leaves as f32 / 2000.0;
        prop_assert!((drawn - share).abs() < 0.05, "{} of leaves drawn for {}", drawn, share);
    }
}
