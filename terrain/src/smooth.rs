//! Separable Gaussian smoothing.

use crate::error::{TerrainError, check};
use crate::heightmap::Heightmap;

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
        let src = self.heights().to_vec();
        let mut tmp = vec![0.0f32; n * n];
        // Horizontal pass through a padded row, so the inner loops run over contiguous memory.
        let mut pad = vec![0.0f32; n + 2 * r];
        for z in 0..n {
            let row = &src[z * n..(z + 1) * n];
            for (i, p) in pad.iter_mut().enumerate() {
                *p = row[index(i as isize - r as isize)];
            }
            let out = &mut tmp[z * n..(z + 1) * n];
            for (x, o) in out.iter_mut().enumerate() {
                *o = w[0] * pad[x + r];
            }
            for (k, &wk) in w.iter().enumerate().skip(1) {
                let (left, right) = (&pad[r - k..r - k + n], &pad[r + k..r + k + n]);
                for ((o, a), b) in out.iter_mut().zip(left).zip(right) {
                    *o += wk * (a + b);
                }
            }
        }
        // Vertical pass: whole rows at a time.
        let heights = self.heights_mut();
        for z in 0..n {
            let out = &mut heights[z * n..(z + 1) * n];
            out.copy_from_slice(&tmp[z * n..(z + 1) * n]);
            out.iter_mut().for_each(|o| *o *= w[0]);
            for (k, &wk) in w.iter().enumerate().skip(1) {
                let (za, zb) = (
                    index(z as isize - k as isize),
                    index(z as isize + k as isize),
                );
                let (a, b) = (&tmp[za * n..(za + 1) * n], &tmp[zb * n..(zb + 1) * n]);
                for ((o, a), b) in out.iter_mut().zip(a).zip(b) {
                    *o += wk * (a + b);
                }
            }
        }
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
