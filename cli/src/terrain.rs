//! `sylva terrain`: a diamond-square heightmap, smoothed and optionally eroded, written as a
//! 16-bit PNG (and optionally RAW); or, with `--analyse`, a real elevation model's fractal
//! character measured (JSON and a variogram plot).

use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use sylva::terrain::{DiamondSquare, EdgeMode, Heightmap, HydraulicErosion, ThermalErosion};

use crate::Failure;
use crate::forest::write_heightmap;
use crate::progress::{ms, phase};

/// `sylva terrain`'s flags.
#[derive(Debug, Args)]
pub(crate) struct TerrainArgs {
    /// Samples per side: 2^n + 1 (257, 513, 1025, 4097 ...).
    #[arg(long, value_name = "N", default_value_t = 1025)]
    size: usize,
    /// Roughness H: larger is smoother.
    #[arg(long, value_name = "H", default_value_t = 0.8)]
    roughness: f32,
    /// Seed.
    #[arg(long, default_value_t = 7)]
    seed: u64,
    /// Gaussian smoothing, sigma in samples.
    #[arg(long, value_name = "SIGMA", default_value_t = 2.0)]
    smooth: f32,
    /// Metres between samples (default 1; with --analyse, overrides the file's).
    #[arg(long, value_name = "D")]
    spacing: Option<f32>,
    /// Measure an elevation model instead (GeoTIFF, .hgt, .asc, PNG16): its Hurst exponent
    /// from the variogram and the power spectrum, the scale range of the fit, anisotropy and
    /// the height distribution, as analysis.json and variogram.png in --report.
    #[arg(long, value_name = "MODEL")]
    analyse: Option<PathBuf>,
    /// The folder --analyse writes to.
    #[arg(long, value_name = "DIR", default_value = "analysis")]
    report: PathBuf,
    /// Make terrain like an elevation model instead: spectral synthesis with its measured H
    /// and scale range, its heights' distribution, --size samples at its own spacing (or
    /// --spacing), written to --out.
    #[arg(long, value_name = "MODEL", conflicts_with_all = ["analyse", "refine"])]
    like: Option<PathBuf>,
    /// Refine an elevation model by fractal interpolation instead: --levels halvings of its
    /// spacing, every measured height kept, written to --out.
    #[arg(long, value_name = "MODEL", conflicts_with = "analyse")]
    refine: Option<PathBuf>,
    /// Halvings of the spacing for --refine (1 to 8; 4 makes a 90 m model a 5.6 m one).
    #[arg(long, value_name = "N", default_value_t = 2)]
    levels: u32,
    /// Height amplitude in metres (default: the generator's).
    #[arg(long, value_name = "A")]
    amplitude: Option<f32>,
    /// Apply thermal and hydraulic erosion afterwards (also to --like and --refine terrain).
    #[arg(long)]
    erode: bool,
    /// Seamless: the map tiles with itself.
    #[arg(long)]
    wrap: bool,
    /// The PNG file to write.
    #[arg(long, value_name = "FILE", default_value = "height.png")]
    out: PathBuf,
    /// Also write a RAW of little-endian 16-bit samples beside it.
    #[arg(long)]
    raw: bool,
    /// Print nothing but errors.
    #[arg(long, short)]
    quiet: bool,
}

pub(crate) fn run(args: TerrainArgs) -> Result<(), Failure> {
    if let Some(model) = &args.analyse {
        return analyse(model, &args);
    }
    if let Some(model) = &args.like {
        return like(model, &args);
    }
    if let Some(model) = &args.refine {
        return refine(model, &args);
    }
    let start = Instant::now();
    let mut ds = DiamondSquare::new(args.size)
        .with_seed(args.seed)
        .with_roughness(args.roughness)
        .with_spacing(args.spacing.unwrap_or(1.0))
        .with_wrap(args.wrap);
    if let Some(a) = args.amplitude {
        ds = ds.with_amplitude(a);
    }
    let mut map = ds.generate()?;
    let generated = start.elapsed();
    let edges = if args.wrap {
        EdgeMode::Wrap
    } else {
        EdgeMode::Mirror
    };
    map.smooth(args.smooth, edges)?;
    let smoothed = start.elapsed();
    erode(&mut map, &args)?;
    let total = start.elapsed();
    write_heightmap(&map, &args.out)?;
    if args.raw {
        let path = args.out.with_extension("raw");
        let (bytes, range) = map.to_raw16();
        sylva::base::file::write(&path, |w| std::io::Write::write_all(w, &bytes))?;
        if !args.quiet {
            println!(
                "wrote {} (16-bit little-endian; 0 = {} and 65535 = {})",
                path.display(),
                range.min,
                range.max
            );
        }
    }
    if args.quiet {
        return Ok(());
    }
    let s = map.stats();
    println!(
        "wrote {} ({} x {}): min {:.3}  max {:.3}  mean {:.3}",
        args.out.display(),
        args.size,
        args.size,
        s.min,
        s.max,
        s.mean
    );
    println!(
        "time: diamond-square {:.1} ms, smoothing {:.1} ms, total {:.1} ms",
        ms(generated),
        ms(smoothed - generated),
        ms(total)
    );
    Ok(())
}

/// Reads `--analyse`, `--like` or `--refine`'s model, `--spacing` overriding the file's.
fn read_model(
    path: &std::path::Path,
    args: &TerrainArgs,
) -> Result<sylva::terrain::dem::ElevationModel, Failure> {
    use sylva::terrain::dem::{ElevationModel, ReadOptions};
    let options = ReadOptions {
        spacing: args.spacing,
        ..ReadOptions::default()
    };
    ElevationModel::read(path, &options)
        .map_err(|e| Failure::job(format!("{}: {e}", path.display())))
}

