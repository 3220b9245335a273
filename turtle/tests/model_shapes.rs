//! A cpfg model's surfaces (`~l`) and contours (`@#(id)`) drawn by the turtle: placed by
//! its frame, sized by their parameters and the width, worked out by hand.

use sylva_lsys::curve::Curve;
use sylva_lsys::surface::Surface;
use sylva_lsys::{Dialect, LSystem, ModelFiles};
use sylva_turtle::glam::Vec3;
use sylva_turtle::{GeometrySink, Segment, TurtleOptions, interpret};

/// Collects polygons.
#[derive(Default)]
struct Polygons(Vec<Vec<Vec3>>);

impl GeometrySink for Polygons {
    fn segment(&mut self, _: &Segment) {}
    fn polygon(&mut self, vertices: &[Vec3]) {
        self.0.push(vertices.to_vec());
    }
}

/// A flat unit patch in the file's frame (heading +y, up +z), its contact point at the
/// origin: one Bézier patch over [0, 1] x [0, 1] in x and y (lsys's test data).
fn unit_patch(letter: char) -> Surface {
    let text = include_str!(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../lsys/tests/data/flat_patch.s"
    ));
    Surface::parse(text, letter).unwrap()
}

fn drawn(axiom: &str, files: ModelFiles) -> Vec<Vec<Vec3>> {
    let text = format!("Lsystem: 1\nderivation length: 0\nAxiom: {axiom}\nendlsystem\n");
    let model = LSystem::parse_with_files(&text, Dialect::Cpfg, files).unwrap();
    let word = model.derive(0, 0).unwrap();
    let mut sink = Polygons::default();
    interpret(&word, &TurtleOptions::for_grammar(&model), &mut sink).unwrap();
    sink.0
}

#[test]
fn a_surface_stands_where_the_turtle_is_sized_by_its_scale_and_parameter() {
    let mut patch = unit_patch('l');
    patch.scale = 2.0;
    patch.divisions = [1, 1];
    let files = ModelFiles {
        surfaces: vec![patch],
        ..ModelFiles::default()
    };
    // The turtle starts as the file's frame does (heading +y, up +z), so the surface
    // appears as written, moved to the turtle and scaled by 2 x 0.5: the patch's far
    // corner (1, 1, 0) lands at (0, 1, 0) + (1, 1, 0).
    let faces = drawn("f(1)~l(0.5)", files.clone());
    assert_eq!(faces.len(), 1);
    let far = faces[0]
        .iter()
        .map(|p| p.distance(Vec3::new(1.0, 2.0, 0.0)))
        .fold(f32::MAX, f32::min);
    assert!(far < 1e-5, "{:?}", faces[0]);
    // Yawed a quarter turn left, the heading is -x and the left -y; the corner (1, 1, 0) is
    // 1 along the file's heading and -1 along its left (up x heading = -x), so it lands at
    // 1 (-1, 0, 0) - 1 (0, -1, 0) = (-1, 1, 0).
    let turned = drawn("+(90)~l(0.5)", files);
    let far = turned[0]
        .iter()
        .map(|p| p.distance(Vec3::new(-1.0, 1.0, 0.0)))
        .fold(f32::MAX, f32::min);
    assert!(far < 1e-5, "{:?}", turned[0]);
}

#[test]
fn a_contour_is_the_cross_section_of_generalized_cylinders() {
    // An open blade from x = -1 to 1 on the contour's plane, sampled at 4 sides: points at
    // x = -1, -0.5, 0, 0.5, 1 (evenly along its length).
    let blade: Vec<[f64; 3]> = [[-1.0, 0.0, 0.0]; 3]
        .into_iter()
        .chain([[1.0, 0.0, 0.0]; 3])
        .collect();
    let files = ModelFiles {
        contours: vec![(1, Curve::new(None, blade, false, 100).unwrap())],
        contour_sides: Some(4),
        ..ModelFiles::default()
    };
    // Width 2 (radius 1), straight up 2: four pieces of the smooth curve, four quads each.
    let faces = drawn("@#(1)#(2)@Gs f(1)@Gc f(1)@Ge", files.clone());
    assert_eq!(faces.len(), 2 * 4 * 4);
    // The contour's x lies along the turtle's up (+z): a flat blade in the y-z plane.
    let points: Vec<Vec3> = faces.iter().flatten().copied().collect();
    assert!(
        points
            .iter()
            .all(|p| p.x.abs() < 1e-5 && p.z.abs() <= 1.0 + 1e-5),
        "{points:?}"
    );
    for z in [-1.0, -0.5, 0.0, 0.5, 1.0] {
        assert!(
            points
                .iter()
                .any(|p| (p.z - z).abs() < 1e-4 && p.y.abs() < 1e-5),
            "{z}"
        );
    }
    // Without `@#`, or with an id the model lacks, the cylinder is a round tube.
    assert!(drawn("#(2)@Gs f(1)@Ge", files.clone()).is_empty());
    assert!(drawn("@#(7)#(2)@Gs f(1)@Ge", files).is_empty());
}
