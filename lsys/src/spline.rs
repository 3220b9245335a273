//! cpfg's function files: the curves of vlab's function editor, which models read with
//! `func(id, x)`. A function is a cubic B-spline through control points on the unit square
//! (x from 0 to 1), with a clamped uniform knot vector so that it starts at the first point
//! and ends at the last; `func(id, x)` is the height of the curve where it crosses x.
//!
//! Files come in two formats: the old (`range: 0 1`, `points: N`, then N lines `x y`) and
//! `fver 1 1` (`name:`, `samples:`, optional `background` and `markers:` lines, `flip:`,
//! `points: N`, then N lines `x y [multiplicity]`, a point repeated `multiplicity` times).
//! A function set (`.fset`, `funcgalleryver 1 1`, `items: K`) holds K functions of the
//! second format, each named.
//!
//! As cpfg does, a function with more than two samples is tabulated at that many evenly
//! spaced x and read by linear interpolation between them; one without is tabulated at
//! [`DENSE_SAMPLES`] (cpfg searches the curve instead, to within 0.001 in x). Arguments
//! outside [0, 1] are clamped.

use crate::file_lines::Lines;

/// Samples of a function whose file gives none (or two or fewer).
pub const DENSE_SAMPLES: usize = 1025;
/// Most control points of one function (counting repeats).
pub const MAX_POINTS: usize = 4096;
/// Most samples of one function.
pub const MAX_SAMPLES: usize = 1 << 16;
/// Most functions in one set.
pub const MAX_FUNCTIONS: usize = 1024;

/// Order of the B-spline (cubic).
const ORDER: usize = 4;
/// How close in x the search for a sample comes (cpfg's tolerance).
const X_TOLERANCE: f64 = 0.001;
/// Most halvings of the search: a curve whose x never reaches the target stops here.
const MAX_HALVINGS: u32 = 60;

/// One function of a function file, ready to evaluate.
#[derive(Debug, Clone, PartialEq)]
pub struct SplineFunction {
    /// Its name (the `name:` line; `None` in the old format).
    pub name: Option<String>,
    /// The control points, repeats included.
    pub points: Vec<[f64; 2]>,
    /// The values at `values.len()` evenly spaced x from 0 to 1.
    values: Vec<f64>,
}

impl SplineFunction {
    /// A function of these control points (at least 4), tabulated at `samples` (more than
    /// 2) or at [`DENSE_SAMPLES`].
    ///
    /// ```
    /// use sylva_lsys::spline::SplineFunction;
    /// // A straight line from (0, 0) to (1, 1): every x maps to itself.
    /// let line = SplineFunction::new(None, vec![[0.0, 0.0], [1.0 / 3.0, 1.0 / 3.0], [2.0 / 3.0, 2.0 / 3.0], [1.0, 1.0]], None)?;
    /// assert!((line.value(0.25) - 0.25).abs() < 2e-3);
    /// assert_eq!(line.value(-1.0), line.value(0.0));
    /// # Ok::<(), String>(())
    /// ```
    pub fn new(
        name: Option<String>,
        points: Vec<[f64; 2]>,
        samples: Option<usize>,
    ) -> Result<SplineFunction, String> {
        if points.len() < ORDER {
            return Err(format!(
                "{} control points: a function needs at least {ORDER}",
                points.len()
            ));
        }
        if points.len() > MAX_POINTS {
            return Err(format!(
                "{} control points: at most {MAX_POINTS}",
                points.len()
            ));
        }
        if points.iter().flatten().any(|v| !v.is_finite()) {
            return Err("a control point is not a finite number".into());
        }
        let samples = match samples {
            Some(s) if s > MAX_SAMPLES => {
                return Err(format!("{s} samples: at most {MAX_SAMPLES}"));
            }
            Some(s) if s > 2 => s,
            _ => DENSE_SAMPLES,
        };
        let mut f = SplineFunction {
            name,
            points,
            values: Vec::new(),
        };
        f.values = (0..samples)
            .map(|i| f.search(i as f64 / (samples - 1) as f64))
            .collect();
        Ok(f)
    }

