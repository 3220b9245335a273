//! Shapes the turtle draws whole: spheres and discs at its position (cpfg's `@o`, `@c`),
//! and generalized cylinders, smooth tubes through control points (cpfg's `@Gs`, `@Gc`,
//! `@Ge`).

use glam::{Quat, Vec3};

use crate::frame::Frame;
use crate::model_shapes::Contour;

/// Rings and sectors of a sphere: coarse, since spheres are buds and fruit seen small.
const SPHERE_RINGS: usize = 6;
const SPHERE_SECTORS: usize = 10;
/// Sides of a disc.
const DISC_SIDES: usize = 16;
/// Pieces each span of a generalized cylinder is cut into.
const CURVE_PIECES: usize = 4;

/// A sphere of `radius` around `centre` as quads (triangles at the poles), aligned with
/// `frame` so that a sphere is the same whichever way the turtle turns about it.
pub(crate) fn sphere(centre: Vec3, radius: f32, frame: &Frame) -> Vec<Vec<Vec3>> {
    let point = |ring: usize, sector: usize| {
        let polar = std::f32::consts::PI * ring as f32 / SPHERE_RINGS as f32;
        let azimuth = std::f32::consts::TAU * sector as f32 / SPHERE_SECTORS as f32;
        let local = Vec3::new(
            polar.sin() * azimuth.cos(),
            polar.cos(),
            polar.sin() * azimuth.sin(),
        );
        centre + frame.rotation * local * radius
    };
    let mut out = Vec::with_capacity(SPHERE_RINGS * SPHERE_SECTORS);
    for ring in 0..SPHERE_RINGS {
        for sector in 0..SPHERE_SECTORS {
            let next = (sector + 1) % SPHERE_SECTORS;
            let quad = [
                point(ring, sector),
                point(ring + 1, sector),
                point(ring + 1, next),
                point(ring, next),
            ];
            let mut face = distinct_corners(quad, |_| 1e-6 * (1.0 + radius));
            if face.len() > 3 && face[0].distance(face[face.len() - 1]) <= 1e-6 * (1.0 + radius) {
                face.pop();
            }
            if face.len() >= 3 {
                out.push(face);
            }
        }
    }
    out
}

/// A quad's corners, each that repeats the one before it dropped: where a sphere or a patch
/// narrows to a point two corners meet, and the quad is a triangle. Corners within
/// `tolerance(corner)` of each other are one.
fn distinct_corners(quad: [Vec3; 4], tolerance: impl Fn(Vec3) -> f32) -> Vec<Vec3> {
    let mut face: Vec<Vec3> = Vec::with_capacity(4);
    for p in quad {
        if face.last().is_none_or(|q| q.distance(p) > tolerance(p)) {
            face.push(p);
        }
    }
    face
}

/// A model's surface ([`crate::ModelShapes`]: quads as heading, left and up offsets) placed
/// at `frame`, `size` times as large: its faces of three or four corners.
pub(crate) fn placed(quads: &[[Vec3; 4]], frame: &Frame, size: f32) -> Vec<Vec<Vec3>> {
    let axes = [frame.heading(), frame.left(), frame.up()];
    quads
        .iter()
        .map(|quad| {
            let corners = quad
                .map(|p| frame.position + (axes[0] * p.x + axes[1] * p.y + axes[2] * p.z) * size);
            distinct_corners(corners, |q| 1e-7 * (1.0 + q.length()))
        })
        .filter(|face| face.len() >= 3)
        .collect()
}

/// A disc of `radius` around `centre` across the turtle's heading (in its left-up plane).
pub(crate) fn disc(centre: Vec3, radius: f32, frame: &Frame) -> Vec<Vec3> {
    (0..DISC_SIDES)
        .map(|k| {
            let a = std::f32::consts::TAU * k as f32 / DISC_SIDES as f32;
            centre + (frame.left() * a.cos() + frame.up() * a.sin()) * radius
        })
        .collect()
}

/// One straight piece of a generalized cylinder: its start frame (heading along it), length
/// and radii at both ends.
pub(crate) struct Piece {
    pub(crate) frame: Frame,
    pub(crate) length: f32,
    pub(crate) radii: (f32, f32),
}

