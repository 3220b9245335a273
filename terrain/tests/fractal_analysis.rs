//! Feature extraction on surfaces of known roughness: the Hurst exponent fitted from the
//! variogram is within 0.05 of the H each was made with, for spectral synthesis and
//! diamond-square at H = 0.3, 0.5 and 0.8 (the mean of four seeds at 513 samples), and the
//! spectrum's fit agrees.

use sylva_terrain::analysis::FractalAnalysis;
use sylva_terrain::{DiamondSquare, Heightmap, SpectralSynthesis};

/// The mean variogram and spectrum fits of `make(h, seed)` over four seeds, for each H.
fn fits(kind: &str, make: impl Fn(f32, u64) -> Heightmap) -> Vec<(f32, f64, f64)> {
    [0.3f32, 0.5, 0.8]
        .into_iter()
        .map(|h| {
            let all: Vec<FractalAnalysis> = (0..4u64)
                .map(|seed| FractalAnalysis::of(&make(h, seed)))
                .collect();
            let mean = |f: &dyn Fn(&FractalAnalysis) -> f64| {
                all.iter().map(f).sum::<f64>() / all.len() as f64
            };
            let (v, s) = (mean(&|a| a.hurst), mean(&|a| a.spectrum_fit.hurst));
            println!(
                "{kind} H {h}: variogram {v:.3}, spectrum {s:.3}, ranges {:?} {:?}",
                all[0].variogram_fit.scale_range, all[0].spectrum_fit.scale_range
            );
            (h, v, s)
        })
        .collect()
}

#[test]
fn spectral_synthesis_at_known_h() {
    for (h, v, s) in fits("spectral", |h, seed| {
        SpectralSynthesis::new(513)
            .with_hurst(h)
            .with_seed(seed)
            .generate()
            .unwrap()
    }) {
        assert!(
            (v - f64::from(h)).abs() <= 0.05,
            "spectral H {h}: variogram fit {v:.3}"
        );
        assert!(
            (s - f64::from(h)).abs() <= 0.1,
            "spectral H {h}: spectrum fit {s:.3}"
        );
    }
}

#[test]
fn diamond_square_at_known_h() {
    for (h, v, _) in fits("diamond-square", |h, seed| {
        DiamondSquare::new(513)
            .with_roughness(h)
            .with_seed(seed)
            .generate()
            .unwrap()
    }) {
        assert!(
            (v - f64::from(h)).abs() <= 0.05,
            "diamond-square H {h}: variogram fit {v:.3}"
        );
    }
}
