//! Straight lines through log-log points, and the range over which one holds.

/// A least-squares line `y = slope x + intercept` over points `from..=to`, with its largest
/// residual.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Line {
    pub(crate) slope: f64,
    pub(crate) intercept: f64,
    pub(crate) worst: f64,
    pub(crate) from: usize,
    pub(crate) to: usize,
}

/// The least-squares line through `points[from..=to]`.
pub(crate) fn line(points: &[(f64, f64)], from: usize, to: usize) -> Line {
    let span = &points[from..=to];
    let n = span.len() as f64;
    let (mx, my) = span
        .iter()
        .fold((0.0, 0.0), |(a, b), p| (a + p.0 / n, b + p.1 / n));
    let num: f64 = span.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let den: f64 = span.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    let slope = if den > 0.0 { num / den } else { 0.0 };
    let intercept = my - slope * mx;
    let worst = span
        .iter()
        .map(|p| (p.1 - slope * p.0 - intercept).abs())
        .fold(0.0, f64::max);
    Line {
        slope,
        intercept,
        worst,
        from,
        to,
    }
}

/// The widest run of at least `min_points` consecutive points that one line fits within
/// `tolerance` (natural-log units) at every point with a slope `accept` takes (a fractal's,
/// not a plateau's); among runs as wide, the closest fit. Where the log-log curve bends, the
/// run ends: its ends are the scale range of the fit. `None` for fewer than `min_points`
/// points.
pub(crate) fn widest_straight_run(
    points: &[(f64, f64)],
    min_points: usize,
    tolerance: f64,
    accept: impl Fn(f64) -> bool,
) -> Option<Line> {
    let n = points.len();
    if n < min_points.max(2) {
        return None;
    }
    let mut best: Option<Line> = None;
    for from in 0..n {
        for to in from + min_points.max(2) - 1..n {
            let l = line(points, from, to);
            if l.worst > tolerance || !accept(l.slope) {
                continue;
            }
            let wider = best.is_none_or(|b| {
                let (w, bw) = (
                    points[l.to].0 - points[l.from].0,
                    points[b.to].0 - points[b.from].0,
                );
                w > bw + 1e-9 || ((w - bw).abs() <= 1e-9 && l.worst < b.worst)
            });
            if wider {
                best = Some(l);
            }
        }
    }
    // Nothing straight enough: the line through all, which says how bent it is.
    best.or_else(|| Some(line(points, 0, n - 1)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_run_ends_where_the_curve_bends() {
        // Slope 1 up to x = 5, then flat: a variogram that saturates.
        let points: Vec<(f64, f64)> = (0..10).map(|i| (i as f64, (i as f64).min(5.0))).collect();
        let l = widest_straight_run(&points, 3, 0.05, |s| s > 0.1).unwrap();
        assert_eq!((l.from, l.to), (0, 5));
        assert!((l.slope - 1.0).abs() < 1e-9);
    }
}
