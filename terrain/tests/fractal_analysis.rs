//! Feature extraction on surfaces of known roughness: the Hurst exponent fitted from the
//! variogram is within 0.05 of the H each was made with, for spectral synthesis and
//! diamond-square at H = 0.3, 0.5 and 0.8 (the mean of four seeds at 513 samples), and the
//! spectrum's fit agrees.

use sylva_terrain::analysis::FractalAnalysis;
use sylva_terrain::{DiamondSquare, SpectralSynthesis};

fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len() as f64
}

#[test]
fn spectral_synthesis_at_known_h() {
    for h in [0.3f32, 0.5, 0.8] {
        let fits: Vec<FractalAnalysis> = (0..4u64)
            .map(|seed| {
                FractalAnalysis::of(
                    &SpectralSynthesis::new(513)
                        .with_hurst(h)
                        .with_seed(seed)
                        .generate()
                        .unwrap(),
                )
            })
            .collect();
        let v = mean(&fits.iter().map(|a| a.hurst).collect::<Vec<_>>());
        let s = mean(
            &fits
                .iter()
                .map(|a| a.spectrum_fit.hurst)
                .collect::<Vec<_>>(),
        );
        println!(
            "spectral H {h}: variogram {v:.3}, spectrum {s:.3}, ranges {:?} {:?}",
            fits[0].variogram_fit.scale_range, fits[0].spectrum_fit.scale_range
        );
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
    for h in [0.3f32, 0.5, 0.8] {
        let fits: Vec<FractalAnalysis> = (0..4u64)
            .map(|seed| {
                FractalAnalysis::of(
                    &DiamondSquare::new(513)
                        .with_roughness(h)
                        .with_seed(seed)
                        .generate()
                        .unwrap(),
                )
            })
            .collect();
        let v = mean(&fits.iter().map(|a| a.hurst).collect::<Vec<_>>());
        let s = mean(
            &fits
                .iter()
                .map(|a| a.spectrum_fit.hurst)
                .collect::<Vec<_>>(),
        );
        println!(
            "diamond-square H {h}: variogram {v:.3}, spectrum {s:.3}, ranges {:?} {:?}",
            fits[0].variogram_fit.scale_range, fits[0].spectrum_fit.scale_range
        );
        assert!(
            (v - f64::from(h)).abs() <= 0.05,
            "diamond-square H {h}: variogram fit {v:.3}"
        );
    }
}
