//! What growth gives: each tree's segments and leaves, handed to any turtle
//! [`GeometrySink`] (meshes, skeletons) as if the turtle had drawn them.

use sylva_turtle::{Frame, GeometrySink, Segment};

/// One placed segment of a grown tree.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GrownSegment {
    /// Frame at its start; the heading is its direction.
    pub frame: Frame,
    /// Its length.
    pub length: f32,
    /// Radius at its start and end.
    pub start_radius: f32,
    /// Radius at its end.
    pub end_radius: f32,
    /// Bracket depth of its branch.
    pub depth: u32,
    /// The segment it grows from, in the same tree.
    pub parent: Option<u32>,
    /// Whether it continues its parent's axis (tubes share the joining ring).
    pub continues_parent: bool,
    /// Shed for want of light: left out of the geometry.
    pub shed: bool,
}

/// One grown tree.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct GrownTree {
    /// Its segments, parents before children.
    pub segments: Vec<GrownSegment>,
    /// Its leaf cards: frame and size (length, width).
    pub leaves: Vec<(Frame, [f32; 2])>,
}

impl GrownTree {
    /// Marks the axis that ends with segment `last` as shed, back to where it branched.
    pub(crate) fn shed_axis(&mut self, last: Option<u32>) {
        let mut at = last;
        while let Some(i) = at {
            let s = &mut self.segments[i as usize];
            s.shed = true;
            at = if s.continues_parent { s.parent } else { None };
        }
    }

    /// Where its crown is: the mean position of its leaves, or for a leafless tree of its
    /// segments' ends weighted by length (None when bare).
    pub fn centre(&self) -> Option<glam::Vec3> {
        if !self.leaves.is_empty() {
            let sum: glam::Vec3 = self.leaves.iter().map(|(f, _)| f.position).sum();
            return Some(sum / self.leaves.len() as f32);
        }
        let mut sum = glam::Vec3::ZERO;
        let mut weight = 0.0;
        for s in self.segments.iter().filter(|s| !s.shed) {
            let end = s.frame.position + s.frame.heading() * s.length;
            sum += end * s.length;
            weight += s.length;
        }
        (weight > 0.0).then(|| sum / weight)
    }

    /// Hands the tree to `sink` as the turtle would: segments with their ids and parents,
    /// axis ends, leaves.
    pub fn emit(&self, sink: &mut impl GeometrySink) {
        sink.begin();
        // A segment's axis ends unless a later, unshed segment continues it.
        let mut continued = vec![false; self.segments.len()];
        for s in self.segments.iter().filter(|s| !s.shed) {
            if let (true, Some(p)) = (s.continues_parent, s.parent) {
                continued[p as usize] = true;
            }
        }
        for (id, s) in self.segments.iter().enumerate() {
            if s.shed {
                continue;
            }
            sink.segment(&Segment {
                id: id as u32,
                parent: s.parent,
                continues_parent: s.continues_parent,
                frame: s.frame,
                length: s.length,
                start_radius: s.start_radius,
                end_radius: s.end_radius,
                depth: s.depth,
            });
            if !continued[id] {
                sink.axis_end(id as u32);
            }
        }
        // A grown tree's cards take their season's order from their place in the list, as
        // the turtle's take it from their place in the word.
        for (k, (frame, size)) in self.leaves.iter().enumerate() {
            let order =
                sylva_base::hash::unit_f32(sylva_base::hash::mix(k as u64 ^ LEAF_ORDER_SALT));
            sink.leaf(frame, *size, order);
        }
        sink.end();
    }
}

/// Separates the leaf-order draws of grown trees from other uses of a leaf's index.
const LEAF_ORDER_SALT: u64 = 0x9e0f_1eaf_5ea5_0a11;