    /// The point of the curve at parameter `d` in [0, 1) (at 1 the clamped basis is empty:
    /// the end point is reached only in the limit).
    pub fn point(&self, d: f64) -> [f64; 2] {
        let n = self.points.len() - 1;
        let u = d.clamp(0.0, 1.0) * (n + 2 - ORDER) as f64;
        let mut sum = [0.0; 2];
        for (k, p) in self.points.iter().enumerate() {
            let w = basis(k, ORDER, u, n);
            sum[0] += w * p[0];
            sum[1] += w * p[1];
        }
        sum
    }

    /// The curve's height where it crosses `x` (clamped to [0, 1]), from the table.
    pub fn value(&self, x: f64) -> f64 {
        let x = if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) };
        let last = self.values.len() - 1;
        let at = x * last as f64;
        let i = (at.floor() as usize).min(last);
        if i == last {
            return self.values[last];
        }
        let t = at - i as f64;
        (1.0 - t) * self.values[i] + t * self.values[i + 1]
    }

    /// The height where the curve crosses `x`, by halving the parameter until the curve's x
    /// is within [`X_TOLERANCE`] of it.
    fn search(&self, x: f64) -> f64 {
        let (mut low, mut high) = (0.0f64, 1.0f64);
        let mut point = self.point(0.5);
        for _ in 0..MAX_HALVINGS {
            let check = (low + high) / 2.0;
            point = self.point(check);
            if point[0] > x {
                high = check;
            } else {
                low = check;
            }
            if (point[0] - x).abs() <= X_TOLERANCE {
                break;
            }
        }
        point[1]
    }

    /// Reads a `.func` file in either format; `samples` (a view file's `function:` line's
    /// count) tabulates an old-format file.
    ///
    /// ```
    /// use sylva_lsys::spline::SplineFunction;
    /// let text = "fver 1 1\nname: growth\nsamples: 100\nflip: off\npoints: 4\n\
    ///             0 0\n0.333333 0.333333\n0.666667 0.666667\n1 1\n";
    /// let f = SplineFunction::parse_func(text, None)?;
    /// assert_eq!(f.name.as_deref(), Some("growth"));
    /// assert!((f.value(0.5) - 0.5).abs() < 2e-3);
    /// # Ok::<(), String>(())
    /// ```
    pub fn parse_func(text: &str, samples: Option<usize>) -> Result<SplineFunction, String> {
        let mut lines = Lines::new(text);
        let first = lines.next_line()?;
        if first.starts_with("range:") {
            let count = lines.count("points:")?;
            let points = lines.points(count, false)?;
            return SplineFunction::new(None, points, samples);
        }
        version(first, "fver")?;
        lines.function()
    }

    /// Reads a function set (`.fset`): its functions in order.
    pub fn parse_set(text: &str) -> Result<Vec<SplineFunction>, String> {
        let mut lines = Lines::new(text);
        version(lines.next_line()?, "funcgalleryver")?;
        let items = lines.count("items:")?;
        if items > MAX_FUNCTIONS {
            return Err(format!("{items} functions: at most {MAX_FUNCTIONS}"));
        }
        (0..items)
            .map(|_| {
                version(lines.next_line()?, "fver")?;
                lines.function()
            })
            .collect()
    }
}

/// The B-spline basis function `k` of order `t` at `u`, over the clamped uniform knots of
/// `n + 1` control points (Cox and de Boor's recursion; `t` is at most 4, so 15 calls).
fn basis(k: usize, t: usize, u: f64, n: usize) -> f64 {
    let knot = |j: usize| -> f64 {
        if j < ORDER {
            0.0
        } else if j > n {
            (n + 2 - ORDER) as f64
        } else {
            (j + 1 - ORDER) as f64
        }
    };
    if t == 1 {
        return if knot(k) <= u && u < knot(k + 1) {
            1.0
        } else {
            0.0
        };
    }
    let mut sum = 0.0;
    let span = knot(k + t - 1) - knot(k);
    if span != 0.0 {
        sum += (u - knot(k)) / span * basis(k, t - 1, u, n);
    }
    let span = knot(k + t) - knot(k + 1);
    if span != 0.0 {
        sum += (knot(k + t) - u) / span * basis(k + 1, t - 1, u, n);
    }
    sum
}

