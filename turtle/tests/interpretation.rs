//! Known answers and properties of the turtle and its meshes.

use proptest::prelude::*;
use sylva_lsys::{LSystem, Word, preset};
use sylva_turtle::glam::Vec3;
use sylva_turtle::{
    BranchShape, GeometrySink, MeshBuilder, NullSink, Skeleton, TurtleError, TurtleOptions,
    interpret, write_obj,
};

fn skeleton(word: &str, options: &TurtleOptions) -> Skeleton {
    let w: Word = word.parse().unwrap();
    let mut s = Skeleton::default();
    interpret(&w, options, &mut s).unwrap();
    s
}

fn mesh(word: &str, options: &TurtleOptions) -> sylva_turtle::Mesh {
    let w: Word = word.parse().unwrap();
    let mut b = MeshBuilder::new(options);
    interpret(&w, options, &mut b).unwrap();
    b.finish()
}

#[test]
fn square_ends_where_it_started() {
    let s = skeleton("F+F+F+F", &TurtleOptions::default().with_angle(90.0));
    assert!(s.bones[3].end.length() < 1e-5);
    let s = skeleton("F(2)&(90)F(2)&(90)F(2)&(90)F(2)", &TurtleOptions::default());
    assert!(s.bones[3].end.length() < 1e-5, "pitch square closes too");
}

#[test]
fn segment_count_equals_drawing_steps() {
    for name in [
        "abop-1.24a",
        "abop-1.24d",
        "abop-honda",
        "abop-ternary",
        "kenwood-leafy",
    ] {
        let p = preset(name).unwrap();
        let w = p
            .lsystem()
            .unwrap()
            .derive(p.generations.min(6), 0)
            .unwrap();
        let draws = w.iter().filter(|m| m.symbol == 'F').count() as u32;
        // F inside a polygon outlines it instead of drawing; these grammars have none.
        let stats = interpret(&w, &TurtleOptions::for_preset(p), &mut NullSink).unwrap();
        assert_eq!(stats.segments, draws, "{name}");
    }
}

#[test]
fn mesh_bounds_contain_the_skeleton() {
    let p = preset("abop-ternary").unwrap();
    let w = p.lsystem().unwrap().derive(4, 0).unwrap();
    let options = TurtleOptions::for_preset(p).with_width_unit(5.0);
    let mut s = Skeleton::default();
    interpret(&w, &options, &mut s).unwrap();
    for shape in [BranchShape::Cylinder, BranchShape::Frustum] {
        let o = options.clone().with_shape(shape);
        let mut b = MeshBuilder::new(&o);
        interpret(&w, &o, &mut b).unwrap();
        let (lo, hi) = b.mesh.bounds().unwrap();
        for bone in &s.bones {
            for p in [bone.start, bone.end] {
                assert!(
                    p.cmpge(lo - 1e-3).all() && p.cmple(hi + 1e-3).all(),
                    "{p} outside {lo}..{hi}"
                );
            }
        }
    }
}

#[test]
fn frustums_share_rings_along_an_axis_and_restart_in_branches() {
    let sides = 8;
    let ring = sides + 1;
    let o = TurtleOptions::default().with_radial_segments(sides as u32);
    assert_eq!(
        mesh("FFF", &o.clone().with_shape(BranchShape::Frustum))
            .vertices
            .len(),
        4 * ring
    );
    assert_eq!(
        mesh("FFF", &o.clone().with_shape(BranchShape::Cylinder))
            .vertices
            .len(),
        6 * ring
    );
    // F[+F]F: the main axis continues through the branch point; the branch starts its own tube.
    assert_eq!(
        mesh("F[+F]F", &o.clone().with_shape(BranchShape::Frustum))
            .vertices
            .len(),
        5 * ring
    );
    let tris = mesh("FFF", &o.clone().with_shape(BranchShape::Frustum)).triangle_count();
    assert_eq!(tris, 3 * 2 * sides);
}

