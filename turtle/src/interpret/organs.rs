//! What the turtle draws whole at its place: leaves, spheres and discs, a model's surfaces,
//! and generalized cylinders (round tubes, or a contour's sheet).

use glam::Vec3;
use sylva_base::hash::{mix, unit_f32};

use super::{Args, LEAF_KEEP_SALT, MAX_CURVE_POINTS, OpenCylinder, Turtle};
use crate::error::TurtleError;
use crate::sink::{GeometrySink, Segment};
use crate::symbols::Command;

impl<S: GeometrySink + ?Sized> Turtle<'_, '_, S> {
    /// A leaf (parameter: its scale), a sphere or a disc (parameter: the diameter, in width
    /// units) at the turtle.
    pub(super) fn organ(&mut self, command: Command, args: Args) -> Result<(), TurtleError> {
        let (options, frame) = (self.options, self.state.frame);
        if self.state.broken {
            return Ok(());
        }
        if command == Command::Leaf {
            self.leaves_seen = self.leaves_seen.wrapping_add(1);
            let order = unit_f32(mix(u64::from(self.leaves_seen) ^ LEAF_KEEP_SALT));
            if options.leaf_keep < 1.0 && order >= options.leaf_keep.max(0.0) {
                return Ok(());
            }
            let scale = args.get(0)?.unwrap_or(1.0).abs();
            self.sink.leaf(
                &frame.facing_sky(options.leaf_facing),
                [options.leaf_size[0] * scale, options.leaf_size[1] * scale],
                order,
            );
            self.stats.leaves += 1;
            return Ok(());
        }
        let diameter = args
            .get(0)?
            .map_or(self.state.width, |d| d * options.width_unit);
        let radius = (diameter * 0.5).abs().max(options.min_radius);
        let faces = if command == Command::Sphere {
            crate::shapes::sphere(frame.position, radius, &frame)
        } else {
            vec![crate::shapes::disc(frame.position, radius, &frame)]
        };
        self.faces(&faces);
        Ok(())
    }

    /// `~l(s)`: the model's surface `k` at the turtle, `s` (default 1) times its size.
    pub(super) fn surface(&mut self, k: usize, args: Args) -> Result<(), TurtleError> {
        let size = args.get(0)?.unwrap_or(1.0) * self.scale * self.options.length_unit;
        let Some((_, quads)) = self.options.shapes.surfaces.get(k) else {
            return Ok(());
        };
        if self.state.broken {
            return Ok(());
        }
        let faces = crate::shapes::placed(quads, &self.state.frame, size);
        self.faces(&faces);
        Ok(())
    }

    /// A generalized cylinder: started, a control point added, or ended and emitted as
    /// segments along the smooth curve through its points.
    pub(super) fn curve(&mut self, command: Command) {
        let radius = self.radius();
        let position = self.state.frame.position;
        if command == Command::CurveStart {
            self.curve = Some(OpenCylinder {
                points: vec![(position, radius)],
                frame: self.state.frame,
                contour: self.state.contour,
            });
            return;
        }
        if let Some(OpenCylinder { points, .. }) = &mut self.curve
            && points.last().map(|p| p.0) != Some(position)
            && points.len() < MAX_CURVE_POINTS
        {
            points.push((position, radius));
        }
        if command != Command::CurveEnd {
            return;
        }
        let Some(OpenCylinder {
            points,
            frame,
            contour,
        }) = self.curve.take()
        else {
            return;
        };
        let pieces = crate::shapes::curve(&points, &frame);
        // A contour's cylinder is a sheet of quads the sink takes as polygons; a circle's
        // is segments, tubes like the branches'.
        if let Some(contour) = self.options.shapes.contour(contour).filter(|_| contour > 0) {
            if self.state.broken {
                return;
            }
            let faces = crate::shapes::sweep(&pieces, contour);
            self.faces(&faces);
            return;
        }
        let mut parent = self.state.last;
        for (k, piece) in pieces.iter().enumerate() {
            self.sink.segment(&Segment {
                id: self.next_id,
                parent,
                continues_parent: k > 0,
                frame: piece.frame,
                length: piece.length,
                start_radius: piece.radii.0,
                end_radius: piece.radii.1,
                depth: self.state.depth,
            });
            parent = Some(self.next_id);
            self.next_id = self.next_id.saturating_add(1);
            self.stats.segments += 1;
        }
        if let Some(id) = parent.filter(|_| points.len() > 1) {
            self.sink.axis_end(id);
        }
    }

    /// Sends whole faces (a sphere's, a surface's, a contour's sheet) to the sink.
    fn faces(&mut self, faces: &[Vec<Vec3>]) {
        for face in faces {
            self.sink.polygon(face);
        }
        self.stats.polygons = self.stats.polygons.saturating_add(faces.len() as u32);
    }
}