/// With `--erode`, thermal then hydraulic erosion (a droplet per four samples) on `map`,
/// whichever way it was made.
fn erode(map: &mut Heightmap, args: &TerrainArgs) -> Result<(), Failure> {
    if args.erode {
        let droplets = (map.size() * map.size() / 4) as u32;
        let (eroded, _) = phase(args.quiet, "eroding", || {
            ThermalErosion::default().apply(map)?;
            HydraulicErosion::new(droplets, args.seed).apply(map)
        });
        eroded?;
    }
    Ok(())
}

/// `--like`: terrain statistically like a model.
fn like(path: &std::path::Path, args: &TerrainArgs) -> Result<(), Failure> {
    use sylva::terrain::analysis::FractalAnalysis;
    let model = read_model(path, args)?;
    let measured = FractalAnalysis::of_model(&model);
    let spacing = args
        .spacing
        .unwrap_or(model.spacing[0].min(model.spacing[1]));
    let mut map = sylva::terrain::synthesize_like(&measured, args.size, spacing, args.seed)?;
    erode(&mut map, args)?;
    write_heightmap(&map, &args.out)?;
    if !args.quiet {
        let made = FractalAnalysis::of(&map);
        let [lo, hi] = measured.variogram_fit.scale_range;
        println!(
            "wrote {}: {} x {} at {spacing:.2} m like {} (H {:.3} from {lo:.0} to {hi:.0} m); made: H {:.3} over that range, heights {:.0} to {:.0} m",
            args.out.display(),
            map.size(),
            map.size(),
            path.display(),
            measured.hurst,
            made.hurst_over([lo, hi]).unwrap_or(f64::NAN),
            made.heights.min,
            made.heights.max
        );
    }
    Ok(())
}

/// `--refine`: a model made finer by fractal interpolation.
fn refine(path: &std::path::Path, args: &TerrainArgs) -> Result<(), Failure> {
    use sylva::terrain::analysis::FractalAnalysis;
    let model = read_model(path, args)?;
    let (coarse, _) = model.to_heightmap()?;
    let mut fine = sylva::terrain::refine(
        &coarse,
        args.levels,
        &FractalAnalysis::of(&coarse),
        args.seed,
    )?;
    erode(&mut fine, args)?;
    write_heightmap(&fine, &args.out)?;
    if !args.quiet {
        let kept = if args.erode {
            "every sample kept, then eroded"
        } else {
            "every sample kept"
        };
        println!(
            "wrote {}: {} x {} at {:.2} m, refined from {} x {} at {:.2} m ({}), {kept}",
            args.out.display(),
            fine.size(),
            fine.size(),
            fine.spacing(),
            coarse.size(),
            coarse.size(),
            coarse.spacing(),
            path.display()
        );
    }
    Ok(())
}

/// `--analyse`: measures a model and writes `analysis.json` and `variogram.png`.
fn analyse(path: &std::path::Path, args: &TerrainArgs) -> Result<(), Failure> {
    use sylva::terrain::analysis::FractalAnalysis;
    let name = path.display().to_string();
    let model = read_model(path, args)?;
    let a = FractalAnalysis::of_model(&model);
    std::fs::create_dir_all(&args.report)
        .map_err(sylva::base::file::FileError::at(&args.report))?;
    let fit = |f: &sylva::terrain::analysis::HurstFit| serde_json::json!({"hurst": f.hurst, "scale_range_m": f.scale_range, "worst_residual": f.worst_residual, "line": f.line});
    let h = &a.heights;
    let json = serde_json::json!({
        "model": name,
        "samples": [model.width, model.height],
        "spacing_m": model.spacing,
        "nodata_filled": model.nodata,
        "hurst": a.hurst,
        "dimension": a.dimension,
        "variogram_fit": fit(&a.variogram_fit),
        "spectrum_fit": fit(&a.spectrum_fit),
        "hurst_x_z": a.hurst_axes,
        "anisotropy": a.anisotropy,
        "heights": {
            "min": h.min, "max": h.max, "mean": h.mean, "std_dev": h.std_dev,
            "skewness": h.skewness, "kurtosis": h.kurtosis,
            "percentiles": sylva::terrain::analysis::PERCENTILES.iter().zip(h.percentiles).map(|(p, v)| serde_json::json!([p, v])).collect::<Vec<_>>(),
        },
        "variogram": a.variogram,
        "spectrum": a.spectrum,
    });
    let text = serde_json::to_string_pretty(&json).map_err(|e| Failure::job(e.to_string()))?;
    let out = args.report.join("analysis.json");
    sylva::base::file::write(&out, |w| std::io::Write::write_all(w, text.as_bytes()))?;
    let label = path.file_name().and_then(|n| n.to_str()).unwrap_or("model");
    crate::plots::variogram(&args.report.join("variogram.png"), &a, label)?;
    if !args.quiet {
        println!(
            "{name}: H = {:.3} (dimension {:.3}) over {:.0} to {:.0} m; spectrum H = {:.3}; H along x, z = {:.3}, {:.3}; anisotropy {:.2}; heights {:.0} to {:.0} m; wrote {}{}",
            a.hurst,
            a.dimension,
            a.variogram_fit.scale_range[0],
            a.variogram_fit.scale_range[1],
            a.spectrum_fit.hurst,
            a.hurst_axes[0],
            a.hurst_axes[1],
            a.anisotropy,
            h.min,
            h.max,
            out.display(),
            if crate::plots::DRAWN {
                " and variogram.png"
            } else {
                ""
            }
        );
    }
    Ok(())
}
