//! Separable Gaussian smoothing, rows on every core. Each output is the same sum in the same
//! order at any thread count, so the heights are the same bits.

use rayon::prelude::*;

use crate::error::{TerrainError, check};
use crate::heightmap::Heightmap;

/// Fewest rows a task takes: enough that a task's rows share their neighbours in cache and
/// the scheduling is paid rarely, few enough that small maps still split.
const ROWS_PER_TASK: usize = 16;
/// Columns summed at once in the vertical pass: a few vector registers' worth.
const STRIP: usize = 32;

/// How the blur treats samples beyond the edges.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum EdgeMode {
    /// Mirror the map about its edge samples: no darkening (as zero padding would cause) and
    /// no pull towards a constant (as clamping would), and a border stays where it was on a
    /// symmetric neighbourhood.
    #[default]
    Mirror,
    /// Periodic, for maps generated with `wrap`: opposite edges stay equal.
    Wrap,
}

/// Largest sigma accepted, in samples.
pub const MAX_SIGMA: f32 = 256.0;

impl Heightmap {
    /// Blurs the heights with a Gaussian of standard deviation `sigma` samples (the kernel
    /// reaches 3 sigma). The mean is preserved exactly with [`EdgeMode::Wrap`] and up to edge
    /// effects with [`EdgeMode::Mirror`].
    ///
    /// ```
    /// let mut map = sylva_terrain::DiamondSquare::new(65).generate().unwrap();
    /// let rough = map.clone();
    /// map.smooth(2.0, sylva_terrain::EdgeMode::Mirror).unwrap();
    /// assert_ne!(map, rough);
    /// ```
    pub fn smooth(&mut self, sigma: f32, edges: EdgeMode) -> Result<(), TerrainError> {
        check(
            "sigma",
            f64::from(sigma),
            (0.0..=MAX_SIGMA).contains(&sigma),
            "in [0, 256] samples",
        )?;
        if sigma == 0.0 {
            return Ok(());
        }
        let r = (3.0 * sigma).ceil() as usize;
        let mut w: Vec<f32> = (0..=r)
            .map(|k| (-((k * k) as f32) / (2.0 * sigma * sigma)).exp())
            .collect();
        let total = w[0] + 2.0 * w[1..].iter().sum::<f32>();
        w.iter_mut().for_each(|v| *v /= total);
        let n = self.size();
        // Periodic maps repeat every n - 1 samples; the last row and column are copies.
        let period = if edges == EdgeMode::Wrap { n - 1 } else { n };
        let index = |i: isize| -> usize {
            match edges {
                EdgeMode::Wrap => i.rem_euclid(period as isize) as usize,
                _ => reflect(i, n),
            }
        };
        // Horizontal pass into `tmp`, rows on every core: each row goes through a padded
        // copy so that the inner loops run over contiguous memory (and vectorise).
        let mut tmp = vec![0.0f32; n * n];
        let src = self.heights();
        tmp.par_chunks_mut(n)
            .zip(src.par_chunks(n))
            .with_min_len(ROWS_PER_TASK)
            .for_each_init(
                || vec![0.0f32; n + 2 * r],
                |pad, (out, row)| {
                    for (i, p) in pad.iter_mut().enumerate() {
                        *p = row[index(i as isize - r as isize)];
                    }
                    for (x, o) in out.iter_mut().enumerate() {
                        *o = w[0] * pad[x + r];
                    }
                    for (k, &wk) in w.iter().enumerate().skip(1) {
                        let (left, right) = (&pad[r - k..r - k + n], &pad[r + k..r + k + n]);
                        for ((o, a), b) in out.iter_mut().zip(left).zip(right) {
                            *o += wk * (a + b);
                        }
                    }
                },
            );
        // Vertical pass back into the heights, whole rows at a time on every core. A row is
        // worked in strips of `STRIP` columns whose sums stay in registers over all 2r + 1
        // rows read, so each output is written once (the sum's order is a row's, term by
        // term: the same bits).
        let heights = self.heights_mut();
        heights
            .par_chunks_mut(n)
            .enumerate()
            .with_min_len(ROWS_PER_TASK)
            .for_each(|(z, out)| {
                let taps: Vec<(f32, &[f32], &[f32])> = w
                    .iter()
                    .enumerate()
                    .skip(1)
                    .map(|(k, &wk)| {
                        let (za, zb) = (
                            index(z as isize - k as isize),
                            index(z as isize + k as isize),
                        );
                        (wk, &tmp[za * n..(za + 1) * n], &tmp[zb * n..(zb + 1) * n])
                    })
                    .collect();
                let centre = &tmp[z * n..(z + 1) * n];
                let mut x = 0;
                while x + STRIP <= n {
                    let mut sum = [0.0f32; STRIP];
                    for (s, c) in sum.iter_mut().zip(&centre[x..x + STRIP]) {
                        *s = c * w[0];
                    }
                    for &(wk, a, b) in &taps {
                        let (a, b) = (&a[x..x + STRIP], &b[x..x + STRIP]);
                        for ((s, a), b) in sum.iter_mut().zip(a).zip(b) {
                            *s += wk * (a + b);
                        }
                    }
                    out[x..x + STRIP].copy_from_slice(&sum);
                    x += STRIP;
                }
                for x in x..n {
                    let mut s = centre[x] * w[0];
                    for &(wk, a, b) in &taps {
                        s += wk * (a[x] + b[x]);
                    }
                    out[x] = s;
                }
            });
        if edges == EdgeMode::Wrap {
            let c = n - 1;
            for z in 0..n {
                heights[z * n + c] = heights[(z % c) * n];
            }
            for x in 0..n {
                heights[c * n + x] = heights[x];
            }
        }
        Ok(())
    }
}

/// Mirror index about the first and last sample (the edge sample is not repeated), folded as
/// often as needed for kernels wider than the map.
fn reflect(i: isize, n: usize) -> usize {
    if n == 1 {
        return 0;
    }
    let period = 2 * (n as isize - 1);
    let m = i.rem_euclid(period);
    if m < n as isize {
        m as usize
    } else {
        (period - m) as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reflect_folds_about_the_edges() {
        let r: Vec<usize> = (-3..8).map(|i| reflect(i, 5)).collect();
        assert_eq!(r, [3, 2, 1, 0, 1, 2, 3, 4, 3, 2, 1]);
    }

    #[test]
    fn constant_maps_stay_constant() {
        let mut m = Heightmap::from_heights(9, 1.0, vec![3.0; 81]).unwrap();
        m.smooth(1.5, EdgeMode::Mirror).unwrap();
        assert!(m.heights().iter().all(|&h| (h - 3.0).abs() < 1e-5));
    }
}
