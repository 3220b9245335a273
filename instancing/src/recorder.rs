//! `HeroRecorder`: a `GeometrySink` that meshes a hero tree and notes, from the marker
//! symbols, which index ranges form instances and where their exits are.

use glam::Vec3;
use sylva_turtle::{Frame, GeometrySink, MeshBuilder, Segment, TurtleOptions};

use crate::rewrite::Markers;
use crate::similarity::Similarity;
use crate::span::Span;

/// An instance found in a hero, with ranges into the hero's own mesh.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct RecordedInstance {
    /// Branch id.
    pub(crate) id: u32,
    /// Age.
    pub(crate) age: u32,
    /// Frame M in the hero.
    pub(crate) frame: Similarity,
    /// Bark index range (start, end) in the hero mesh.
    pub(crate) bark: Span,
    /// Leaf index range (start, end).
    pub(crate) leaves: Span,
    /// Exit range (start, end) into [`HeroRecorder::exits`].
    pub(crate) exits: Span,
    /// Order in which its start marker appeared.
    pub(crate) start_order: u32,
}

#[derive(Debug, Clone)]
struct Open {
    id: u32,
    age: u32,
    frame: Similarity,
    bark: u32,
    leaves: u32,
    exits: u32,
    order: u32,
}

/// Meshes a hero tree and records its instances and exit points.
#[derive(Debug, Clone)]
pub(crate) struct HeroRecorder {
    /// The hero's geometry.
    pub(crate) builder: MeshBuilder,
    /// Instances in the order they closed.
    pub(crate) instances: Vec<RecordedInstance>,
    /// Exit points (id, age, world frame) in the order they appeared.
    pub(crate) exits: Vec<(u32, u32, Similarity)>,
    markers: Markers,
    open: Vec<Open>,
    started: u32,
}

fn key(params: &[f64]) -> Option<(u32, u32)> {
    match params {
        [id, age, ..] if *id >= 0.0 && *age >= 0.0 && *id < 1e9 && *age < 1e9 => {
            Some((*id as u32, *age as u32))
        }
        _ => None,
    }
}

impl HeroRecorder {
    /// A recorder meshing with `options` and reading `markers`.
    pub(crate) fn new(options: &TurtleOptions, markers: Markers) -> Self {
        HeroRecorder {
            builder: MeshBuilder::new(options),
            instances: Vec::new(),
            exits: Vec::new(),
            markers,
            open: Vec::new(),
            started: 0,
        }
    }
}

impl GeometrySink for HeroRecorder {
    fn begin(&mut self) {
        self.builder.begin();
    }

    fn segment(&mut self, segment: &Segment) {
        self.builder.segment(segment);
    }

    fn axis_end(&mut self, id: u32) {
        self.builder.axis_end(id);
    }

    fn polygon(&mut self, vertices: &[Vec3]) {
        self.builder.polygon(vertices);
    }

    fn leaf(&mut self, frame: &Frame, size: [f32; 2], order: f32) {
        self.builder.leaf(frame, size, order);
    }

    fn marker(&mut self, symbol: char, params: &[f64], frame: &Frame) {
        let Some((id, age)) = key(params) else { return };
        let mesh = &self.builder.mesh;
        if symbol == self.markers.start {
            self.open.push(Open {
                id,
                age,
                frame: Similarity::from_frame(frame),
                bark: mesh.bark.len() as u32,
                leaves: mesh.leaves.len() as u32,
                exits: self.exits.len() as u32,
                order: self.started,
            });
            self.started += 1;
        } else if symbol == self.markers.stop {
            if self.open.last().is_some_and(|o| o.id == id && o.age == age)
                && let Some(o) = self.open.pop()
            {
                self.instances.push(RecordedInstance {
                    id,
                    age,
                    frame: o.frame,
                    bark: Span::between(o.bark, mesh.bark.len() as u32),
                    leaves: Span::between(o.leaves, mesh.leaves.len() as u32),
                    exits: Span::between(o.exits, self.exits.len() as u32),
                    start_order: o.order,
                });
            }
        } else if symbol == self.markers.get {
            self.exits.push((id, age, Similarity::from_frame(frame)));
        }
    }

    fn end(&mut self) {
        self.builder.end();
    }
}
