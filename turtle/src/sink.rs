//! The `GeometrySink` trait: what the turtle emits.

use glam::Vec3;

use crate::frame::Frame;

/// One drawn step of the turtle: a straight piece of branch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    /// Index of the segment within one interpretation, counting from 0.
    pub id: u32,
    /// The segment drawn last on the turtle's path before this one (the one it grows from).
    pub parent: Option<u32>,
    /// Whether this segment continues its parent's axis (no `[` between them), so that a
    /// tube can share the joining ring.
    pub continues_parent: bool,
    /// Frame at the start; its heading is the segment's direction.
    pub frame: Frame,
    /// Length along the heading.
    pub length: f32,
    /// Radius at the start.
    pub start_radius: f32,
    /// Radius at the end.
    pub end_radius: f32,
    /// Bracket depth at which it was drawn.
    pub depth: u32,
}

impl Segment {
    /// Start point.
    pub fn start(&self) -> Vec3 {
        self.frame.position
    }

    /// End point.
    pub fn end(&self) -> Vec3 {
        self.frame.position + self.frame.heading() * self.length
    }
}

/// Receives the turtle's output. Every method but [`GeometrySink::segment`] has a no-op default.
pub trait GeometrySink {
    /// Called once before the first module.
    fn begin(&mut self) {}
    /// A drawn segment.
    fn segment(&mut self, segment: &Segment);
    /// The axis that ends with segment `id` will not be continued (a `]`, a move, or the end
    /// of the word follows): tubes close here.
    fn axis_end(&mut self, id: u32) {
        let _ = id;
    }
    /// A closed polygon (at least three vertices), from `{ ... }`.
    fn polygon(&mut self, vertices: &[Vec3]) {
        let _ = vertices;
    }
    /// A leaf at `frame`, `size` = (length along the heading, width along the left vector).
    /// `order`, in `[0, 1)`, is the card's place in its tree's leaf season, a pure function
    /// of its place in the word: [`TurtleOptions::leaf_keep`] draws the cards whose order is
    /// below it, so a tree in leaf fall or flush keeps the same cards whoever draws it, and
    /// the meshes carry it (as the card's wind phase) for shaders that play a year.
    ///
    /// [`TurtleOptions::leaf_keep`]: crate::TurtleOptions::leaf_keep
    fn leaf(&mut self, frame: &Frame, size: [f32; 2], order: f32) {
        let _ = (frame, size, order);
    }
    /// A symbol the table marks as a marker, with its parameters and the current frame.
    fn marker(&mut self, symbol: char, params: &[f64], frame: &Frame) {
        let _ = (symbol, params, frame);
    }
    /// The turtle's colour index changed (cpfg's and L-Py's `;` and `,`, or a `]` returning
    /// to another); what follows has this colour. It starts at 0.
    fn colour(&mut self, index: u32) {
        let _ = index;
    }
    /// A query module, by its index in the word, and the turtle's frame there.
    fn query(&mut self, index: usize, frame: &Frame) {
        let _ = (index, frame);
    }
    /// Called once after the last module.
    fn end(&mut self) {}
}

/// A sink that discards everything (for tests and for timing the turtle alone).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct NullSink;

impl GeometrySink for NullSink {
    fn segment(&mut self, _segment: &Segment) {}
}

impl<S: GeometrySink + ?Sized> GeometrySink for &mut S {
    fn begin(&mut self) {
        (**self).begin();
    }
    fn segment(&mut self, segment: &Segment) {
        (**self).segment(segment);
    }
    fn axis_end(&mut self, id: u32) {
        (**self).axis_end(id);
    }
    fn polygon(&mut self, vertices: &[Vec3]) {
        (**self).polygon(vertices);
    }
    fn leaf(&mut self, frame: &Frame, size: [f32; 2], order: f32) {
        (**self).leaf(frame, size, order);
    }
    fn marker(&mut self, symbol: char, params: &[f64], frame: &Frame) {
        (**self).marker(symbol, params, frame);
    }
    fn query(&mut self, index: usize, frame: &Frame) {
        (**self).query(index, frame);
    }
    fn colour(&mut self, index: u32) {
        (**self).colour(index);
    }
    fn end(&mut self) {
        (**self).end();
    }
}
