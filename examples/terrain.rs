//! A diamond-square heightmap, smoothed, written as a 16-bit PNG and read back: the terrain
//! crate's generator, `HeightField` sampling and its file format.
//!
//! ```text
//! cargo run --example terrain [OUT.png]
//! ```
//!
//! `sylva terrain` has flags for size, roughness, erosion and RAW output.

use sylva::terrain::{DiamondSquare, EdgeMode, HeightField, Heightmap};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "height.png".into());
    let mut map = DiamondSquare::new(257)
        .with_seed(7)
        .with_spacing(2.0)
        .with_amplitude(40.0)
        .generate()?;
    map.smooth(2.0, EdgeMode::Mirror)?;
    let stats = map.stats();
    sylva::base::file::write(&out, |w| {
        map.write_png16(w)
            .map(|_| ())
            .map_err(std::io::Error::other)
    })?;
    let back = Heightmap::read_png16(std::io::BufReader::new(std::fs::File::open(&out)?), None)?;
    // 16 bits over the height range: the file keeps heights to a few millimetres.
    let step = (stats.max - stats.min) / 65535.0;
    assert!((back.height(100.0, 100.0) - map.height(100.0, 100.0)).abs() <= step);
    println!(
        "wrote {out}: 257 x 257 samples 2 m apart, heights {:.1} to {:.1} m",
        stats.min, stats.max
    );
    Ok(())
}
