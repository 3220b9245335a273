//! cpfg's curve files: the curves of vlab's curve editor, which models read by arc length
//! with `curveX(id, t)`, `curveY(id, t)`, `curveZ(id, t)` and `curveGAL(id)` (the curve's
//! length), and which shape the cross-sections of generalized cylinders (`contour:` lines,
//! chosen with `@#(id)`).
//!
//! A curve is a uniform cubic B-spline: its control points (a point repeated as often as its
//! multiplicity says; a point given three times at each end pins the curve to it) with
//! integer knots, so that the span between knots `i` and `i + 1` blends points `i - 3` to
//! `i`. Parameter `u` in [0, 1] runs over all the spans. For lookups by arc length the curve
//! is sampled at `samples` evenly spaced parameters; its length is the length of that
//! polyline (as cpfg measures it), and the point at a fraction `t` of the length is found in
//! the table, then evaluated on the curve itself.
//!
//! A closed curve (`type: cr`) runs on from its last point to its first: its spans start
//! at every point and blend the points after it, wrapping round.
//!
//! Files come in two formats: `version: 1.4` (header lines `contact:`, `end:`, `heading:`,
//! `up:`, `size:`, `points: N`, `range:`, `dimension: D`, `type: bspline`, then N lines of
//! D numbers: `x y z multiplicity` when D is 4) and `cver 1 3` (`name:`, `points: N M`,
//! `type:`, `samples:`, then N lines `x y z multiplicity`).

use crate::file_lines::Lines;

/// Samples of a curve whose `curve:` line gives none (cpfg's default).
pub const DEFAULT_CURVE_SAMPLES: usize = 100;
/// Most control points of one curve (counting repeats).
pub const MAX_CURVE_POINTS: usize = 4096;
/// Most samples of one curve.
pub const MAX_CURVE_SAMPLES: usize = 1 << 16;
/// Most curves (or contours) one model reads.
pub const MAX_CURVES: usize = 1024;

/// Control points of one cubic span.
const ORDER: usize = 4;
/// Keeps the last parameter inside the last span (cpfg's own margin).
const END_MARGIN: f64 = 0.000_001;

/// One curve of a curve file, with its arc-length table.
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    /// Its name (a `cver` file's `name:` line).
    pub name: Option<String>,
    /// The control points, repeats included.
    pub points: Vec<[f64; 3]>,
    /// Whether the curve closes on itself (`type: cr`): its spans run on past the last
    /// point to the first.
    pub closed: bool,
    /// The polyline's length from the start to each of the evenly spaced samples.
    lengths: Vec<f64>,
}

impl Curve {
    /// A curve of these control points (at least 4) measured at `samples` (at least 2)
    /// evenly spaced parameters.
    ///
    /// ```
    /// use sylva_lsys::curve::Curve;
    /// // A straight line from (0, 0, 0) to (3, 0, 0), its ends pinned by repeats.
    /// let points = vec![[0.0, 0.0, 0.0]; 3].into_iter().chain(vec![[3.0, 0.0, 0.0]; 3]).collect();
    /// let line = Curve::new(None, points, false, 10)?;
    /// assert!((line.length() - 3.0).abs() < 1e-9);
    /// assert!((line.at_length(0.5)[0] - 1.5).abs() < 1e-5);
    /// # Ok::<(), String>(())
    /// ```
    pub fn new(
        name: Option<String>,
        points: Vec<[f64; 3]>,
        closed: bool,
        samples: usize,
    ) -> Result<Curve, String> {
        if points.len() < ORDER {
            return Err(format!(
                "{} control points: a curve needs at least {ORDER}",
                points.len()
            ));
        }
        if points.len() > MAX_CURVE_POINTS {
            return Err(format!(
                "{} control points: at most {MAX_CURVE_POINTS}",
                points.len()
            ));
        }
        if points.iter().flatten().any(|v| !v.is_finite()) {
            return Err("a control point is not a finite number".into());
        }
        if !(2..=MAX_CURVE_SAMPLES).contains(&samples) {
            return Err(format!(
                "{samples} samples: a curve takes 2 to {MAX_CURVE_SAMPLES}"
            ));
        }
        let mut curve = Curve {
            name,
            points,
            closed,
            lengths: Vec::with_capacity(samples),
        };
        let mut total = 0.0;
        let mut last = curve.point(0.0);
        for i in 0..samples {
            let here = curve.point(i as f64 / (samples - 1) as f64);
            total += distance(last, here);
            curve.lengths.push(total);
            last = here;
        }
        Ok(curve)
    }

