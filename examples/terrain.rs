//! Generates a diamond-square heightmap and writes it as a 16-bit PNG (and optionally RAW).
//!
//! ```text
//! cargo run --release --example terrain -- [--size 1025] [--roughness 0.8] [--seed 7]
//!     [--smooth 2.0] [--spacing 1.0] [--amplitude A] [--erode] [--wrap] [--out height.png] [--raw]
//! ```
//!
//! Prints min, max and mean height and the time taken.

mod common;

use std::process::ExitCode;
use std::time::Instant;

use sylva::terrain::{DiamondSquare, EdgeMode, HydraulicErosion, ThermalErosion};

const USAGE: &str = "usage: terrain [--size N] [--roughness H] [--seed S] [--smooth SIGMA] [--spacing D] \
                     [--amplitude A] [--erode] [--wrap] [--out height.png] [--raw]";

fn run() -> Result<(), String> {
    let mut size = 1025usize;
    let (mut roughness, mut seed, mut sigma, mut spacing) = (0.8f32, 7u64, 2.0f32, 1.0f32);
    let (mut amplitude, mut erode, mut wrap, mut raw) = (None, false, false, false);
    let mut out = String::from("height.png");
    let mut it = std::env::args().skip(1);
    while let Some(a) = it.next() {
        match a.as_str() {
            "--size" => size = common::parse_value("--size", it.next())?,
            "--roughness" => roughness = common::parse_value("--roughness", it.next())?,
            "--seed" => seed = common::parse_value("--seed", it.next())?,
            "--smooth" => sigma = common::parse_value("--smooth", it.next())?,
            "--spacing" => spacing = common::parse_value("--spacing", it.next())?,
            "--amplitude" => {
                amplitude = Some(common::parse_value::<f32>("--amplitude", it.next())?)
            }
            "--erode" => erode = true,
            "--wrap" => wrap = true,
            "--raw" => raw = true,
            "--out" => out = common::parse_value::<String>("--out", it.next())?,
            "--help" | "-h" => common::print_help(USAGE),
            s => return Err(format!("unknown argument {s}\n{USAGE}")),
        }
    }
    let start = Instant::now();
    let mut ds = DiamondSquare::new(size)
        .with_seed(seed)
        .with_roughness(roughness)
        .with_spacing(spacing)
        .with_wrap(wrap);
    if let Some(a) = amplitude {
        ds = ds.with_amplitude(a);
    }
    let mut map = ds.generate().map_err(|e| e.to_string())?;
    let generated = start.elapsed();
    map.smooth(
        sigma,
        if wrap {
            EdgeMode::Wrap
        } else {
            EdgeMode::Mirror
        },
    )
    .map_err(|e| e.to_string())?;
    let smoothed = start.elapsed();
    if erode {
        ThermalErosion::default()
            .apply(&mut map)
            .map_err(|e| e.to_string())?;
        HydraulicErosion::new((size * size / 4) as u32, seed)
            .apply(&mut map)
            .map_err(|e| e.to_string())?;
    }
    let total = start.elapsed();
    let file = std::fs::File::create(&out).map_err(|e| format!("{out}: {e}"))?;
    let range = map
        .write_png16(std::io::BufWriter::new(file))
        .map_err(|e| format!("{out}: {e}"))?;
    println!(
        "wrote {out} ({size} x {size}, heights {} to {} in the 16-bit range)",
        range.min, range.max
    );
    if raw {
        let path = std::path::Path::new(&out).with_extension("raw");
        let (bytes, range) = map.to_raw16();
        std::fs::write(&path, bytes).map_err(|e| format!("{}: {e}", path.display()))?;
        println!(
            "wrote {} (16-bit little-endian; 0 = {} and 65535 = {})",
            path.display(),
            range.min,
            range.max
        );
    }
    let s = map.stats();
    println!("min {:.3}  max {:.3}  mean {:.3}", s.min, s.max, s.mean);
    println!(
        "time: diamond-square {:.1} ms, smoothing {:.1} ms, total {:.1} ms",
        generated.as_secs_f64() * 1e3,
        (smoothed - generated).as_secs_f64() * 1e3,
        total.as_secs_f64() * 1e3
    );
    Ok(())
}

fn main() -> ExitCode {
    common::finish(run())
}
