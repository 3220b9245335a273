//! Terrain made to match a measured one (the Garden of Eden thesis, 7.5): synthesis from the
//! features [`FractalAnalysis`] extracts, and fractal interpolation of a coarse model.
//!
//! - [`synthesize_like`]: spectral synthesis with the measured H, its wavelengths bounded by
//!   the measured scale range, then the heights mapped onto the measured distribution (its
//!   percentiles), so the variogram's slope, the scale range and the spread of heights follow
//!   the real land. On the bundled real models it matches H over their scale ranges better
//!   than diamond-square with the same H (mean error 0.07 against 0.09; `examples/real_land.rs`).
//! - [`refine`]: a coarse model made finer by midpoint displacement whose offsets follow the
//!   model's own variogram, extrapolated below its spacing with its H; every measured height
//!   stays where it was, so a 90 m model becomes a 5 m one that passes through its samples.

use sylva_base::hash::{hash_cell, unit_f32};

use crate::analysis::{FractalAnalysis, HeightDistribution};
use crate::error::{TerrainError, check};
use crate::heightmap::Heightmap;
use crate::spectral::SpectralSynthesis;

/// A terrain of `size` samples at `spacing` metres statistically like the one `like`
/// measured: its H, its scale range's ends (wavelengths past sixteen times the top are left
/// out, on maps that large; below half the foot they fade), its height distribution. A pure function of its inputs and `seed`.
///
/// ```
/// use sylva_terrain::analysis::FractalAnalysis;
/// use sylva_terrain::{DiamondSquare, synthesize_like};
///
/// let real = DiamondSquare::new(257).with_roughness(0.6).with_seed(2).generate()?;
/// let measured = FractalAnalysis::of(&real);
/// let made = synthesize_like(&measured, 257, real.spacing(), 9)?;
/// let again = FractalAnalysis::of(&made);
/// assert!((again.hurst - measured.hurst).abs() < 0.1);
/// assert!((again.heights.std_dev - measured.heights.std_dev).abs() < 0.1 * measured.heights.std_dev);
/// # Ok::<(), sylva_terrain::TerrainError>(())
/// ```
pub fn synthesize_like(
    like: &FractalAnalysis,
    size: usize,
    spacing: f32,
    seed: u64,
) -> Result<Heightmap, TerrainError> {
    let hurst = like.hurst.clamp(0.0, 1.0) as f32;
    // Beyond the range's top the measured surface grows rougher ever more slowly; far beyond
    // it (sixteen times, found by comparing with real models) its hills end.
    let side = (size.saturating_sub(1)) as f32 * spacing;
    let top = like.variogram_fit.scale_range[1] as f32;
    let longest = if top * 16.0 < side { 16.0 * top } else { 0.0 };
    // Below the range's foot the measured surface is smoother than a fractal: wavelengths
    // under half of it fade (the roll-off leaves the range itself whole).
    let foot = 0.5 * like.variogram_fit.scale_range[0] as f32;
    let shortest = if foot > 2.0 * spacing { foot } else { 0.0 };
    let mut map = SpectralSynthesis::new(size)
        .with_spacing(spacing)
        .with_hurst(hurst)
        .with_seed(seed)
        .with_amplitude(1.0)
        .with_longest_wavelength(longest)
        .with_shortest_wavelength(shortest)
        .generate()?;
    match_distribution(&mut map, &like.heights);
    Ok(map)
}

/// Maps `map`'s heights onto `target`'s distribution by rank: the lowest height becomes the
/// target's minimum, the median its median, and so on through its percentiles (linear
/// between them), so the result has the target's spread and skew with `map`'s shapes.
pub fn match_distribution(map: &mut Heightmap, target: &HeightDistribution) {
    let knots: Vec<(f32, f32)> = std::iter::once((0.0, target.min))
        .chain(
            crate::analysis::PERCENTILES
                .iter()
                .copied()
                .zip(target.percentiles),
        )
        .chain(std::iter::once((100.0, target.max)))
        .collect();
    let quantile = |p: f32| {
        let k = knots
            .partition_point(|&(q, _)| q <= p)
            .clamp(1, knots.len() - 1);
        let ((p0, h0), (p1, h1)) = (knots[k - 1], knots[k]);
        if p1 > p0 {
            h0 + (h1 - h0) * (p - p0) / (p1 - p0)
        } else {
            h0
        }
    };
    let h = map.heights_mut();
    let mut order: Vec<usize> = (0..h.len()).collect();
    order.sort_by(|&a, &b| h[a].total_cmp(&h[b]).then(a.cmp(&b)));
    let last = (order.len().max(2) - 1) as f32;
    for (rank, &i) in order.iter().enumerate() {
        h[i] = quantile(100.0 * rank as f32 / last);
    }
}