#[test]
fn frustum_radii_run_on_from_segment_to_segment() {
    let s = skeleton(
        "!(1)F!(0.5)F!(0.25)F",
        &TurtleOptions::default().with_shape(BranchShape::Frustum),
    );
    let radii: Vec<(f32, f32)> = s
        .bones
        .iter()
        .map(|b| (b.start_radius, b.end_radius))
        .collect();
    assert_eq!(radii, [(0.5, 0.5), (0.5, 0.25), (0.25, 0.125)]);
    let c = skeleton(
        "!(1)F!(0.5)F",
        &TurtleOptions::default().with_shape(BranchShape::Cylinder),
    );
    assert_eq!(c.bones[1].start_radius, c.bones[1].end_radius);
}

#[test]
fn caps_close_tube_ends() {
    let o = TurtleOptions::default()
        .with_radial_segments(6)
        .with_caps(true);
    let frustum = mesh("FF[+F]", &o.clone().with_shape(BranchShape::Frustum));
    // Two tubes (the trunk FF and the branch F), each with two caps of 6 triangles.
    assert_eq!(frustum.triangle_count(), 3 * 12 + 4 * 6);
    let cylinder = mesh("FF", &o.with_shape(BranchShape::Cylinder));
    assert_eq!(cylinder.triangle_count(), 2 * 12 + 4 * 6);
}

#[test]
fn polygons_and_leaves_use_the_leaf_material() {
    let leafy = preset("kenwood-leafy").unwrap();
    let w = leafy.lsystem().unwrap().derive(3, 0).unwrap();
    let o = TurtleOptions::for_preset(leafy);
    let mut b = MeshBuilder::new(&o);
    let stats = interpret(&w, &o, &mut b).unwrap();
    let leaves = w.iter().filter(|m| m.symbol == '{').count() as u32;
    assert_eq!(stats.polygons, leaves);
    // Each leaf outline has 6 points (the start and six moves, the last returning to the
    // start), so 4 fan triangles.
    assert_eq!(b.mesh.leaves.len() as u32, leaves * 4 * 3);
    let quad = mesh("J", &TurtleOptions::default());
    assert_eq!(quad.leaves.len(), 6);
    assert_eq!(quad.vertices[0].normal, [0.0, 0.0, 1.0]);
}

#[test]
fn normals_are_unit_and_outward() {
    let m = mesh(
        "F&(30)F/(50)F",
        &TurtleOptions::default().with_shape(BranchShape::Cylinder),
    );
    for v in &m.vertices {
        let n = Vec3::from(v.normal);
        assert!((n.length() - 1.0).abs() < 1e-4);
    }
    // Every bark triangle faces the way its vertex normals point.
    for t in m.bark.chunks_exact(3) {
        let p: Vec<Vec3> = t
            .iter()
            .map(|&i| Vec3::from(m.vertices[i as usize].position))
            .collect();
        let face = (p[1] - p[0]).cross(p[2] - p[0]);
        let n: Vec3 = t
            .iter()
            .map(|&i| Vec3::from(m.vertices[i as usize].normal))
            .sum();
        assert!(face.dot(n) > 0.0);
    }
}

/// Issue 60: `axiom: F` / `F -> FF` at 22 generations drew a 4 M-segment tree (6.6 GB);
/// the turtle stops at its piece budget with an error naming the module.
#[test]
fn a_doubling_grammar_stops_at_the_piece_budget() {
    let bomb = LSystem::parse("axiom: F\nF -> FF").unwrap();
    let word = bomb.derive(21, 0).unwrap();
    assert_eq!(word.len(), 1 << 21);
    let err = interpret(&word, &TurtleOptions::default(), &mut NullSink).unwrap_err();
    assert_eq!(
        err,
        TurtleError::TooManyPieces {
            index: sylva_turtle::MAX_PIECES as usize,
            limit: sylva_turtle::MAX_PIECES
        }
    );
    assert!(
        err.to_string().contains("derive fewer generations"),
        "{err}"
    );
    // A smaller budget stops sooner; a word within it is drawn whole.
    let small = TurtleOptions::default().with_max_pieces(100);
    assert!(interpret(&word, &small, &mut NullSink).is_err());
    let tree = bomb.derive(6, 0).unwrap();
    assert_eq!(
        interpret(&tree, &small, &mut NullSink).unwrap().segments,
        64
    );
}

