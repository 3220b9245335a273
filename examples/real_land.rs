//! Real land: each bundled real elevation model measured (its Hurst exponent and the scale
//! range of the fit), terrain synthesized to match it two ways (spectral synthesis and
//! diamond-square, each with the measured H and heights), and the model refined fourfold from
//! a quarter of its samples by fractal interpolation; a table of the figures, and a picture
//! per model: hillshades of the real, synthesized and interpolated terrain side by side.
//!
//! ```text
//! cargo run --release --example real_land [OUT_DIR]
//! ```

use std::path::Path;

use sylva::terrain::analysis::FractalAnalysis;
use sylva::terrain::dem::{ElevationModel, ReadOptions};
use sylva::terrain::{
    DiamondSquare, Heightmap, hillshade, match_distribution, refine, synthesize_like,
};

/// The models, in `terrain/tests/data/dems` (sources and licences in its README).
const MODELS: [&str; 3] = [
    "front_range_srtmgl3.asc",
    "west_bijou_escarpment.asc",
    "dem-hills.tiff",
];

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "real_land".into());
    std::fs::create_dir_all(&out)?;
    let dems = Path::new(env!("CARGO_MANIFEST_DIR")).join("terrain/tests/data/dems");
    println!(
        "| model | samples | H (variogram) | scale range (m) | H (spectrum) | height sd (m) | spectral synthesis: H over the real range, its own range (m), height sd | diamond-square: the same | interpolated 4x: H over the real range, rms error (m), samples kept |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    for name in MODELS {
        let model = ElevationModel::read(dems.join(name), &ReadOptions::default())?;
        let real = FractalAnalysis::of_model(&model);
        // The model's own land, square, nothing padded.
        let map = model.square_heightmap()?;
        let (size, spacing) = (map.size(), map.spacing());
        let spectral = synthesize_like(&real, size, spacing, 1)?;
        let mut ds = DiamondSquare::new(size)
            .with_spacing(spacing)
            .with_roughness(real.hurst.clamp(0.0, 1.0) as f32)
            .with_seed(1)
            .generate()?;
        match_distribution(&mut ds, &real.heights);
        // A quarter of the samples each way, refined back by fractal interpolation.
        let quarter = (size - 1) / 4 + 1;
        let coarse_heights: Vec<f32> = (0..quarter * quarter)
            .map(|i| map.get((i % quarter) * 4, (i / quarter) * 4))
            .collect();
        let coarse = Heightmap::from_heights(quarter, spacing * 4.0, coarse_heights)?;
        let refined = refine(&coarse, 2, &FractalAnalysis::of(&coarse), 1)?;
        let rms = (map
            .heights()
            .iter()
            .zip(refined.heights())
            .map(|(a, b)| f64::from(a - b).powi(2))
            .sum::<f64>()
            / map.heights().len() as f64)
            .sqrt();
        let kept = (0..quarter * quarter)
            .filter(|&i| {
                refined.get((i % quarter) * 4, (i / quarter) * 4)
                    == coarse.get(i % quarter, i / quarter)
            })
            .count();
        let (s, d, r) = (
            FractalAnalysis::of(&spectral),
            FractalAnalysis::of(&ds),
            FractalAnalysis::of(&refined),
        );
        let range = |a: &FractalAnalysis| {
            format!(
                "{:.0}-{:.0}",
                a.variogram_fit.scale_range[0], a.variogram_fit.scale_range[1]
            )
        };
        // Each made terrain's H over the real one's scale range.
        let over = |a: &FractalAnalysis| {
            a.hurst_over(real.variogram_fit.scale_range)
                .unwrap_or(f64::NAN)
        };
        println!(
            "| {name} | {} x {} | {:.3} | {} | {:.3} | {:.1} | {:.3}, {}, {:.1} | {:.3}, {}, {:.1} | {:.3}, {rms:.2}, {kept} of {} |",
            model.width,
            model.height,
            real.hurst,
            range(&real),
            real.spectrum_fit.hurst,
            real.heights.std_dev,
            over(&s),
            range(&s),
            s.heights.std_dev,
            over(&d),
            range(&d),
            d.heights.std_dev,
            over(&r),
            quarter * quarter
        );
        assert_eq!(
            kept,
            quarter * quarter,
            "fractal interpolation must keep every measured height"
        );
        let stem = name.split('.').next().unwrap_or(name);
        write_sheet(
            &Path::new(&out).join(format!("{stem}.png")),
            &[&map, &spectral, &ds, &refined],
        )?;
    }
    println!(
        "\nwrote {out}/*.png: real, spectral synthesis, diamond-square, interpolated from a quarter of the samples"
    );
    Ok(())
}

/// Hillshades of `maps` side by side, 8 pixels of white between them.
fn write_sheet(path: &Path, maps: &[&Heightmap]) -> Result<(), Box<dyn std::error::Error>> {
    let n = maps[0].size();
    let gap = 8;
    let width = maps.len() * n + (maps.len() - 1) * gap;
    let mut pixels = vec![255u8; width * n];
    for (k, map) in maps.iter().enumerate() {
        let shade = hillshade(map);
        for z in 0..n {
            let row = z * width + k * (n + gap);
            pixels[row..row + n].copy_from_slice(&shade[z * n..(z + 1) * n]);
        }
    }
    let file = std::io::BufWriter::new(std::fs::File::create(path)?);
    let mut encoder = png::Encoder::new(file, width as u32, n as u32);
    encoder.set_color(png::ColorType::Grayscale);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.write_header()?.write_image_data(&pixels)?;
    Ok(())
}
