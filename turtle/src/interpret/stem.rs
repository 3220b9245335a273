//! The turtle's steps forward: a segment drawn (in pieces where the tropism curves it), a
//! polygon's outline traced, or a move, each bent by the tropism in force.

use super::{Args, MAX_COORDINATE, Turtle, end_axis};
use crate::error::TurtleError;
use crate::frame::Frame;
use crate::sink::{GeometrySink, Segment};

/// The thinnest stem drawn curved, as a share of the first segment's radius: thinner ones
/// are too short for their bend to show.
const CURVE_MIN_SHARE: f32 = 0.15;
/// The least bend, radians, for which a stem is drawn curved.
const MIN_CURVE_BEND: f32 = 0.02;
/// The most pieces a curved stem is drawn in.
const MAX_CURVE_STEPS: u32 = 8;
/// How much narrower a broken trunk ends than it would have been there: torn wood, not a
/// saw cut.
const BREAK_TAPER: f32 = 0.7;

impl<S: GeometrySink + ?Sized> Turtle<'_, '_, S> {
    /// `F` and `f`: a step forward (parameter: its length), drawing a segment when `draw`,
    /// tracing a polygon's outline inside one, only moving inside a generalized cylinder;
    /// then bent by the tropism in force (a drawn segment of several pieces is bent after
    /// each).
    pub(super) fn advance(&mut self, args: Args, draw: bool) -> Result<(), TurtleError> {
        let length = args.get(0)?.map_or(self.state.step, |l| {
            l * self.options.length_unit * self.scale
        });
        let start = self.state.frame;
        self.state.frame.position += self.state.frame.heading() * length;
        let reach = self.state.frame.position.abs().max_element();
        if reach.is_nan() || reach > MAX_COORDINATE {
            return Err(args.out_of_range(f64::from(length)));
        }
        let mut steps = 1;
        if self.curve.is_some() {
            // Inside a generalized cylinder the turtle only moves; the tube comes from the
            // control points.
        } else if let Some(poly) = self.polygons.last_mut() {
            // Inside a polygon, moves trace its outline instead of drawing branches.
            if poly.is_empty() {
                poly.push(start.position);
            }
            poly.push(self.state.frame.position);
        } else if draw {
            steps = self.curve_steps();
            self.state.frame = start;
            self.draw(length, steps);
        } else {
            end_axis(&mut self.state, self.sink);
        }
        self.bend(steps);
        Ok(())
    }

    /// How many pieces the segment drawn now is drawn in: [`TurtleOptions::curve_steps`]
    /// for stems of at least [`CURVE_MIN_SHARE`] of the first segment's radius that the
    /// tropism bends by more than [`MIN_CURVE_BEND`]; 1 otherwise.
    ///
    /// [`TurtleOptions::curve_steps`]: crate::TurtleOptions::curve_steps
    fn curve_steps(&self) -> u32 {
        let steps = self.options.curve_steps.clamp(1, MAX_CURVE_STEPS);
        let Some(t) = self.state.tropism.filter(|_| steps > 1) else {
            return 1;
        };
        // The first segment sets the base radius, so it is thick by definition.
        let thick = self
            .base_radius
            .is_none_or(|base| self.radius() >= CURVE_MIN_SHARE * base);
        // A stem the tropism would turn by less than a degree (a trunk along gravity) has
        // nothing to curve.
        let h = self.state.frame.heading();
        let bend = t.susceptibility.abs() * h.cross(t.direction.normalize_or_zero()).length();
        if thick && bend > MIN_CURVE_BEND {
            steps
        } else {
            1
        }
    }

    /// Turns the heading by a `steps`-th of the tropism in force.
    fn bend(&mut self, steps: u32) {
        if let Some(t) = self.state.tropism {
            self.state.frame.bend_towards(
                t.direction.normalize_or_zero(),
                t.susceptibility / steps as f32,
            );
        }
    }

    /// A segment of `length` from the turtle, continuing the axis of the last one when
    /// nothing branched off between them, drawn as `steps` straight pieces with the tropism
    /// bending the heading between them (the caller bends after the last), so the stem
    /// curves through its length; the radius runs from the start's to the end's across the
    /// pieces.
    fn draw(&mut self, length: f32, steps: u32) {
        let continues = self.state.same_axis && self.state.last.is_some();
        let to = self.radius();
        let from = match (continues, self.options.shape) {
            (true, crate::BranchShape::Frustum) => self.state.last_radius,
            _ => to,
        };
        let radius = |k: u32| {
            if k == steps {
                to
            } else {
                from + (to - from) * (k as f32 / steps as f32)
            }
        };
        let piece = length / steps as f32;
        for k in 0..steps {
            if k > 0 {
                self.bend(steps);
            }
            let start = self.state.frame;
            self.state.frame.position += self.state.frame.heading() * piece;
            self.draw_piece(start, piece, (radius(k), radius(k + 1)));
        }
    }

    /// One straight segment of `length` from `start` with the radii at its ends.
    fn draw_piece(&mut self, start: Frame, length: f32, (start_radius, radius): (f32, f32)) {
        if self.state.broken {
            return;
        }
        let (mut length, mut radius) = (length, radius);
        let mut breaks = false;
        if let Some(height) = self
            .options
            .stem_break
            .filter(|b| start_radius >= b.min_radius)
            .map(|b| b.height)
        {
            let rise = start.heading().y * length;
            let from = start.position.y;
            if from >= height {
                self.state.broken = true;
                end_axis(&mut self.state, self.sink);
                return;
            }
            if from + rise > height {
                // The trunk snaps here: the piece ends at the break, a little splintered
                // (narrower) where it tore.
                let share = (height - from) / rise;
                length *= share;
                radius = (start_radius + (radius - start_radius) * share) * BREAK_TAPER;
                breaks = true;
            }
        }
        let continues = self.state.same_axis && self.state.last.is_some();
        self.base_radius.get_or_insert(start_radius);
        self.sink.segment(&Segment {
            id: self.next_id,
            parent: self.state.last,
            continues_parent: continues,
            frame: start,
            length,
            start_radius,
            end_radius: radius,
            depth: self.state.depth,
        });
        self.state.last = Some(self.next_id);
        self.state.same_axis = true;
        self.state.last_radius = radius;
        self.next_id = self.next_id.saturating_add(1);
        self.stats.segments += 1;
        if breaks {
            end_axis(&mut self.state, self.sink);
            self.state.broken = true;
        }
    }
}
