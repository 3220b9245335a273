//! The distribution of heights: range, moments and percentiles.

use crate::heightmap::Heightmap;

/// How a surface's heights are spread.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct HeightDistribution {
    /// Lowest height.
    pub min: f32,
    /// Highest height.
    pub max: f32,
    /// Mean height.
    pub mean: f32,
    /// Standard deviation.
    pub std_dev: f32,
    /// Skewness (0 for a symmetric spread; positive: a long tail of peaks).
    pub skewness: f32,
    /// Excess kurtosis (0 for a normal spread).
    pub kurtosis: f32,
    /// Heights at the 1st, 5th, 25th, 50th, 75th, 95th and 99th percentiles.
    pub percentiles: [f32; 7],
}

/// The percentiles [`HeightDistribution::percentiles`] holds.
pub const PERCENTILES: [f32; 7] = [1.0, 5.0, 25.0, 50.0, 75.0, 95.0, 99.0];

impl HeightDistribution {
    /// The distribution of `map`'s heights.
    pub fn of(map: &Heightmap) -> HeightDistribution {
        Self::of_heights(map.heights())
    }

    /// The distribution of heights `h` (all zero for none).
    pub fn of_heights(h: &[f32]) -> HeightDistribution {
        if h.is_empty() {
            return HeightDistribution {
                min: 0.0,
                max: 0.0,
                mean: 0.0,
                std_dev: 0.0,
                skewness: 0.0,
                kurtosis: 0.0,
                percentiles: [0.0; 7],
            };
        }
        let n = h.len() as f64;
        let mean = h.iter().map(|&v| f64::from(v)).sum::<f64>() / n;
        let (m2, m3, m4) = h.iter().fold((0.0, 0.0, 0.0), |(a, b, c), &v| {
            let d = f64::from(v) - mean;
            (a + d * d / n, b + d * d * d / n, c + d * d * d * d / n)
        });
        let sd = m2.sqrt();
        let mut sorted = h.to_vec();
        sorted.sort_by(f32::total_cmp);
        let at = |p: f32| sorted[((p / 100.0) * (sorted.len() - 1) as f32).round() as usize];
        HeightDistribution {
            min: sorted[0],
            max: sorted[sorted.len() - 1],
            mean: mean as f32,
            std_dev: sd as f32,
            skewness: if sd > 0.0 {
                (m3 / (sd * sd * sd)) as f32
            } else {
                0.0
            },
            kurtosis: if sd > 0.0 {
                (m4 / (m2 * m2) - 3.0) as f32
            } else {
                0.0
            },
            percentiles: PERCENTILES.map(at),
        }
    }
}