/// A smooth tube through `points` (position and radius), starting with `frame`'s
/// orientation: a Catmull-Rom curve through the points cut into straight pieces, each frame
/// carried from the last by the smallest rotation (so the tube does not twist).
pub(crate) fn curve(points: &[(Vec3, f32)], frame: &Frame) -> Vec<Piece> {
    if points.len() < 2 {
        return Vec::new();
    }
    let at = |k: isize| {
        let k = k.clamp(0, points.len() as isize - 1) as usize;
        points[k]
    };
    let mut samples = Vec::with_capacity((points.len() - 1) * CURVE_PIECES + 1);
    for span in 0..points.len() - 1 {
        let s = span as isize;
        let (p0, p1, p2, p3) = (at(s - 1), at(s), at(s + 1), at(s + 2));
        for k in 0..CURVE_PIECES {
            let t = k as f32 / CURVE_PIECES as f32;
            let (t2, t3) = (t * t, t * t * t);
            let position = 0.5
                * ((2.0 * p1.0)
                    + (p2.0 - p0.0) * t
                    + (2.0 * p0.0 - 5.0 * p1.0 + 4.0 * p2.0 - p3.0) * t2
                    + (3.0 * p1.0 - p0.0 - 3.0 * p2.0 + p3.0) * t3);
            samples.push((position, p1.1 + (p2.1 - p1.1) * t));
        }
    }
    samples.push(points[points.len() - 1]);
    let mut rotation = frame.rotation;
    let mut out = Vec::with_capacity(samples.len());
    for pair in samples.windows(2) {
        let ((a, ra), (b, rb)) = (pair[0], pair[1]);
        let Some(direction) = (b - a).try_normalize() else {
            continue;
        };
        let heading = rotation * Vec3::Y;
        rotation = (Quat::from_rotation_arc(heading, direction) * rotation).normalize();
        out.push(Piece {
            frame: Frame {
                position: a,
                rotation,
            },
            length: a.distance(b),
            radii: (ra, rb),
        });
    }
    out
}

/// The sheet a contour sweeps along a generalized cylinder's pieces: at the start of each
/// piece and at the end of the last, the contour across the piece (x along its up, y to
/// its right) scaled by its radius there; quads join each ring to the next.
pub(crate) fn sweep(pieces: &[Piece], contour: &Contour) -> Vec<Vec<Vec3>> {
    let ring = |frame: &Frame, centre: Vec3, radius: f32| -> Vec<Vec3> {
        contour
            .points
            .iter()
            .map(|p| centre + (frame.up() * p.x - frame.left() * p.y) * radius)
            .collect()
    };
    let mut rings: Vec<Vec<Vec3>> = pieces
        .iter()
        .map(|piece| ring(&piece.frame, piece.frame.position, piece.radii.0))
        .collect();
    if let Some(last) = pieces.last() {
        let end = last.frame.position + last.frame.heading() * last.length;
        rings.push(ring(&last.frame, end, last.radii.1));
    }
    let sides = contour.points.len();
    let around = if contour.closed { sides } else { sides - 1 };
    let mut out = Vec::with_capacity(rings.len().saturating_sub(1) * around);
    for pair in rings.windows(2) {
        for k in 0..around {
            let next = (k + 1) % sides;
            out.push(vec![pair[0][k], pair[1][k], pair[1][next], pair[0][next]]);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sphere_is_closed_and_round() {
        let faces = sphere(Vec3::new(1.0, 2.0, 3.0), 0.5, &Frame::IDENTITY);
        assert_eq!(faces.len(), SPHERE_RINGS * SPHERE_SECTORS);
        for p in faces.iter().flatten() {
            assert!((p.distance(Vec3::new(1.0, 2.0, 3.0)) - 0.5).abs() < 1e-5);
        }
    }

    #[test]
    fn a_curve_passes_through_its_points_smoothly() {
        let points = [
            (Vec3::ZERO, 0.1),
            (Vec3::new(0.0, 1.0, 0.0), 0.2),
            (Vec3::new(1.0, 2.0, 0.0), 0.3),
        ];
        let pieces = curve(&points, &Frame::IDENTITY);
        assert_eq!(pieces.len(), 2 * CURVE_PIECES);
        // Through every control point, ends included.
        for (p, _) in points {
            assert!(pieces.iter().any(|q| q.frame.position.distance(p) < 1e-5
                || (q.frame.position + q.frame.heading() * q.length).distance(p) < 1e-5));
        }
        // Consecutive pieces join end to start and turn gently.
        for w in pieces.windows(2) {
            let end = w[0].frame.position + w[0].frame.heading() * w[0].length;
            assert!(end.distance(w[1].frame.position) < 1e-4);
            assert!(w[0].frame.heading().dot(w[1].frame.heading()) > 0.8);
        }
    }
}
