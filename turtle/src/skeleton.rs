//! Skeletons: the drawn segments as bones with radii and parents.

use glam::Vec3;

use crate::sink::{GeometrySink, Segment};

/// One segment of a skeleton.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bone {
    /// Start point.
    pub start: Vec3,
    /// End point.
    pub end: Vec3,
    /// Radius at the start.
    pub start_radius: f32,
    /// Radius at the end.
    pub end_radius: f32,
    /// Index of the bone this one grows from.
    pub parent: Option<u32>,
}

/// A [`GeometrySink`] that keeps segments as bones; polygons and leaves are ignored.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Skeleton {
    /// Bones in drawing order; a bone's index is its segment id.
    pub bones: Vec<Bone>,
}

impl Skeleton {
    /// Smallest box holding every bone end point, or `None` when empty.
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        let mut it = self.bones.iter().flat_map(|b| [b.start, b.end]);
        let first = it.next()?;
        Some(it.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p))))
    }

    /// Largest horizontal distance (in the x-z plane) of any bone end from the root, plus its
    /// radius: the measured canopy radius.
    pub fn horizontal_extent(&self) -> f32 {
        let root = self.bones.first().map_or(Vec3::ZERO, |b| b.start);
        self.bones
            .iter()
            .flat_map(|b| [(b.start, b.start_radius), (b.end, b.end_radius)])
            .map(|(p, r)| (p - root).with_y(0.0).length() + r)
            .fold(0.0, f32::max)
    }
}

impl GeometrySink for Skeleton {
    fn begin(&mut self) {
        self.bones.clear();
    }

    fn segment(&mut self, s: &Segment) {
        self.bones.push(Bone {
            start: s.start(),
            end: s.end(),
            start_radius: s.start_radius,
            end_radius: s.end_radius,
            parent: s.parent,
        });
    }
}