#[test]
fn bad_words_give_errors_not_panics() {
    let w: Word = "F]F".parse().unwrap();
    assert_eq!(
        interpret(&w, &TurtleOptions::default(), &mut NullSink),
        Err(TurtleError::UnbalancedPop { index: 1 })
    );
    let w: Word = "F(1e30)".parse().unwrap();
    assert!(matches!(
        interpret(&w, &TurtleOptions::default(), &mut NullSink),
        Err(TurtleError::OutOfRange { .. })
    ));
    let mut w: Word = "F".parse().unwrap();
    w.push(w.alphabet().id('F').unwrap(), &[f64::NAN]);
    assert!(matches!(
        interpret(&w, &TurtleOptions::default(), &mut NullSink),
        Err(TurtleError::OutOfRange { index: 1, .. })
    ));
    let empty: Word = "".parse().unwrap();
    let mut b = MeshBuilder::new(&TurtleOptions::default());
    interpret(&empty, &TurtleOptions::default(), &mut b).unwrap();
    assert_eq!(b.mesh.vertices.len(), 0);
    // Negative widths are clamped to zero: defined, finite geometry.
    let m = mesh("!(-3)F", &TurtleOptions::default());
    assert!(
        m.vertices
            .iter()
            .all(|v| v.position.iter().all(|c| c.is_finite()))
    );
    // Unclosed brackets and polygons at the end of the word are simply dropped.
    assert_eq!(mesh("[F{.f+f", &TurtleOptions::default()).leaves.len(), 0);
    let deep = "[".repeat(100);
    let w: Word = deep.parse().unwrap();
    let mut o = TurtleOptions::default();
    o.max_depth = 10;
    assert!(matches!(
        interpret(&w, &o, &mut NullSink),
        Err(TurtleError::TooDeep { limit: 10, .. })
    ));
}

#[test]
fn markers_reach_the_sink_with_frame_and_params() {
    #[derive(Default)]
    struct Markers(Vec<(char, Vec<f64>, Vec3)>);
    impl GeometrySink for Markers {
        fn segment(&mut self, _: &sylva_turtle::Segment) {}
        fn marker(&mut self, symbol: char, params: &[f64], frame: &sylva_turtle::Frame) {
            self.0.push((symbol, params.to_vec(), frame.position));
        }
    }
    let mut o = TurtleOptions::default();
    o.symbols.set('S', sylva_turtle::Command::Marker);
    let w: Word = "F(2)S(3,1)FX".parse().unwrap();
    let mut m = Markers::default();
    interpret(&w, &o, &mut m).unwrap();
    assert_eq!(m.0, vec![('S', vec![3.0, 1.0], Vec3::new(0.0, 2.0, 0.0))]);
}

#[test]
fn obj_export_lists_every_vertex_and_face() {
    let m = mesh("F[+FJ]F", &TurtleOptions::default());
    let mut out = Vec::new();
    write_obj(&m, &mut out).unwrap();
    let text = String::from_utf8(out).unwrap();
    assert_eq!(
        text.lines().filter(|l| l.starts_with("v ")).count(),
        m.vertices.len()
    );
    assert_eq!(
        text.lines().filter(|l| l.starts_with("vt ")).count(),
        m.vertices.len()
    );
    assert_eq!(
        text.lines().filter(|l| l.starts_with("f ")).count(),
        m.triangle_count()
    );
}

#[test]
fn interpretation_is_deterministic() {
    let p = preset("goe-random").unwrap();
    let g: LSystem = p.lsystem().unwrap();
    let w = g.derive(4, 11).unwrap();
    let o = TurtleOptions::for_preset(p);
    let run = || {
        let mut b = MeshBuilder::new(&o);
        interpret(&w, &o, &mut b).unwrap();
        b.finish()
    };
    assert_eq!(run(), run());
}

