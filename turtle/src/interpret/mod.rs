//! The turtle itself: walks a word and drives a `GeometrySink`.

use glam::Vec3;
use sylva_lsys::Word;

mod organs;
mod stem;

use crate::error::TurtleError;
use crate::frame::Frame;
use crate::options::{Tropism, TurtleOptions};
use crate::sink::GeometrySink;
use crate::symbols::{Command, Sign};

/// Largest distance from the origin the turtle may reach.
const MAX_COORDINATE: f32 = 1e9;

/// Counts of what one interpretation emitted.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct InterpretStats {
    /// Segments drawn.
    pub segments: u32,
    /// Polygons emitted.
    pub polygons: u32,
    /// Leaves emitted.
    pub leaves: u32,
    /// Markers passed on.
    pub markers: u32,
    /// Deepest bracket nesting reached.
    pub max_depth: u32,
}

#[derive(Debug, Clone, Copy)]
struct State {
    frame: Frame,
    width: f32,
    step: f32,
    angle: f32,
    /// The last segment drawn on this path, and whether the next one continues its axis.
    last: Option<u32>,
    same_axis: bool,
    /// End radius of `last`, where a continuing frustum starts.
    last_radius: f32,
    depth: u32,
    /// The tropism in force: the options' at first, changed by tropism modules and kept
    /// per branch like the rest of the state.
    tropism: Option<Tropism>,
    /// The colour index (cpfg's and L-Py's `;` and `,`).
    colour: u32,
    /// Whether this path lies above a broken stem ([`TurtleOptions::stem_break`]): the
    /// turtle moves on but draws nothing. Kept per branch, so branches that left the trunk
    /// below the break, and restored by their `]`, draw.
    broken: bool,
    /// The contour generalized cylinders take as their cross-section (`@#(id)`; 0 a
    /// circle).
    contour: u32,
}

/// The stems `word` would draw with `options` (its modules that draw), or
/// [`TurtleError::TooManyPieces`] at the first past [`TurtleOptions::max_pieces`]: the cost
/// of a tree known before any geometry is made, in the memory of its word alone.
/// [`interpret`] checks it first.
///
/// ```
/// use sylva_turtle::{check_stems, TurtleOptions};
/// let word: sylva_lsys::Word = "F[+F]F[-F]f".parse().unwrap();
/// assert_eq!(check_stems(&word, &TurtleOptions::default()), Ok(4));
/// assert!(check_stems(&word, &TurtleOptions::default().with_max_pieces(3)).is_err());
/// ```
pub fn check_stems(word: &Word, options: &TurtleOptions) -> Result<u64, TurtleError> {
    count_stems(
        word,
        &options.symbols.resolve(word.alphabet()),
        options.max_pieces,
    )
}

/// [`check_stems`] with the word's symbols already resolved (`interpret` resolves them once
/// for both).
fn count_stems(word: &Word, table: &[Option<Command>], limit: u64) -> Result<u64, TurtleError> {
    let mut stems = 0u64;
    for (index, module) in word.iter().enumerate() {
        if table.get(module.id.index()).copied().flatten() == Some(Command::Draw) {
            stems += 1;
            if stems > limit {
                return Err(TurtleError::TooManyPieces { index, limit });
            }
        }
    }
    Ok(stems)
}

