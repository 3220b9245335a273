//! The variogram: half the mean squared height difference at each lag, along x, along z and
//! both, at lags growing by a factor of about 1.4 from one sample to a quarter of the map.
//! For fractional Brownian motion it grows as lag^(2H).

/// The lags measured, in samples: 1, then growing by about 1.4 up to a quarter of the side.
pub(crate) fn lags(size: usize) -> Vec<usize> {
    let mut out = vec![1usize];
    let top = (size / 4).max(2);
    while let Some(&last) = out.last() {
        let next = ((last as f64 * std::f64::consts::SQRT_2).round() as usize).max(last + 1);
        if next > top {
            break;
        }
        out.push(next);
    }
    out
}

/// Half the mean squared difference at `lag` along x and along z of a square grid of `n`
/// samples a side.
pub(crate) fn semivariance(n: usize, h: &[f32], lag: usize) -> (f64, f64) {
    let (mut sx, mut sz) = (0.0f64, 0.0f64);
    for z in 0..n {
        let row = &h[z * n..(z + 1) * n];
        for x in 0..n - lag {
            let d = f64::from(row[x + lag] - row[x]);
            sx += d * d;
        }
    }
    for z in 0..n - lag {
        let (a, b) = (&h[z * n..(z + 1) * n], &h[(z + lag) * n..(z + lag + 1) * n]);
        for x in 0..n {
            let d = f64::from(b[x] - a[x]);
            sz += d * d;
        }
    }
    let count = (n * (n - lag)) as f64;
    (0.5 * sx / count, 0.5 * sz / count)
}