fn turtle_word() -> impl Strategy<Value = String> {
    let module = prop_oneof![
        Just("F".to_string()),
        Just("f".to_string()),
        Just("$".to_string()),
        Just("|".to_string()),
        Just("J".to_string()),
        (
            prop::sample::select(vec!['+', '-', '&', '^', '/', '\\', 'F', '!', '"', ';']),
            -400.0f64..400.0
        )
            .prop_map(|(c, a)| format!("{c}({a})")),
        Just("[".to_string()),
        Just("]".to_string()),
        Just("{".to_string()),
        Just(".".to_string()),
        Just("}".to_string()),
    ];
    prop::collection::vec(module, 0..300).prop_map(|v| v.concat())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    /// Turning a leaf to the sky keeps its heading and position, turns the card only about
    /// the heading, never tilts it further from level than before, and fully turned leaves
    /// its left vector level.
    #[test]
    fn facing_sky_rolls_about_the_heading_towards_level(
        pitch in -3.2f32..3.2, roll in -3.2f32..3.2, yaw in -3.2f32..3.2, amount in 0.0f32..1.0,
    ) {
        let mut f = sylva_turtle::Frame::IDENTITY;
        f.yaw(yaw);
        f.pitch(pitch);
        f.roll(roll);
        let turned = f.facing_sky(amount);
        prop_assert!((turned.heading() - f.heading()).length() < 1e-4);
        prop_assert_eq!(turned.position, f.position);
        prop_assert!(turned.left().y.abs() <= f.left().y.abs() + 1e-4);
        let level = f.facing_sky(1.0);
        if f.heading().y.abs() < 0.999 {
            prop_assert!(level.left().y.abs() < 1e-3, "{}", level.left());
        }
    }

    #[test]
    fn frame_stays_orthonormal(text in turtle_word()) {
        #[derive(Default)]
        struct Frames(Vec<sylva_turtle::Frame>);
        impl GeometrySink for Frames {
            fn segment(&mut self, s: &sylva_turtle::Segment) { self.0.push(s.frame); }
        }
        let w: Word = text.parse().unwrap();
        let mut f = Frames::default();
        let o = TurtleOptions::default().with_tropism(Vec3::new(0.3, -1.0, 0.2), 0.3);
        if interpret(&w, &o, &mut f).is_ok() {
            for fr in f.0 {
                let (h, l, u) = (fr.heading(), fr.left(), fr.up());
                prop_assert!((h.length() - 1.0).abs() < 1e-4 && (l.length() - 1.0).abs() < 1e-4);
                prop_assert!(h.dot(l).abs() < 1e-4 && h.dot(u).abs() < 1e-4 && l.dot(u).abs() < 1e-4);
                prop_assert!((h.cross(l) - u).length() < 1e-4);
            }
        }
    }

    #[test]
    fn meshes_never_hold_nan(text in turtle_word(), frustum: bool, caps: bool) {
        let w: Word = text.parse().unwrap();
        let shape = if frustum { BranchShape::Frustum } else { BranchShape::Cylinder };
        let o = TurtleOptions::default().with_shape(shape).with_caps(caps);
        let mut b = MeshBuilder::new(&o);
        if interpret(&w, &o, &mut b).is_ok() {
            let m = b.finish();
            for v in &m.vertices {
                prop_assert!(v.position.iter().chain(&v.normal).chain(&v.uv).all(|c| c.is_finite()));
            }
            let n = m.vertices.len() as u32;
            prop_assert!(m.bark.iter().chain(&m.leaves).all(|&i| i < n));
        }
    }
}

#[test]
fn length_unit_scales_explicit_lengths_only() {
    let o = TurtleOptions::default()
        .with_length_unit(0.5)
        .with_step(3.0);
    let s = skeleton("F(4)F", &o);
    assert!((s.bones[0].end.y - 2.0).abs() < 1e-6);
    assert!((s.bones[1].end.y - 5.0).abs() < 1e-6);
}