/// Refines `coarse` by `levels` halvings of its spacing (a 2^levels-times finer grid) with
/// fractal detail: diamond-square steps from the coarse samples, each new point its parents'
/// mean plus a Gaussian offset whose spread follows `stats`' variogram line at that distance
/// (`stats` measured on `coarse` itself, normally). Every coarse sample keeps its height. At
/// most 8193 samples a side.
///
/// ```
/// use sylva_terrain::analysis::FractalAnalysis;
/// use sylva_terrain::{DiamondSquare, refine};
///
/// let coarse = DiamondSquare::new(65).with_spacing(90.0).with_seed(4).generate()?;
/// let fine = refine(&coarse, 4, &FractalAnalysis::of(&coarse), 1)?;
/// assert_eq!((fine.size(), fine.spacing()), (1025, 90.0 / 16.0));
/// assert_eq!(fine.get(16 * 10, 16 * 7), coarse.get(10, 7)); // measured heights stay
/// # Ok::<(), sylva_terrain::TerrainError>(())
/// ```
pub fn refine(
    coarse: &Heightmap,
    levels: u32,
    stats: &FractalAnalysis,
    seed: u64,
) -> Result<Heightmap, TerrainError> {
    check(
        "levels",
        f64::from(levels),
        (1..=8).contains(&levels),
        "1 to 8",
    )?;
    let stride = 1usize << levels;
    let size = (coarse.size() - 1) * stride + 1;
    if size > 8193 {
        return Err(TerrainError::TooLarge {
            what: format!("{size} samples a side after refining"),
            limit: "8193 a side".into(),
        });
    }
    let spacing = coarse.spacing() / stride as f32;
    let mut h = vec![0.0f32; size * size];
    for z in 0..coarse.size() {
        for x in 0..coarse.size() {
            h[z * stride * size + x * stride] = coarse.get(x, z);
        }
    }
    // The variogram line gamma(d) = exp(intercept) d^slope, its H held below the measured
    // lags (a fractal goes on); the offset of a midpoint between parents d apart has variance
    // gamma(d) (1 - 2^(2H - 2)) / 2 for fractional Brownian motion.
    let [slope, intercept] = stats.variogram_fit.line;
    let hurst = (slope / 2.0).clamp(0.05, 1.0);
    let spread = |d: f64| {
        let gamma = (intercept + 2.0 * hurst * d.ln()).exp();
        (gamma * (1.0 - 2f64.powf(2.0 * hurst - 2.0)) / 2.0)
            .max(0.0)
            .sqrt()
    };
    let gaussian = |x: usize, z: usize, salt: u64| {
        let r = hash_cell(seed, x as i64, z as i64, salt);
        let (u1, u2) = (
            f64::from(unit_f32(r)).max(1e-12),
            f64::from(unit_f32(r.rotate_left(32))),
        );
        (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
    };
    let mut step = stride;
    while step > 1 {
        let half = step / 2;
        // Diamond: square centres from their four corners, which are step * sqrt(2) apart.
        let s = spread(step as f64 * std::f64::consts::SQRT_2 * f64::from(spacing));
        for z in (half..size).step_by(step) {
            for x in (half..size).step_by(step) {
                let m = 0.25
                    * (h[(z - half) * size + x - half]
                        + h[(z - half) * size + x + half]
                        + h[(z + half) * size + x - half]
                        + h[(z + half) * size + x + half]);
                h[z * size + x] = m + (s * gaussian(x, z, 1)) as f32;
            }
        }
        // Square: edge midpoints from their two to four neighbours, step apart.
        let s = spread(step as f64 * f64::from(spacing));
        for z in (0..size).step_by(half) {
            let start = if (z / half).is_multiple_of(2) {
                half
            } else {
                0
            };
            for x in (start..size).step_by(step) {
                let mut sum = 0.0f32;
                let mut n = 0.0f32;
                for (dx, dz) in [(0isize, -1isize), (0, 1), (-1, 0), (1, 0)] {
                    let (nx, nz) = (
                        x as isize + dx * half as isize,
                        z as isize + dz * half as isize,
                    );
                    if nx >= 0 && nz >= 0 && (nx as usize) < size && (nz as usize) < size {
                        sum += h[nz as usize * size + nx as usize];
                        n += 1.0;
                    }
                }
                h[z * size + x] = sum / n + (s * gaussian(x, z, 2)) as f32;
            }
        }
        step = half;
    }
    Heightmap::from_heights(size, spacing, h)
}

/// A grey hillshade of `map`, one byte a sample, row-major: Lambert shading under a sun from
/// the north-west, 45 degrees up, as maps draw relief.
pub fn hillshade(map: &Heightmap) -> Vec<u8> {
    let n = map.size();
    let s = map.spacing();
    let sun = glam::Vec3::new(-1.0, std::f32::consts::SQRT_2, -1.0).normalize();
    let at = |x: usize, z: usize| map.get(x.min(n - 1), z.min(n - 1));
    let mut out = Vec::with_capacity(n * n);
    for z in 0..n {
        for x in 0..n {
            let (x0, x1) = (x.saturating_sub(1), (x + 1).min(n - 1));
            let (z0, z1) = (z.saturating_sub(1), (z + 1).min(n - 1));
            let dx = (at(x1, z) - at(x0, z)) / ((x1 - x0).max(1) as f32 * s);
            let dz = (at(x, z1) - at(x, z0)) / ((z1 - z0).max(1) as f32 * s);
            let normal = glam::Vec3::new(-dx, 1.0, -dz).normalize();
            out.push((normal.dot(sun).clamp(0.0, 1.0) * 255.0) as u8);
        }
    }
    out
}