/// Interprets `word` with the turtle described by `options`, sending geometry to `sink`.
///
/// ```
/// use sylva_turtle::{interpret, Skeleton, TurtleOptions};
/// let word: sylva_lsys::Word = "F+F+F+F".parse().unwrap();
/// let mut skeleton = Skeleton::default();
/// interpret(&word, &TurtleOptions::default().with_angle(90.0), &mut skeleton).unwrap();
/// assert_eq!(skeleton.bones.len(), 4);
/// assert!(skeleton.bones[3].end.length() < 1e-5); // back at the start
/// ```
pub fn interpret<S: GeometrySink + ?Sized>(
    word: &Word,
    options: &TurtleOptions,
    sink: &mut S,
) -> Result<InterpretStats, TurtleError> {
    let table = options.symbols.resolve(word.alphabet());
    count_stems(word, &table, options.max_pieces)?;
    let mut turtle = Turtle::new(options, sink);
    turtle.sink.begin();
    for (index, module) in word.iter().enumerate() {
        let Some(command) = table.get(module.id.index()).copied().flatten() else {
            continue;
        };
        let args = Args {
            params: module.params,
            index,
            symbol: module.symbol,
        };
        match command {
            Command::Draw | Command::Move => turtle.advance(args, command == Command::Draw)?,
            Command::Yaw(_)
            | Command::Pitch(_)
            | Command::Roll(_)
            | Command::TurnAround
            | Command::RollToHorizontal => turtle.turn(command, args)?,
            Command::Push => turtle.push(index)?,
            Command::Pop => turtle.pop(index)?,
            Command::Width | Command::ScaleLength | Command::ScaleAngle => {
                turtle.scale(command, args)?;
            }
            Command::PolygonStart | Command::PolygonVertex | Command::PolygonEnd => {
                turtle.polygon(command, index)?;
            }
            Command::Leaf | Command::Sphere | Command::Disc => turtle.organ(command, args)?,
            Command::Marker => {
                turtle
                    .sink
                    .marker(module.symbol, module.params, &turtle.state.frame);
                turtle.stats.markers += 1;
            }
            Command::Query => turtle.sink.query(index, &turtle.state.frame),
            Command::CurveStart | Command::CurvePoint | Command::CurveEnd => turtle.curve(command),
            Command::Colour(sign) => turtle.colour(sign, args)?,
            Command::SubStart => turtle.sub_start(args)?,
            Command::SubEnd => turtle.sub_end(),
            Command::TropismDirection | Command::TropismSusceptibility => {
                turtle.tropism(command, args)?;
            }
            Command::Surface(k) => turtle.surface(usize::from(k), args)?,
            Command::Contour => {
                turtle.state.contour = args.get(0)?.map_or(0, |id| id.max(0.0) as u32);
            }
            Command::Ignore => {}
        }
        // Checked as the geometry grows: a bomb stops at the limit, in bounded memory.
        let s = &turtle.stats;
        let pieces = u64::from(s.segments) + u64::from(s.leaves) + u64::from(s.polygons);
        if pieces > options.max_pieces {
            return Err(TurtleError::TooManyPieces {
                index,
                limit: options.max_pieces,
            });
        }
    }
    Ok(turtle.finish())
}

/// A generalized cylinder between its `@Gs` and its `@Ge`.
struct OpenCylinder {
    /// Control points: position and radius.
    points: Vec<(Vec3, f32)>,
    /// The turtle's frame at the start.
    frame: Frame,
    /// The contour in force at the start (0: a circle).
    contour: u32,
}

/// One module's actual parameters, with where it is for errors.
#[derive(Debug, Clone, Copy)]
struct Args<'a> {
    params: &'a [f64],
    index: usize,
    symbol: char,
}

impl Args<'_> {
    /// Parameter `k` as a length or angle: none when absent, an error when not finite or
    /// beyond [`MAX_COORDINATE`].
    fn get(&self, k: usize) -> Result<Option<f32>, TurtleError> {
        match self.params.get(k) {
            None => Ok(None),
            Some(&v) if v.is_finite() && v.abs() <= f64::from(MAX_COORDINATE) => Ok(Some(v as f32)),
            Some(&v) => Err(self.out_of_range(v)),
        }
    }

    fn out_of_range(&self, value: f64) -> TurtleError {
        TurtleError::OutOfRange {
            index: self.index,
            symbol: self.symbol,
            value,
        }
    }
}

/// The turtle walking a word: its state, the branches it will return to, the open polygons,
/// curve and sub-L-systems, and what it emitted so far.
struct Turtle<'o, 's, S: GeometrySink + ?Sized> {
    options: &'o TurtleOptions,
    sink: &'s mut S,
    state: State,
    stack: Vec<State>,
    polygons: Vec<Vec<Vec3>>,
    /// The generalized cylinder being traced.
    curve: Option<OpenCylinder>,
    /// The step, width and scale before each open sub-L-system (cpfg's `?(id, scale)` ...
    /// `$`).
    sub_scales: Vec<(f32, f32, f32)>,
    /// The scale in force: explicit lengths are multiplied by it.
    scale: f32,
    next_id: u32,
    /// The radius of the first segment drawn: stems of at least `stem::CURVE_MIN_SHARE` of
    /// it are drawn curved ([`TurtleOptions::curve_steps`]).
    base_radius: Option<f32>,
    /// Leaves met so far, drawn or not: [`TurtleOptions::leaf_keep`] draws by this count.
    leaves_seen: u32,
    stats: InterpretStats,
}