/// Found in review: the Honda trunk twisted, because each ring was drawn in the turtle's own
/// frame, which rolls 137.5 degrees between segments, while rings are joined vertex to
/// vertex. Rings are now carried along the axis by parallel transport: on a straight axis
/// with rolls, vertex k of every ring lies in the same direction from the axis.
#[test]
fn rings_do_not_twist_when_the_turtle_rolls() {
    let sides = 8;
    let ring = sides + 1;
    let o = TurtleOptions::default()
        .with_radial_segments(sides as u32)
        .with_shape(BranchShape::Frustum);
    let m = mesh("F/(137.5)F/(137.5)F\\(60)F", &o);
    assert_eq!(m.vertices.len(), 5 * ring);
    let offset = |r: usize, k: usize| {
        let p = Vec3::from(m.vertices[r * ring + k].position);
        Vec3::new(p.x, 0.0, p.z).normalize()
    };
    for r in 1..5 {
        for k in 0..ring {
            assert!(
                offset(r, k).dot(offset(0, k)) > 0.9999,
                "ring {r} vertex {k} turned"
            );
        }
    }
    // On a bending axis the seam stays on one side: successive rings' vertex k differ by no
    // more than the bend.
    let m = mesh("F+(20)/(137.5)F+(20)/(137.5)F", &o);
    for r in 1..4 {
        for k in 0..sides {
            let n0 = Vec3::from(m.vertices[(r - 1) * ring + k].normal);
            let n1 = Vec3::from(m.vertices[r * ring + k].normal);
            assert!(
                n0.dot(n1) > (25f32).to_radians().cos(),
                "ring {r} vertex {k}: {n0} {n1}"
            );
        }
    }
}

/// cpfg's sub-L-systems draw at their scale: `?(id, 0.5) F(2) $ F(2)` draws one unit, then
/// two; and in cpfg's table `$` is that end, not ABOP's roll (cpfg rolls with `@v`).
#[test]
fn cpfg_sub_lsystems_scale_what_they_draw() {
    use sylva_lsys::{Dialect, LSystem};
    use sylva_turtle::{Skeleton, SymbolTable};
    let g = LSystem::parse_dialect(
        "Lsystem: 1\nAxiom: ?(2,0.5) F(2) $ F(2)\nendlsystem",
        Dialect::Cpfg,
    )
    .unwrap();
    let word = g.derive(0, 0).unwrap();
    let options = TurtleOptions::default().with_symbols(SymbolTable::for_dialect(Dialect::Cpfg));
    let mut skeleton = Skeleton::default();
    interpret(&word, &options, &mut skeleton).unwrap();
    let length = |k: usize| skeleton.bones[k].start.distance(skeleton.bones[k].end);
    assert!((length(0) - 1.0).abs() < 1e-5 && (length(1) - 2.0).abs() < 1e-5);
}

/// cpfg's colour index reaches the mesh: each triangle records the index in force where it
/// was drawn, and a branch's colour ends with the branch.
#[test]
fn colour_indices_are_recorded_per_triangle() {
    use sylva_lsys::{Dialect, LSystem};
    use sylva_turtle::SymbolTable;
    let g = LSystem::parse_dialect(
        "Lsystem: 1\nAxiom: F ;(2) F [;(5) F] F ; F\nendlsystem",
        Dialect::Cpfg,
    )
    .unwrap();
    let word = g.derive(0, 0).unwrap();
    let options = TurtleOptions::default().with_symbols(SymbolTable::for_dialect(Dialect::Cpfg));
    let mut builder = MeshBuilder::new(&options);
    interpret(&word, &options, &mut builder).unwrap();
    let coloured = builder.finish();
    assert_eq!(coloured.bark_colours.len(), coloured.bark.len() / 3);
    // Runs of one colour in drawing order.
    let mut runs: Vec<u32> = Vec::new();
    for &c in &coloured.bark_colours {
        if runs.last() != Some(&c) {
            runs.push(c);
        }
    }
    assert_eq!(runs, [0, 2, 5, 2, 3]);
    let mut obj = Vec::new();
    write_obj(&coloured, &mut obj).unwrap();
    let obj = String::from_utf8(obj).unwrap();
    assert!(obj.contains("usemtl colour_5"), "{obj}");
    // A grammar that never changes colour leaves the lists empty.
    let plain = mesh("F[+F]F", &TurtleOptions::default());
    assert!(plain.bark_colours.is_empty() && plain.leaf_colours.is_empty());
}
