//! The tropism: branches bend towards its direction, a module sets it for its own branch,
//! and thick stems curve along their length under it.

use sylva_turtle::glam::Vec3;
use sylva_turtle::{Skeleton, TurtleOptions, interpret};

fn skeleton(word: &str, options: &TurtleOptions) -> Skeleton {
    let w: sylva_lsys::Word = word.parse().unwrap();
    let mut s = Skeleton::default();
    interpret(&w, options, &mut s).unwrap();
    s
}

#[test]
fn tropism_towards_gravity_bends_a_horizontal_branch_down() {
    let straight = skeleton("&(90)FFFFF", &TurtleOptions::default());
    assert!(straight.bones[4].end.y.abs() < 1e-5);
    let bent = skeleton(
        "&(90)FFFFF",
        &TurtleOptions::default().with_tropism(Vec3::NEG_Y, 0.2),
    );
    assert!(bent.bones[4].end.y < -0.5, "{:?}", bent.bones[4].end);
    let ys: Vec<f32> = bent.bones.iter().map(|b| b.end.y).collect();
    assert!(
        ys.windows(2).all(|w| w[1] < w[0]),
        "keeps bending down: {ys:?}"
    );
}

/// With `curve_steps` a thick stem under a tropism is drawn in pieces that turn a little
/// each, so its heading changes smoothly along its length and ends near where the one-piece
/// stem's does; thin twigs and stems without a tropism stay one piece.
#[test]
fn curved_stems_bend_along_their_length() {
    let droop = TurtleOptions::default().with_tropism(Vec3::NEG_Y, 0.3);
    let word = "!(0.4)&(80)F(2)F(2)[!(0.02)F(1)]";
    let straight = skeleton(word, &droop);
    let curved = skeleton(word, &droop.clone().with_curve_steps(4));
    assert_eq!(straight.bones.len(), 3);
    // Two thick segments of four pieces each; the thin twig stays one piece.
    assert_eq!(curved.bones.len(), 4 + 4 + 1);
    let heading = |b: &sylva_turtle::Bone| (b.end - b.start).normalize();
    let turns = |bones: &[sylva_turtle::Bone]| -> Vec<f32> {
        bones
            .windows(2)
            .map(|w| heading(&w[0]).angle_between(heading(&w[1])).to_degrees())
            .collect()
    };
    let one_piece = turns(&straight.bones[..2])[0];
    let pieces = turns(&curved.bones[..8]);
    assert!(
        pieces.iter().all(|&t| t > 0.0 && t < one_piece * 0.5),
        "each piece turns a little ({pieces:?}), the one-piece joint {one_piece}"
    );
    let (a, b) = (straight.bones[1].end, curved.bones[7].end);
    assert!(a.distance(b) < 0.25 * 4.0, "{a} {b}");
    // Radii run on across the pieces.
    assert!(
        curved.bones[..8]
            .windows(2)
            .all(|w| (w[0].end_radius - w[1].start_radius).abs() < 1e-6)
    );
    // Without a tropism nothing bends, so nothing is cut into pieces.
    let still = skeleton(word, &TurtleOptions::default().with_curve_steps(4));
    assert_eq!(still.bones.len(), 3);
}

/// Tropism set by modules (L-Py's and cpfg's @Tp direction, @Ts susceptibility) bends only
/// the branch it is set in, from where it is set.
#[test]
fn tropism_modules_bend_their_own_branch() {
    use sylva_lsys::{Dialect, LSystem};
    use sylva_turtle::{Skeleton, SymbolTable};
    let plant = LSystem::parse_dialect(
        "module A\nAxiom: [@Tp(1,0,0) @Ts(0.5) F F F F] [F F F F]\nderivation length: 0\nproduction:\nendlsystem",
        Dialect::LPy,
    )
    .unwrap();
    let word = plant.derive(0, 0).unwrap();
    let options = TurtleOptions::default().with_symbols(SymbolTable::for_dialect(Dialect::LPy));
    let mut skeleton = Skeleton::default();
    interpret(&word, &options, &mut skeleton).unwrap();
    let tip = |k: usize| skeleton.bones[k].end;
    // The first branch leans towards +x; the second, after the bracket, grows straight up.
    assert!(tip(3).x > 0.5, "{:?}", tip(3));
    assert!(tip(7).x.abs() < 1e-5, "{:?}", tip(7));
}
