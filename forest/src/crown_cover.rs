//! How much ground a crown's foliage hides, seen straight down: what a patch must hold for
//! the canopy to close.

use std::collections::{BTreeMap, HashMap, HashSet};

use glam::{Vec2, Vec3};
use sylva_turtle::{Frame, GeometrySink, Segment, Skeleton};

/// Side of the cells foliage is counted in, in metres: finer than a leaf card, coarse enough
/// that a crown is a few thousand cells.
const CELL: f32 = 0.25;

/// Most sample points along one side of a card or triangle, so one huge card costs a bounded
/// amount.
const MOST_SAMPLES: usize = 64;

/// A turtle sink that keeps the skeleton and, for each cell of the ground plane, how many
/// leaf cards lie over it and whether a polygon does.
#[derive(Debug)]
pub(crate) struct CrownCover {
    /// The tree's bones, as [`Skeleton`] collects them.
    pub(crate) skeleton: Skeleton,
    /// The share of a leaf card that hides what is behind it ([`LeafShape::opacity`]).
    ///
    /// [`LeafShape::opacity`]: crate::LeafShape::opacity
    opacity: f32,
    /// Per cell, the number of cards over it so far (`u32::MAX`: an opaque polygon).
    layers: HashMap<(i32, i32), u32>,
    /// The cells under the shape being drawn, so a card counts once per cell.
    shape: HashSet<(i32, i32)>,
}

impl CrownCover {
    /// An empty crown whose leaf cards have this opacity (0 to 1); polygons are opaque.
    pub(crate) fn new(opacity: f32) -> Self {
        CrownCover {
            skeleton: Skeleton::default(),
            opacity: opacity.clamp(0.0, 1.0),
            layers: HashMap::new(),
            shape: HashSet::new(),
        }
    }

    /// The area (m²) of ground the foliage drawn so far hides, seen straight down: each cell
    /// counts for the share of light its cards stop, 1 - (1 - opacity)^cards.
    pub(crate) fn area(&self) -> f32 {
        // Cells gathered by their number of layers and summed in that order, so the area
        // does not depend on the hash map's order (a different last bit would size the
        // patches, and so the forest, differently run to run).
        let mut by_layers = BTreeMap::<u32, u64>::new();
        for &n in self.layers.values() {
            *by_layers.entry(n).or_default() += 1;
        }
        let hidden: f64 = by_layers
            .iter()
            .map(|(&n, &cells)| {
                let through = if n == u32::MAX {
                    0.0
                } else {
                    (1.0 - f64::from(self.opacity)).powi(n.min(1 << 16) as i32)
                };
                cells as f64 * (1.0 - through)
            })
            .sum();
        (hidden * f64::from(CELL * CELL)) as f32
    }

    /// Lays one more card over every cell under the shape just drawn, or an opaque polygon.
    fn settle(&mut self, opaque: bool) {
        for cell in self.shape.drain() {
            let n = self.layers.entry(cell).or_insert(0);
            *n = if opaque || *n == u32::MAX {
                u32::MAX
            } else {
                (*n + 1).min(u32::MAX - 1)
            };
        }
    }

    /// Marks the cells under the triangle `a b c`, projected straight down.
    fn triangle(&mut self, a: Vec3, b: Vec3, c: Vec3) {
        let flat = |p: Vec3| Vec2::new(p.x, p.z);
        let (a, b, c) = (flat(a), flat(b), flat(c));
        let n = samples((b - a).length().max((c - a).length()));
        for i in 0..=n {
            for j in 0..=(n - i) {
                let (u, v) = (i as f32 / n as f32, j as f32 / n as f32);
                self.mark(a + (b - a) * u + (c - a) * v);
            }
        }
    }

    fn mark(&mut self, p: Vec2) {
        if p.is_finite() {
            self.shape
                .insert(((p.x / CELL).floor() as i32, (p.y / CELL).floor() as i32));
        }
    }
}

/// Sample points along an edge of `length` metres: two per cell, so no cell under the shape
/// is skipped.
fn samples(length: f32) -> usize {
    ((2.0 * length / CELL).ceil() as usize).clamp(1, MOST_SAMPLES)
}

impl GeometrySink for CrownCover {
    fn segment(&mut self, segment: &Segment) {
        self.skeleton.segment(segment);
    }

    fn leaf(&mut self, frame: &Frame, size: [f32; 2], _order: f32) {
        // The card as the mesher draws it.
        let [a, b, c, d] = frame.card_corners(size);
        self.triangle(a, b, c);
        self.triangle(a, c, d);
        self.settle(false);
    }

    fn polygon(&mut self, vertices: &[Vec3]) {
        for pair in vertices.windows(2).skip(1) {
            self.triangle(vertices[0], pair[0], pair[1]);
        }
        self.settle(true);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Quat;
    use std::f32::consts::FRAC_PI_2;

    /// Heading along +x with the left vector along +z: a card lying flat.
    fn flat() -> Quat {
        Quat::from_rotation_z(-FRAC_PI_2) * Quat::from_rotation_y(FRAC_PI_2)
    }

    #[test]
    fn a_level_opaque_card_covers_its_own_area() {
        let mut cover = CrownCover::new(1.0);
        // A card lying flat, 2 m by 1 m.
        let frame = Frame {
            position: Vec3::new(0.1, 3.0, 0.1),
            rotation: flat(),
        };
        cover.leaf(&frame, [2.0, 1.0], 0.5);
        let area = cover.area();
        // Cells on the outline count whole, so the count runs a little over 2 m².
        assert!((2.0..2.9).contains(&area), "{area}");
    }

    #[test]
    fn an_upright_card_hides_almost_nothing() {
        let mut cover = CrownCover::new(1.0);
        // The identity frame heads up +Y with its face towards +Z: seen from above, a line.
        cover.leaf(&Frame::IDENTITY, [2.0, 1.0], 0.5);
        assert!(cover.area() <= 5.0 * CELL * CELL, "{}", cover.area());
    }

    #[test]
    fn stacked_cards_let_through_what_each_lets_through_in_turn() {
        let mut cover = CrownCover::new(0.4);
        let frame = Frame {
            position: Vec3::ZERO,
            rotation: flat(),
        };
        cover.leaf(&frame, [2.0, 1.0], 0.5);
        let once = cover.area();
        cover.leaf(&frame, [2.0, 1.0], 0.5);
        // One card stops 0.4 of the light, two stop 1 - 0.6 * 0.6 = 0.64 of it.
        assert!((cover.area() / once - 0.64 / 0.4).abs() < 1e-4);
        let mut opaque = CrownCover::new(1.0);
        opaque.leaf(&frame, [2.0, 1.0], 0.5);
        opaque.leaf(&frame, [2.0, 1.0], 0.5);
        assert!((opaque.area() * 0.4 - once).abs() < 1e-4);
    }

    #[test]
    fn a_polygon_covers_its_triangles() {
        let mut cover = CrownCover::new(0.1);
        let square = [
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(1.0, 1.0, 1.0),
            Vec3::new(0.0, 1.0, 1.0),
        ];
        cover.polygon(&square);
        let area = cover.area();
        assert!((1.0..1.6).contains(&area), "{area}");
    }
}