impl<'o, 's, S: GeometrySink + ?Sized> Turtle<'o, 's, S> {
    fn new(options: &'o TurtleOptions, sink: &'s mut S) -> Self {
        Turtle {
            options,
            sink,
            state: State {
                frame: Frame::IDENTITY,
                width: sanitize_width(options.width),
                step: options.step,
                angle: options.angle.to_radians(),
                last: None,
                same_axis: false,
                last_radius: 0.0,
                depth: 0,
                tropism: options.tropism,
                colour: 0,
                broken: false,
                contour: 0,
            },
            stack: Vec::new(),
            polygons: Vec::new(),
            curve: None,
            sub_scales: Vec::new(),
            scale: 1.0,
            next_id: 0,
            base_radius: None,
            leaves_seen: 0,
            stats: InterpretStats::default(),
        }
    }

    /// Ends the open axes (this path's and every unclosed branch's) and the sink.
    fn finish(mut self) -> InterpretStats {
        end_axis(&mut self.state, self.sink);
        while let Some(mut saved) = self.stack.pop() {
            end_axis(&mut saved, self.sink);
        }
        self.sink.end();
        self.stats
    }

    /// The radius of a branch drawn now.
    fn radius(&self) -> f32 {
        (self.state.width * 0.5).max(self.options.min_radius)
    }

    /// An error if `open` more of something would pass the nesting limit.
    fn check_depth(&self, open: usize, index: usize) -> Result<(), TurtleError> {
        if open >= self.options.max_depth {
            return Err(TurtleError::TooDeep {
                index,
                limit: self.options.max_depth,
            });
        }
        Ok(())
    }

    /// The rotations: yaw, pitch and roll by the parameter (degrees) or the angle in force,
    /// turning around, rolling level.
    fn turn(&mut self, command: Command, args: Args) -> Result<(), TurtleError> {
        let by = |sign: Sign| -> Result<f32, TurtleError> {
            Ok(sign.factor() * angle(args.get(0)?, self.state.angle))
        };
        match command {
            Command::Yaw(sign) => self.state.frame.yaw(by(sign)?),
            Command::Pitch(sign) => self.state.frame.pitch(by(sign)?),
            Command::Roll(sign) => self.state.frame.roll(by(sign)?),
            Command::TurnAround => self.state.frame.yaw(std::f32::consts::PI),
            Command::RollToHorizontal => self.state.frame.roll_to_horizontal(),
            _ => {}
        }
        Ok(())
    }

    /// `[`: a branch starts; the state is kept to return to.
    fn push(&mut self, index: usize) -> Result<(), TurtleError> {
        self.check_depth(self.stack.len(), index)?;
        self.stack.push(self.state);
        self.state.same_axis = false;
        self.state.depth += 1;
        self.stats.max_depth = self.stats.max_depth.max(self.state.depth);
        Ok(())
    }

    /// `]`: the branch ends; back to the state at its `[`, and its colour.
    fn pop(&mut self, index: usize) -> Result<(), TurtleError> {
        let Some(saved) = self.stack.pop() else {
            return Err(TurtleError::UnbalancedPop { index });
        };
        end_axis(&mut self.state, self.sink);
        if saved.colour != self.state.colour {
            self.sink.colour(saved.colour);
        }
        self.state = saved;
        Ok(())
    }

    /// `!`, `"` and `;`-like scalings: the width set (parameter, in width units) or
    /// multiplied by the options' factor; the step and the angle multiplied.
    fn scale(&mut self, command: Command, args: Args) -> Result<(), TurtleError> {
        let options = self.options;
        match command {
            Command::Width => {
                self.state.width = match args.get(0)? {
                    Some(w) => sanitize_width(w * options.width_unit),
                    None => sanitize_width(self.state.width * options.width_factor),
                };
            }
            Command::ScaleLength => {
                self.state.step *= args.get(0)?.unwrap_or(options.length_factor);
            }
            Command::ScaleAngle => {
                self.state.angle *= args.get(0)?.unwrap_or(options.angle_factor);
            }
            _ => {}
        }
        Ok(())
    }

