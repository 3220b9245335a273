//! The power spectrum of the profiles: every row and column detrended, Hann-windowed and
//! Fourier transformed (rustfft), the powers averaged over profiles and gathered into bins
//! growing by about 1.4 in frequency. A profile of a fractional Brownian surface has
//! P(k) ~ k^-(2H + 1).

use rustfft::FftPlanner;
use rustfft::num_complex::Complex;

/// (frequency in cycles per sample, mean power) for each bin, lowest first, of a square grid
/// of `n` samples a side.
pub(crate) fn profile_spectrum(n: usize, h: &[f32]) -> Vec<(f64, f64)> {
    // The transform's length: the largest power of two in a side.
    let len = 1usize << (usize::BITS - 1 - n.leading_zeros());
    let fft = FftPlanner::<f64>::new().plan_fft_forward(len);
    let window: Vec<f64> = (0..len)
        .map(|i| 0.5 - 0.5 * (2.0 * std::f64::consts::PI * i as f64 / (len - 1) as f64).cos())
        .collect();
    let mut power = vec![0.0f64; len / 2 + 1];
    let mut buffer = vec![Complex::new(0.0, 0.0); len];
    let mut profiles = 0usize;
    for axis in 0..2 {
        for line in 0..n {
            let at = |i: usize| {
                f64::from(if axis == 0 {
                    h[line * n + i]
                } else {
                    h[i * n + line]
                })
            };
            // The line through the ends is taken out, so the profile's trend does not leak
            // into every frequency.
            let (a, b) = (at(0), at(len - 1));
            for (i, c) in buffer.iter_mut().enumerate() {
                let trend = a + (b - a) * i as f64 / (len - 1) as f64;
                *c = Complex::new((at(i) - trend) * window[i], 0.0);
            }
            fft.process(&mut buffer);
            for (k, p) in power.iter_mut().enumerate() {
                *p += buffer[k].norm_sqr();
            }
            profiles += 1;
        }
    }
    // Log-spaced bins from frequency 1 to len / 2.
    let mut bins = Vec::new();
    let mut k = 1usize;
    while k <= len / 2 {
        let end = ((k as f64 * std::f64::consts::SQRT_2).round() as usize)
            .max(k + 1)
            .min(len / 2 + 1);
        let mean = power[k..end].iter().sum::<f64>() / (end - k) as f64 / profiles as f64;
        let centre = ((k * (end - 1)) as f64).sqrt();
        bins.push((centre / len as f64, mean));
        k = end;
    }
    bins
}