/// Checks a version line `word 1 1`.
fn version(line: &str, word: &str) -> Result<(), String> {
    let mut parts = line.split_whitespace();
    if parts.next() != Some(word) {
        return Err(format!("expected '{word} 1 1', found '{line}'"));
    }
    match (parts.next(), parts.next()) {
        (Some("1"), Some("1")) => Ok(()),
        (major, minor) => Err(format!(
            "{word} {} {}: only version 1 1 is known",
            major.unwrap_or("?"),
            minor.unwrap_or("?")
        )),
    }
}

impl Lines<'_> {
    /// `count` lines of `x y` (and, with `repeats`, an optional multiplicity).
    fn points(&mut self, count: usize, repeats: bool) -> Result<Vec<[f64; 2]>, String> {
        if count > MAX_POINTS {
            return Err(self.at(format!("{count} points: at most {MAX_POINTS}")));
        }
        let mut points = Vec::with_capacity(count);
        for _ in 0..count {
            let line = self.next_line()?;
            let numbers: Vec<f64> = line
                .split_whitespace()
                .map(str::parse)
                .collect::<Result<_, _>>()
                .map_err(|_| self.at(format!("'{line}': expected x y")))?;
            let times = match (numbers.len(), repeats) {
                (2, _) => 1,
                (3, true) if numbers[2] >= 1.0 && numbers[2] <= 4.0 => numbers[2] as usize,
                _ => return Err(self.at(format!("'{line}': expected x y"))),
            };
            self.repeat(&mut points, [numbers[0], numbers[1]], times, MAX_POINTS)?;
        }
        Ok(points)
    }

    /// A function of the `fver 1 1` format, after its version line.
    fn function(&mut self) -> Result<SplineFunction, String> {
        let name = self.field("name:")?.to_owned();
        let samples = self.count("samples:")?;
        // Optional lines the editor keeps for itself: a background image, markers.
        let mut line = self.next_line()?;
        if line.starts_with("background") {
            self.next_line()?;
            line = self.next_line()?;
        }
        if let Some(markers) = line.strip_prefix("markers:") {
            let markers: usize = markers
                .trim()
                .parse()
                .map_err(|_| self.at("markers: expected a count"))?;
            if markers > MAX_POINTS {
                return Err(self.at(format!("{markers} markers: at most {MAX_POINTS}")));
            }
            for _ in 0..markers {
                self.next_line()?;
            }
            line = self.next_line()?;
        }
        if !line.starts_with("flip:") {
            return Err(self.at(format!("expected 'flip:', found '{line}'")));
        }
        let count = self.count("points:")?;
        let points = self.points(count, true)?;
        SplineFunction::new(Some(name), points, Some(samples)).map_err(|e| self.at(e))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Control points on the line y = 2x: the basis weights at every parameter sum to 1, so
    /// every point of the curve is a mean of points on the line, and its height at x is 2x.
    #[test]
    fn collinear_points_give_their_line() {
        let points: Vec<[f64; 2]> = (0..7)
            .map(|i| [i as f64 / 6.0, 2.0 * i as f64 / 6.0])
            .collect();
        let f = SplineFunction::new(None, points, Some(101)).unwrap();
        for x in [0.0, 0.1, 0.37, 0.5, 0.9] {
            assert!((f.value(x) - 2.0 * x).abs() < 3e-3, "{x}: {}", f.value(x));
        }
        // The curve starts at its first point.
        assert_eq!(f.point(0.0), [0.0, 0.0]);
    }

    /// Four points: the curve is one cubic Bezier segment (clamped knots 0 0 0 0 1 1 1 1).
    /// At parameter 1/2 it is (P0 + 3 P1 + 3 P2 + P3) / 8, worked by hand.
    #[test]
    fn four_points_are_a_bezier_segment() {
        let points = vec![[0.0, 0.0], [0.2, 1.0], [0.8, 1.0], [1.0, 0.0]];
        let f = SplineFunction::new(None, points, None).unwrap();
        let mid = f.point(0.5);
        assert!(
            (mid[0] - 0.5).abs() < 1e-12 && (mid[1] - 0.75).abs() < 1e-12,
            "{mid:?}"
        );
        // By symmetry the curve's height at x = 1/2 is that point's.
        assert!((f.value(0.5) - 0.75).abs() < 1e-3, "{}", f.value(0.5));
        // At u = 1/4 the Bernstein weights are 27/64, 27/64, 9/64, 1/64:
        // x = (27/64)(0.2) + (9/64)(0.8) + 1/64 = 0.2125, y = 27/64 + 9/64 = 0.5625.
        let q = f.point(0.25);
        assert!(
            (q[0] - 0.2125).abs() < 1e-12 && (q[1] - 0.5625).abs() < 1e-12,
            "{q:?}"
        );
        assert!(
            (f.value(0.2125) - 0.5625).abs() < 2e-3,
            "{}",
            f.value(0.2125)
        );
    }

    #[test]
    fn both_formats_and_sets_read() {
        let old = "range: 0.0 1.0\npoints: 4\n0 1\n0.3 1\n0.6 1\n1 1\n";
        let f = SplineFunction::parse_func(old, Some(10)).unwrap();
        assert_eq!((f.name.clone(), f.values.len()), (None, 10));
        assert!((f.value(0.3) - 1.0).abs() < 1e-9);
        let set = "funcgalleryver 1 1\nitems: 2\n\
                   fver 1 1\nname: A\nsamples: 5\nflip: off\npoints: 4\n0 0\n0.3 0\n0.6 0\n1 0\n\
                   fver 1 1\nname: B\nsamples: 5\nmarkers: 1\nm1 0.5 0.5\nflip: on\npoints: 3\n0 2 2\n0.5 2\n1 2\n";
        let fs = SplineFunction::parse_set(set).unwrap();
        assert_eq!(fs.len(), 2);
        assert_eq!(fs[1].name.as_deref(), Some("B"));
        // The first point counted twice: four control points.
        assert_eq!(fs[1].points.len(), 4);
        assert!((fs[1].value(0.7) - 2.0).abs() < 1e-9);
    }

    #[test]
    fn bad_files_are_errors_with_their_line() {
        let e = SplineFunction::parse_func("fver 1 1\nname: a\nsamples: x\n", None).unwrap_err();
        assert!(e.starts_with("line 3:"), "{e}");
        assert!(SplineFunction::parse_func("fver 2 0\n", None).is_err());
        let few = "range: 0 1\npoints: 3\n0 0\n0.5 0\n1 0\n";
        assert!(
            SplineFunction::parse_func(few, None)
                .unwrap_err()
                .contains("at least 4")
        );
        let huge = "range: 0 1\npoints: 99999999\n";
        assert!(SplineFunction::parse_func(huge, None).is_err());
        let nan = "range: 0 1\npoints: 4\n0 0\nNaN 0\n0.5 0\n1 0\n";
        assert!(SplineFunction::parse_func(nan, None).is_err());
        // A curve whose x never reaches 1 still ends: the search stops after its halvings.
        let short = SplineFunction::new(
            None,
            vec![[0.0, 0.0], [0.1, 0.0], [0.2, 0.0], [0.3, 1.0]],
            Some(4),
        )
        .unwrap();
        assert!(short.value(1.0).is_finite());
    }
}
