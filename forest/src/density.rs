//! Density models: where trees may grow, before the terrain has its say.

use glam::Vec2;

/// An axis-aligned rectangle in the x-z plane, half-open: `min <= p < max`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rect {
    /// Lower corner (x, z).
    pub min: Vec2,
    /// Upper corner (x, z).
    pub max: Vec2,
}

impl Rect {
    /// The rectangle from `min` to `max`.
    pub fn new(min: Vec2, max: Vec2) -> Self {
        Rect { min, max }
    }

    /// Whether `p` lies inside (half-open).
    pub fn contains(&self, p: Vec2) -> bool {
        p.x >= self.min.x && p.y >= self.min.y && p.x < self.max.x && p.y < self.max.y
    }

    /// Whether the rectangle has no area (or is not finite).
    pub fn is_empty(&self) -> bool {
        !(self.min.is_finite()
            && self.max.is_finite()
            && self.max.x > self.min.x
            && self.max.y > self.min.y)
    }

    /// The overlap of two rectangles.
    #[must_use]
    pub fn intersect(&self, other: &Rect) -> Rect {
        Rect {
            min: self.min.max(other.min),
            max: self.max.min(other.max),
        }
    }

    /// The smallest rectangle holding both.
    #[must_use]
    pub fn union(&self, other: &Rect) -> Rect {
        Rect {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    /// The cells of side `side` of the global lattice (cell (i, j) spans `i * side` to
    /// `(i + 1) * side` in x, likewise j in z) that the rectangle overlaps: the columns, then
    /// the rows. Generators that draw per cell of the world use it, so regions asked apart
    /// draw the same cells.
    ///
    /// ```
    /// use sylva_forest::Rect;
    /// use sylva_terrain::glam::Vec2;
    ///
    /// let r = Rect::new(Vec2::new(-5.0, 10.0), Vec2::new(25.0, 20.0));
    /// assert_eq!(r.cells(10.0), (-1..3, 1..2));
    /// ```
    pub fn cells(&self, side: f32) -> (std::ops::Range<i64>, std::ops::Range<i64>) {
        let lo = |v: f32| (v / side).floor() as i64;
        let hi = |v: f32| (v / side).ceil() as i64;
        (
            lo(self.min.x)..hi(self.max.x),
            lo(self.min.y)..hi(self.max.y),
        )
    }

    /// The rectangle grown by `margin` on every side.
    #[must_use]
    pub fn expanded(&self, margin: f32) -> Rect {
        Rect {
            min: self.min - margin,
            max: self.max + margin,
        }
    }
}

/// The distance from `p` to the segment from `a` to `b` in the x-z plane (the growth crate's
/// segment distance, in the plane): how far a trunk is from a walker's step, a paint cell
/// from a brush stroke.
///
/// ```
/// use sylva_forest::distance_to_segment;
/// use sylva_terrain::glam::Vec2;
///
/// let (a, b) = (Vec2::ZERO, Vec2::new(10.0, 0.0));
/// assert_eq!(distance_to_segment(Vec2::new(5.0, 3.0), a, b), 3.0);
/// assert_eq!(distance_to_segment(Vec2::new(-4.0, 3.0), a, b), 5.0);
/// assert_eq!(distance_to_segment(Vec2::new(1.0, 0.0), a, a), 1.0);
/// ```
pub fn distance_to_segment(p: Vec2, a: Vec2, b: Vec2) -> f32 {
    sylva_growth::distance_to_segment(p.extend(0.0), a.extend(0.0), b.extend(0.0))
}

/// A proposed tree.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Candidate {
    /// Position (x, z).
    pub position: Vec2,
    /// Index into the forest's species.
    pub species: usize,
    /// A seedling (fewer generations) rather than a canopy tree.
    pub seedling: bool,
    /// Per-tree randomness: yaw, scale and instance choices derive from it.
    pub key: u64,
    /// Distinguishes the candidates of one patch: 0 for the canopy tree, 1 + k for the k-th
    /// seedling. Trees of one patch with different slots never share a crown.
    pub slot: u32,
}

/// Decides where trees may stand. Implementations must make the candidates of a region a pure
/// function of (seed, region), and a candidate's presence must not depend on which region is
/// asked, so that tiles generated apart join without seams.
pub trait DensityModel {
    /// Appends the candidates whose positions lie in `region`.
    fn candidates(&self, region: Rect, seed: u64, out: &mut Vec<Candidate>);
}