    /// The point at parameter `u` (clamped to [0, 1]).
    pub fn point(&self, u: f64) -> [f64; 3] {
        let u = if u.is_nan() { 0.0 } else { u.clamp(0.0, 1.0) };
        let n = self.points.len();
        // Points changed since [`Curve::new`] checked them may be too few for a span.
        if n < ORDER {
            return self.points.first().copied().unwrap_or_default();
        }
        // An open curve's spans start at each point from the fourth on; a closed one's at
        // every point, the last ones blending the first points again.
        let (first, spans) = if self.closed {
            (ORDER - 1, n)
        } else {
            (ORDER - 1, n - 3)
        };
        let at = first as f64 + u * (spans as f64 - END_MARGIN);
        let span = (at.floor() as usize).clamp(first, first + spans - 1);
        let s = at - span as f64;
        // The uniform cubic B-spline's four blending weights at s in [0, 1).
        let weights = [
            (1.0 - s).powi(3) / 6.0,
            (3.0 * s.powi(3) - 6.0 * s * s + 4.0) / 6.0,
            (-3.0 * s.powi(3) + 3.0 * s * s + 3.0 * s + 1.0) / 6.0,
            s.powi(3) / 6.0,
        ];
        let mut sum = [0.0; 3];
        let blended = (span + 1 - ORDER..=span).map(|k| &self.points[k % n]);
        for (w, p) in weights.iter().zip(blended) {
            for (axis, v) in sum.iter_mut().zip(p) {
                *axis += w * v;
            }
        }
        sum
    }

    /// The curve's length, measured along its samples (cpfg's `curveGAL`).
    pub fn length(&self) -> f64 {
        self.lengths.last().copied().unwrap_or(0.0)
    }

    /// How many samples measure it.
    pub fn samples(&self) -> usize {
        self.lengths.len()
    }

    /// The point a fraction `t` (clamped to [0, 1]) of the length along the curve (cpfg's
    /// `curveX`, `curveY`, `curveZ`).
    pub fn at_length(&self, t: f64) -> [f64; 3] {
        let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
        let total = self.length();
        let last = self.lengths.len() - 1;
        if total <= 0.0 {
            return self.point(t);
        }
        let target = t * total;
        // The first sample at or past the target; the span before it holds it.
        let next = self.lengths.partition_point(|&l| l < target).clamp(1, last);
        let (low, high) = (self.lengths[next - 1], self.lengths[next]);
        let within = if high > low {
            (target - low) / (high - low)
        } else {
            0.0
        };
        self.point((next - 1) as f64 / last as f64 + within / last as f64)
    }

