//! `sylva terrain`: a diamond-square heightmap, smoothed and optionally eroded, written as a
//! 16-bit PNG (and optionally RAW).

use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use sylva::terrain::{DiamondSquare, EdgeMode, HydraulicErosion, ThermalErosion};

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
    /// Metres between samples.
    #[arg(long, value_name = "D", default_value_t = 1.0)]
    spacing: f32,
    /// Height amplitude in metres (default: the generator's).
    #[arg(long, value_name = "A")]
    amplitude: Option<f32>,
    /// Apply thermal and hydraulic erosion.
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
    let start = Instant::now();
    let mut ds = DiamondSquare::new(args.size)
        .with_seed(args.seed)
        .with_roughness(args.roughness)
        .with_spacing(args.spacing)
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
    if args.erode {
        let (eroded, _) = phase(args.quiet, "eroding", || {
            ThermalErosion::default().apply(&mut map)?;
            HydraulicErosion::new((args.size * args.size / 4) as u32, args.seed).apply(&mut map)
        });
        eroded?;
    }
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
