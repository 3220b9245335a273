//! Feature extraction (the Garden of Eden thesis, 7.5, after Yokoya, Yamamoto and Funakubo,
//! "Fractal-based analysis and interpolation of 3D natural surface shapes", 1989): how rough
//! a surface is and over which scales, measured so that terrain can be made to match.
//!
//! [`FractalAnalysis::of`] fits the Hurst exponent H (fractal dimension 3 - H) twice: from
//! the variogram (half the mean squared height difference grows as lag^(2H)) and from the
//! profiles' power spectrum (power falls as frequency^-(2H + 1)). Each fit is over the widest
//! range of scales on which the log-log points stay on one line: where they bend (the
//! variogram flattening at the size of the hills, the grid's imprint at the finest lags) is
//! where the surface stops being that fractal, and the range is reported in metres.
//!
//! ```
//! use sylva_terrain::analysis::FractalAnalysis;
//! use sylva_terrain::SpectralSynthesis;
//!
//! let map = SpectralSynthesis::new(257).with_hurst(0.7).with_seed(3).generate()?;
//! let a = FractalAnalysis::of(&map);
//! assert!((a.hurst - 0.7).abs() < 0.1, "{}", a.hurst);
//! assert!((a.dimension - (3.0 - a.hurst)).abs() < 1e-9);
//! # Ok::<(), sylva_terrain::TerrainError>(())
//! ```

mod fit;
mod heights;
mod spectrum;
mod variogram;

pub use heights::{HeightDistribution, PERCENTILES};

use crate::dem::ElevationModel;
use crate::heightmap::Heightmap;
use fit::{Line, widest_straight_run};

/// How far (natural log) a point may stray from the fitted line inside the scale range.
const TOLERANCE: f64 = 0.06;
/// Fewest points a fit stands on.
const MIN_POINTS: usize = 4;

/// A fit of H over a range of scales.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct HurstFit {
    /// The Hurst exponent.
    pub hurst: f64,
    /// The scales the fit holds over, metres (lags for the variogram, wavelengths for the
    /// spectrum), finest first.
    pub scale_range: [f64; 2],
    /// The largest distance of a point in the range from the line (natural log).
    pub worst_residual: f64,
    /// Slope and intercept of the line in log-log (natural logs, metres).
    pub line: [f64; 2],
}

/// A surface's fractal character.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct FractalAnalysis {
    /// H from the variogram, both axes (the headline figure).
    pub hurst: f64,
    /// Fractal dimension of the surface, 3 - H.
    pub dimension: f64,
    /// The variogram's fit, both axes.
    pub variogram_fit: HurstFit,
    /// The power spectrum's fit.
    pub spectrum_fit: HurstFit,
    /// H along x (east-west) and along z (north-south), over the variogram's range.
    pub hurst_axes: [f64; 2],
    /// Anisotropy: the square root of the semivariance along x over that along z at the
    /// middle of the range (1 for a surface as rough both ways).
    pub anisotropy: f64,
    /// The variogram: (lag in metres, semivariance along x, along z, both).
    pub variogram: Vec<[f64; 4]>,
    /// The spectrum: (wavelength in metres, mean profile power).
    pub spectrum: Vec<[f64; 2]>,
    /// The heights' spread.
    pub heights: HeightDistribution,
}

/// The fit as H over a range, from a line through (ln scale, ln value) points.
fn hurst_fit(
    line: Line,
    points: &[(f64, f64)],
    hurst: impl Fn(f64) -> f64,
    wavelengths: bool,
) -> HurstFit {
    let (a, b) = (points[line.from].0.exp(), points[line.to].0.exp());
    HurstFit {
        hurst: hurst(line.slope),
        scale_range: if wavelengths {
            [b.min(a), a.max(b)]
        } else {
            [a, b]
        },
        worst_residual: line.worst,
        line: [line.slope, line.intercept],
    }
}

impl FractalAnalysis {
    /// Measures `map`.
    pub fn of(map: &Heightmap) -> FractalAnalysis {
        let s = f64::from(map.spacing());
        Self::of_square(map.size(), map.heights(), [s, s])
    }

    /// Measures an elevation model as it was read: the largest square of its own samples
    /// about its middle, so nothing resampled or padded enters the statistics. Lags and
    /// wavelengths are in metres of the geometric mean of its two spacings (a fit's H does
    /// not depend on them).
    pub fn of_model(model: &ElevationModel) -> FractalAnalysis {
        let side = model.width.min(model.height);
        let (x0, z0) = ((model.width - side) / 2, (model.height - side) / 2);
        let mut heights = Vec::with_capacity(side * side);
        for z in z0..z0 + side {
            heights.extend_from_slice(
                &model.heights[z * model.width + x0..z * model.width + x0 + side],
            );
        }
        let [dx, dz] = model.spacing.map(f64::from);
        Self::of_square(side, &heights, [dx, dz])
    }