    /// Reads a curve file in either format, measured at `samples` (a `curve:` line's count)
    /// or else at the file's own `samples:` or [`DEFAULT_CURVE_SAMPLES`].
    ///
    /// ```
    /// use sylva_lsys::curve::Curve;
    /// let text = "cver 1 3\nname: flat\npoints: 2 6\ntype: or\nsamples: 8\n\
    ///             -1 0 0 3\n1 0 0 3\n";
    /// let c = Curve::parse(text, None)?;
    /// assert_eq!((c.points.len(), c.samples()), (6, 8));
    /// assert!((c.length() - 2.0).abs() < 1e-9);
    /// # Ok::<(), String>(())
    /// ```
    pub fn parse(text: &str, samples: Option<usize>) -> Result<Curve, String> {
        let mut lines = Lines::new(text);
        let mut line = lines.next_line()?;
        if line.starts_with("cver") {
            line = lines.next_line()?;
        }
        let (mut name, mut count, mut own_samples, mut dimension) = (None, None, None, 4);
        let mut closed = false;
        // Header lines (`version: 1.4` among them) until the first line of numbers.
        while let Some((key, value)) = line.split_once(':') {
            let value = value.trim();
            let number = || {
                value
                    .split_whitespace()
                    .next()
                    .and_then(|n| n.parse::<usize>().ok())
                    .ok_or_else(|| lines.at(format!("{key} '{value}': expected a count")))
            };
            match key.trim() {
                "name" => name = Some(value.to_owned()),
                "points" => count = Some(number()?),
                "samples" => own_samples = Some(number()?),
                "dimension" => dimension = number()?,
                // `o` open or `c` closed, then `r` regular knots or `e` end points
                // interpolated, which cpfg draws as regular too.
                "type" if value == "bspline" => {}
                "type" => match value.as_bytes() {
                    [b'o' | b'c', b'r' | b'e'] => closed = value.starts_with('c'),
                    _ => {
                        return Err(lines.at(format!(
                            "unsupported: curve type '{value}' (bspline, or, oe, cr and ce are read)"
                        )));
                    }
                },
                _ => {}
            }
            line = lines.next_line()?;
        }
        let count = count.ok_or_else(|| lines.at("no 'points:' line"))?;
        if count > MAX_CURVE_POINTS {
            return Err(lines.at(format!("{count} points: at most {MAX_CURVE_POINTS}")));
        }
        if !(2..=4).contains(&dimension) {
            return Err(lines.at(format!("dimension {dimension}: 2 to 4 are read")));
        }
        let mut points = Vec::with_capacity(count);
        for k in 0..count {
            if k > 0 {
                line = lines.next_line()?;
            }
            let numbers = lines.numbers_of(line, "a control point")?;
            if numbers.len() < dimension.min(3) {
                return Err(lines.at(format!("{} numbers: expected {dimension}", numbers.len())));
            }
            let times = match numbers.get(3) {
                Some(&m) if (1.0..=4.0).contains(&m) => m as usize,
                Some(&m) => return Err(lines.at(format!("multiplicity {m}: 1 to 4 are read"))),
                None => 1,
            };
            let point = [
                numbers[0],
                numbers[1],
                numbers.get(2).copied().unwrap_or(0.0),
            ];
            lines.repeat(&mut points, point, times, MAX_CURVE_POINTS)?;
        }
        let samples = samples.or(own_samples).unwrap_or(DEFAULT_CURVE_SAMPLES);
        Curve::new(name, points, closed, samples).map_err(|e| lines.at(e))
    }
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A closed square of four corners: the uniform B-spline through it is a rounded
    /// square, symmetric about both axes, that ends where it starts. At a span's start it
    /// is (P0 + 4 P1 + P2) / 6: for corners (1,1), (-1,1), (-1,-1), (1,-1) the first point
    /// is (1 - 4 - 1, 1 + 4 - 1) / 6 = (-2/3, 2/3).
    #[test]
    fn a_closed_curve_wraps_round() {
        let corners = vec![
            [1.0, 1.0, 0.0],
            [-1.0, 1.0, 0.0],
            [-1.0, -1.0, 0.0],
            [1.0, -1.0, 0.0],
        ];
        let c = Curve::new(None, corners, true, 401).unwrap();
        let start = c.point(0.0);
        assert!(
            (start[0] + 2.0 / 3.0).abs() < 1e-12 && (start[1] - 2.0 / 3.0).abs() < 1e-12,
            "{start:?}"
        );
        let end = c.point(1.0);
        assert!(
            (end[0] - start[0]).abs() < 1e-5 && (end[1] - start[1]).abs() < 1e-5,
            "{end:?}"
        );
        // A quarter of the way round by length: the next corner's point, (-2/3, -2/3).
        let quarter = c.at_length(0.25);
        assert!(
            (quarter[0] + 2.0 / 3.0).abs() < 1e-3 && (quarter[1] + 2.0 / 3.0).abs() < 1e-3,
            "{quarter:?}"
        );
        let text = "cver 1 3\nname: sq\npoints: 4 4\ntype: cr\nsamples: 8\n1 1 0 1\n-1 1 0 1\n-1 -1 0 1\n1 -1 0 1\n";
        assert!(Curve::parse(text, None).unwrap().closed);
    }