    /// `{`, `.` and `}`: a polygon opened, a vertex recorded, the polygon closed and emitted
    /// when it has three or more vertices.
    fn polygon(&mut self, command: Command, index: usize) -> Result<(), TurtleError> {
        let position = self.state.frame.position;
        match command {
            Command::PolygonStart => {
                self.check_depth(self.polygons.len(), index)?;
                self.polygons.push(Vec::new());
            }
            Command::PolygonVertex => {
                if let Some(poly) = self.polygons.last_mut()
                    && poly.last() != Some(&position)
                {
                    poly.push(position);
                }
            }
            Command::PolygonEnd => {
                if let Some(mut poly) = self.polygons.pop() {
                    // An outline that returns to its start closes itself; drop the duplicate.
                    if let (Some(&a), Some(&b)) = (poly.first(), poly.last())
                        && poly.len() > 1
                        && a.distance(b) <= 1e-5 * (1.0 + a.length())
                    {
                        poly.pop();
                    }
                    if poly.len() >= 3 && !self.state.broken {
                        self.sink.polygon(&poly);
                        self.stats.polygons += 1;
                    }
                }
            }
            _ => {}
        }
        Ok(())
    }

    /// `;` and `,`: the colour index set (parameter) or stepped up or down.
    fn colour(&mut self, sign: Sign, args: Args) -> Result<(), TurtleError> {
        let colour = match args.get(0)? {
            Some(n) => n.max(0.0).min(u32::MAX as f32) as u32,
            None if sign == Sign::Positive => self.state.colour.saturating_add(1),
            None => self.state.colour.saturating_sub(1),
        };
        if colour != self.state.colour {
            self.state.colour = colour;
            self.sink.colour(colour);
        }
        Ok(())
    }

    /// cpfg's `?(id, scale)`: a sub-L-system starts, its lengths and widths scaled.
    fn sub_start(&mut self, args: Args) -> Result<(), TurtleError> {
        self.check_depth(self.sub_scales.len(), args.index)?;
        let factor = args.get(1)?.unwrap_or(1.0);
        self.sub_scales
            .push((self.state.step, self.state.width, self.scale));
        self.state.step *= factor;
        self.state.width = sanitize_width(self.state.width * factor);
        self.scale *= factor;
        Ok(())
    }

    /// `$`: the sub-L-system ends; back to the step, width and scale before it.
    fn sub_end(&mut self) {
        if let Some((step, width, before)) = self.sub_scales.pop() {
            self.state.step = step;
            self.state.width = width;
            self.scale = before;
        }
    }

    /// The tropism's direction (parameters x, y, z) or susceptibility (parameter) changed,
    /// the other kept.
    fn tropism(&mut self, command: Command, args: Args) -> Result<(), TurtleError> {
        let before = self.state.tropism;
        let tropism = if command == Command::TropismDirection {
            Tropism {
                direction: Vec3::new(
                    args.get(0)?.unwrap_or(0.0),
                    args.get(1)?.unwrap_or(-1.0),
                    args.get(2)?.unwrap_or(0.0),
                ),
                susceptibility: before.map_or(0.0, |t| t.susceptibility),
            }
        } else {
            Tropism {
                direction: before.map_or(Vec3::NEG_Y, |t| t.direction),
                susceptibility: args.get(0)?.unwrap_or(0.0),
            }
        };
        self.state.tropism = Some(tropism);
        Ok(())
    }
}

/// Separates the leaf-thinning draws from other uses of the leaf count.
const LEAF_KEEP_SALT: u64 = 0x1eaf_0000_d1eb_ac4b;

/// Most control points one generalized cylinder keeps: the rest are dropped.
const MAX_CURVE_POINTS: usize = 1 << 16;

fn angle(param: Option<f32>, default: f32) -> f32 {
    param.map_or(default, f32::to_radians)
}

/// Negative and non-finite widths become 0 (a defined result instead of NaN geometry).
fn sanitize_width(w: f32) -> f32 {
    if w.is_finite() { w.max(0.0) } else { 0.0 }
}

fn end_axis<S: GeometrySink + ?Sized>(state: &mut State, sink: &mut S) {
    if state.same_axis
        && let Some(id) = state.last
    {
        sink.axis_end(id);
    }
    state.same_axis = false;
}