    /// H fitted from this surface's variogram (both axes) over the lags within `range`
    /// metres: to compare a surface with another over the other's scale range. `None` for
    /// fewer than two lags in it.
    pub fn hurst_over(&self, range: [f64; 2]) -> Option<f64> {
        let points: Vec<(f64, f64)> = self
            .variogram
            .iter()
            .filter(|v| v[0] >= range[0] * 0.999 && v[0] <= range[1] * 1.001 && v[3] > 0.0)
            .map(|v| (v[0].ln(), v[3].ln()))
            .collect();
        (points.len() >= 2).then(|| fit::line(&points, 0, points.len() - 1).slope / 2.0)
    }

    /// Measures a square grid of `side` samples with the spacings along x and z.
    fn of_square(side: usize, h: &[f32], [dx, dz]: [f64; 2]) -> FractalAnalysis {
        let spacing = (dx * dz).sqrt();
        let lags = variogram::lags(side);
        let variogram: Vec<[f64; 4]> = lags
            .iter()
            .map(|&lag| {
                let (x, z) = variogram::semivariance(side, h, lag);
                [lag as f64 * spacing, x, z, 0.5 * (x + z)]
            })
            .collect();
        let log = |column: usize| -> Vec<(f64, f64)> {
            variogram
                .iter()
                .map(|v| (v[0].ln(), v[column].max(1e-30).ln()))
                .collect()
        };
        let both = log(3);
        // The fit looks for its straight run between the lags where the terrain itself shows:
        // from 2 samples (a model's first lag shows its sensor and resampling, smooth, H near
        // 1) to a tenth of the side (at least 12 samples; beyond it relief the size of the map
        // and regional slope bend the curve). Over the whole range the run of lags 1 to 6 won
        // on an SRTM tile (H 0.89 against an independent variogram fit's 0.59); in this window
        // the two agree within 0.06 on five real models, and surfaces made at a known H are
        // still fitted within 0.05 of it (`tools/variogram_fit.py`, docs/real-land.md). Grids
        // too small for the window keep the whole range.
        let window = straight_run_window(&lags, side);
        let (lo, hi) = if window.len() >= MIN_POINTS {
            (window.start, window.end)
        } else {
            (0, both.len())
        };
        let variogram_line = widest_straight_run(&both[lo..hi], MIN_POINTS, TOLERANCE, |s| {
            s > 0.02 && s < 2.2
        })
        .map(|l| Line {
            from: l.from + lo,
            to: l.to + lo,
            ..l
        })
        .unwrap_or(Line {
            slope: 0.0,
            intercept: 0.0,
            worst: 0.0,
            from: 0,
            to: 0,
        });
        let variogram_fit = hurst_fit(variogram_line, &both, |s| s / 2.0, false);
        // Each axis over the same range.
        let axis = |column: usize| {
            let points = log(column);
            fit::line(
                &points,
                variogram_line.from,
                variogram_line
                    .to
                    .max(variogram_line.from + 1)
                    .min(points.len() - 1),
            )
            .slope
                / 2.0
        };
        let hurst_axes = [axis(1), axis(2)];
        let middle = &variogram[(variogram_line.from + variogram_line.to) / 2];
        let anisotropy = if middle[2] > 0.0 {
            (middle[1] / middle[2]).sqrt()
        } else {
            1.0
        };

        let spectrum: Vec<[f64; 2]> = spectrum::profile_spectrum(side, h)
            .into_iter()
            .map(|(k, p)| [spacing / k, p])
            .collect();
        // In frequency, so the slope is -(2H + 1).
        let points: Vec<(f64, f64)> = spectrum
            .iter()
            .map(|s| ((spacing / s[0]).ln(), s[1].max(1e-30).ln()))
            .collect();
        let spectrum_line = widest_straight_run(&points, MIN_POINTS, 2.0 * TOLERANCE, |s| {
            s < -1.04 && s > -3.4
        })
        .unwrap_or(Line {
            slope: -1.0,
            intercept: 0.0,
            worst: 0.0,
            from: 0,
            to: 0,
        });
        let mut spectrum_fit = hurst_fit(spectrum_line, &points, |s| (-s - 1.0) / 2.0, true);
        // The range as wavelengths in metres.
        let (k0, k1) = (
            points[spectrum_line.from].0.exp(),
            points[spectrum_line.to].0.exp(),
        );
        spectrum_fit.scale_range = [spacing / k1, spacing / k0];
        let hurst = variogram_fit.hurst;
        FractalAnalysis {
            hurst,
            dimension: 3.0 - hurst,
            variogram_fit,
            spectrum_fit,
            hurst_axes,
            anisotropy,
            variogram,
            spectrum,
            heights: HeightDistribution::of_heights(h),
        }
    }
}

/// The indices of `lags` (in samples, rising) where the variogram's straight run is looked
/// for on a grid of `side` samples: from 2 samples to a tenth of the side, at least 12 and
/// at most a quarter of the side.
fn straight_run_window(lags: &[usize], side: usize) -> std::ops::Range<usize> {
    let longest = (side / 4).min((side / 10).max(12));
    let start = lags.iter().position(|&l| l >= 2).unwrap_or(lags.len());
    let end = lags
        .iter()
        .rposition(|&l| l <= longest)
        .map_or(start, |i| i + 1);
    start..end.max(start)
}
