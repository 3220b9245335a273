//! The turtle itself: walks a word and drives a `GeometrySink`.

use glam::Vec3;
use sylva_lsys::Word;

use crate::error::TurtleError;
use crate::frame::Frame;
use crate::options::{Tropism, TurtleOptions};
use crate::sink::{GeometrySink, Segment};
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
    let mut stats = InterpretStats::default();
    let mut state = State {
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
    };
    let mut stack: Vec<State> = Vec::new();
    let mut polygons: Vec<Vec<Vec3>> = Vec::new();
    // The control points of the generalized cylinder being traced, and the frame it
    // started with.
    let mut curve: Option<(Vec<(Vec3, f32)>, Frame)> = None;
    // The step, width and scale before each open sub-L-system (cpfg's `?(id, scale)` ...
    // `$`), and the scale in force: explicit lengths are multiplied by it.
    let mut sub_scales: Vec<(f32, f32, f32)> = Vec::new();
    let mut scale = 1.0f32;
    let mut next_id = 0u32;
    sink.begin();
    for (index, module) in word.iter().enumerate() {
        let Some(command) = table.get(module.id.index()).copied().flatten() else {
            continue;
        };
        let arg = |k: usize| -> Result<Option<f32>, TurtleError> {
            match module.params.get(k) {
                None => Ok(None),
                Some(&v) if v.is_finite() && v.abs() <= f64::from(MAX_COORDINATE) => {
                    Ok(Some(v as f32))
                }
                Some(&v) => Err(TurtleError::OutOfRange {
                    index,
                    symbol: module.symbol,
                    value: v,
                }),
            }
        };
        match command {
            Command::Draw | Command::Move => {
                let length = arg(0)?.map_or(state.step, |l| l * options.length_unit * scale);
                let start = state.frame;
                state.frame.position += state.frame.heading() * length;
                let reach = state.frame.position.abs().max_element();
                if reach.is_nan() || reach > MAX_COORDINATE {
                    return Err(TurtleError::OutOfRange {
                        index,
                        symbol: module.symbol,
                        value: f64::from(length),
                    });
                }
                if curve.is_some() {
                    // Inside a generalized cylinder the turtle only moves; the tube comes
                    // from the control points.
                } else if let Some(poly) = polygons.last_mut() {
                    // Inside a polygon, moves trace its outline instead of drawing branches.
                    if poly.is_empty() {
                        poly.push(start.position);
                    }
                    poly.push(state.frame.position);
                } else if command == Command::Draw {
                    let radius = (state.width * 0.5).max(options.min_radius);
                    let continues = state.same_axis && state.last.is_some();
                    let start_radius = match (continues, options.shape) {
                        (true, crate::BranchShape::Frustum) => state.last_radius,
                        _ => radius,
                    };
                    let segment = Segment {
                        id: next_id,
                        parent: state.last,
                        continues_parent: continues,
                        frame: start,
                        length,
                        start_radius,
                        end_radius: radius,
                        depth: state.depth,
                    };
                    sink.segment(&segment);
                    state.last = Some(next_id);
                    state.same_axis = true;
                    state.last_radius = radius;
                    next_id = next_id.saturating_add(1);
                    stats.segments += 1;
                } else {
                    end_axis(&mut state, sink);
                }
                if let Some(t) = state.tropism {
                    state
                        .frame
                        .bend_towards(t.direction.normalize_or_zero(), t.susceptibility);
                }
            }
            Command::Yaw(sign) => state.frame.yaw(sign.factor() * angle(arg(0)?, state.angle)),
            Command::Pitch(sign) => state
                .frame
                .pitch(sign.factor() * angle(arg(0)?, state.angle)),
            Command::Roll(sign) => state
                .frame
                .roll(sign.factor() * angle(arg(0)?, state.angle)),
            Command::TurnAround => state.frame.yaw(std::f32::consts::PI),
            Command::RollToHorizontal => state.frame.roll_to_horizontal(),
            Command::Push => {
                if stack.len() >= options.max_depth {
                    return Err(TurtleError::TooDeep {
                        index,
                        limit: options.max_depth,
                    });
                }
                stack.push(state);
                state.same_axis = false;
                state.depth += 1;
                stats.max_depth = stats.max_depth.max(state.depth);
            }
            Command::Pop => {
                let Some(saved) = stack.pop() else {
                    return Err(TurtleError::UnbalancedPop { index });
                };
                end_axis(&mut state, sink);
                if saved.colour != state.colour {
                    sink.colour(saved.colour);
                }
                state = saved;
            }
            Command::Width => {
                state.width = match arg(0)? {
                    Some(w) => sanitize_width(w * options.width_unit),
                    None => sanitize_width(state.width * options.width_factor),
                };
            }
            Command::ScaleLength => state.step *= arg(0)?.unwrap_or(options.length_factor),
            Command::ScaleAngle => state.angle *= arg(0)?.unwrap_or(options.angle_factor),
            Command::PolygonStart => {
                if polygons.len() >= options.max_depth {
                    return Err(TurtleError::TooDeep {
                        index,
                        limit: options.max_depth,
                    });
                }
                polygons.push(Vec::new());
            }
            Command::PolygonVertex => {
                if let Some(poly) = polygons.last_mut()
                    && poly.last() != Some(&state.frame.position)
                {
                    poly.push(state.frame.position);
                }
            }
            Command::PolygonEnd => {
                if let Some(mut poly) = polygons.pop() {
                    // An outline that returns to its start closes itself; drop the duplicate.
                    if let (Some(&a), Some(&b)) = (poly.first(), poly.last())
                        && poly.len() > 1
                        && a.distance(b) <= 1e-5 * (1.0 + a.length())
                    {
                        poly.pop();
                    }
                    if poly.len() >= 3 {
                        sink.polygon(&poly);
                        stats.polygons += 1;
                    }
                }
            }
            Command::Leaf => {
                let scale = arg(0)?.unwrap_or(1.0).abs();
                sink.leaf(
                    &state.frame.facing_sky(options.leaf_facing),
                    [options.leaf_size[0] * scale, options.leaf_size[1] * scale],
                );
                stats.leaves += 1;
            }
            Command::Marker => {
                sink.marker(module.symbol, module.params, &state.frame);
                stats.markers += 1;
            }
            Command::Sphere | Command::Disc => {
                let diameter = arg(0)?.map_or(state.width, |d| d * options.width_unit);
                let radius = (diameter * 0.5).abs().max(options.min_radius);
                let faces = if command == Command::Sphere {
                    crate::shapes::sphere(state.frame.position, radius, &state.frame)
                } else {
                    vec![crate::shapes::disc(
                        state.frame.position,
                        radius,
                        &state.frame,
                    )]
                };
                for face in &faces {
                    sink.polygon(face);
                }
                stats.polygons = stats.polygons.saturating_add(faces.len() as u32);
            }
            Command::CurveStart => {
                let radius = (state.width * 0.5).max(options.min_radius);
                curve = Some((vec![(state.frame.position, radius)], state.frame));
            }
            Command::CurvePoint | Command::CurveEnd => {
                let radius = (state.width * 0.5).max(options.min_radius);
                if let Some((points, _)) = &mut curve
                    && points.last().map(|p| p.0) != Some(state.frame.position)
                    && points.len() < MAX_CURVE_POINTS
                {
                    points.push((state.frame.position, radius));
                }
                if command == Command::CurveEnd
                    && let Some((points, frame)) = curve.take()
                {
                    let mut parent = state.last;
                    for (k, piece) in crate::shapes::curve(&points, &frame).iter().enumerate() {
                        let segment = Segment {
                            id: next_id,
                            parent,
                            continues_parent: k > 0,
                            frame: piece.frame,
                            length: piece.length,
                            start_radius: piece.radii.0,
                            end_radius: piece.radii.1,
                            depth: state.depth,
                        };
                        sink.segment(&segment);
                        parent = Some(next_id);
                        next_id = next_id.saturating_add(1);
                        stats.segments += 1;
                    }
                    if let Some(id) = parent.filter(|_| points.len() > 1) {
                        sink.axis_end(id);
                    }
                }
            }
            Command::Query => sink.query(index, &state.frame),
            Command::Colour(sign) => {
                let colour = match arg(0)? {
                    Some(n) => n.max(0.0).min(u32::MAX as f32) as u32,
                    None if sign == Sign::Positive => state.colour.saturating_add(1),
                    None => state.colour.saturating_sub(1),
                };
                if colour != state.colour {
                    state.colour = colour;
                    sink.colour(colour);
                }
            }
            Command::SubStart => {
                if sub_scales.len() >= options.max_depth {
                    return Err(TurtleError::TooDeep {
                        index,
                        limit: options.max_depth,
                    });
                }
                let factor = arg(1)?.unwrap_or(1.0);
                sub_scales.push((state.step, state.width, scale));
                state.step *= factor;
                state.width = sanitize_width(state.width * factor);
                scale *= factor;
            }
            Command::SubEnd => {
                if let Some((step, width, before)) = sub_scales.pop() {
                    state.step = step;
                    state.width = width;
                    scale = before;
                }
            }
            Command::TropismDirection => {
                let direction = Vec3::new(
                    arg(0)?.unwrap_or(0.0),
                    arg(1)?.unwrap_or(-1.0),
                    arg(2)?.unwrap_or(0.0),
                );
                let susceptibility = state.tropism.map_or(0.0, |t| t.susceptibility);
                state.tropism = Some(Tropism {
                    direction,
                    susceptibility,
                });
            }
            Command::TropismSusceptibility => {
                let susceptibility = arg(0)?.unwrap_or(0.0);
                let direction = state.tropism.map_or(Vec3::NEG_Y, |t| t.direction);
                state.tropism = Some(Tropism {
                    direction,
                    susceptibility,
                });
            }
            Command::Ignore => {}
        }
    }
    end_axis(&mut state, sink);
    while let Some(mut saved) = stack.pop() {
        end_axis(&mut saved, sink);
    }
    sink.end();
    Ok(stats)
}

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