    /// The profile of vlab's Ridley phyllotaxis model (`version: 1.4`, four points, the
    /// ends tripled: eight control points, five spans).
    const PROFILE: &str = "version: 1.4\ncontact: 0 0 0\nend: 0 0 0\nheading: 0 1 0\n\
        up: 0 0 -1\nsize: 1\npoints: 4\nrange: 0.0 1.0\ndimension: 4\ntype: bspline\n\
        0.269398 -0.447751 0 3\n0.274471 -0.109864 0 1\n0.165305 0.175183 0 1\n\
        -0.001478 0.202475 0 3\n";

    #[test]
    fn ends_are_pinned_and_the_middle_blends_four_points() {
        let c = Curve::parse(PROFILE, None).unwrap();
        assert_eq!(c.points.len(), 8);
        let start = c.point(0.0);
        assert!((start[0] - 0.269398).abs() < 1e-12 && (start[1] + 0.447751).abs() < 1e-12);
        let end = c.point(1.0);
        assert!((end[0] + 0.001478).abs() < 1e-5 && (end[1] - 0.202475).abs() < 1e-5);
        // u = 1/2 is 3 + 2.5 (less the margin): span 5 at s = 1/2 blends control points 2
        // to 5 (the given P0, P1, P2, P3) by 1/48, 23/48, 23/48, 1/48: x = (0.269398 +
        // 23 * (0.274471 + 0.165305) - 0.001478) / 48 = 0.216308.
        let mid = c.point(0.5);
        assert!((mid[0] - 0.216_308).abs() < 1e-5, "{mid:?}");
    }

    #[test]
    fn lengths_and_lookups_match_cpfg() {
        // Known answers of cpfg's curveGAL and curveX/Y on this file at 100 samples.
        let c = Curve::parse(PROFILE, Some(100)).unwrap();
        assert!((c.length() - 0.779429).abs() < 1e-6, "{}", c.length());
        let half = c.at_length(0.5);
        assert!(
            (half[0] - 0.243388).abs() < 1e-5 && (half[1] + 0.060038).abs() < 1e-5,
            "{half:?}"
        );
        let quarter = c.at_length(0.25);
        assert!(
            (quarter[0] - 0.268860).abs() < 1e-5 && (quarter[1] + 0.252937).abs() < 1e-5,
            "{quarter:?}"
        );
        // Clamped at both ends.
        assert_eq!(c.at_length(-3.0), c.at_length(0.0));
        assert_eq!(c.at_length(7.0), c.at_length(1.0));
    }

    #[test]
    fn bad_files_are_errors_with_their_line() {
        assert!(
            Curve::parse("cver 1 3\nname: a\npoints: x\n", None)
                .unwrap_err()
                .starts_with("line 3:")
        );
        let odd = "cver 1 3\nname: a\npoints: 4 4\ntype: xr\nsamples: 8\n";
        assert!(
            Curve::parse(odd, None)
                .unwrap_err()
                .contains("unsupported: curve type 'xr'")
        );
        let few = "cver 1 3\npoints: 2 2\ntype: or\n0 0 0 1\n1 0 0 1\n";
        assert!(Curve::parse(few, None).unwrap_err().contains("at least 4"));
        let huge = "cver 1 3\npoints: 999999 3\ntype: or\n";
        assert!(Curve::parse(huge, None).is_err());
        let nan = "cver 1 3\npoints: 4 4\n0 0 0 1\nNaN 0 0 1\n0 1 0 1\n1 1 0 1\n";
        assert!(
            Curve::parse(nan, None)
                .unwrap_err()
                .contains("expected a control point")
        );
        let short = "cver 1 3\npoints: 4 4\n0 0 0 1\n";
        assert!(
            Curve::parse(short, None)
                .unwrap_err()
                .contains("ends after")
        );
    }
}
