//! Trees grown into their environment (the voxel growth paper): four oaks planted close
//! together compete for light and space, and the stand is written as glTF. `sylva grow` grows
//! a whole stand around a boulder, with flags.
//!
//! ```text
//! cargo run --release --example grow [OUT.glb]
//! ```

use sylva::export::write_stand_glb;
use sylva::forest::{Planting, StandOptions, grow_stand};
use sylva::growth::Response;
use sylva::terrain::FlatPlane;
use sylva::terrain::glam::Vec2;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "small_stand.glb".into());
    let oak = sylva::presets::species()?.remove(0);
    let ground = FlatPlane {
        height: 0.0,
        min: Vec2::ZERO,
        max: Vec2::splat(20.0),
    };
    let plantings: Vec<Planting> = [(8.0, 8.0), (12.0, 8.0), (8.0, 12.0), (12.0, 12.0)]
        .iter()
        .enumerate()
        .map(|(i, &(x, z))| Planting {
            species: 0,
            position: Vec2::new(x, z),
            seed: i as u64,
            start: 0,
            response: Response::default(),
        })
        .collect();
    let stand = grow_stand(
        std::slice::from_ref(&oak),
        &plantings,
        &ground,
        &StandOptions::default(),
    )?;
    // Growing together, branches turned aside rather than through each other.
    assert_eq!(stand.trees.len(), 4);
    assert!(stand.stats.segments > 0);
    let bytes = write_stand_glb(&stand, std::slice::from_ref(&oak), None, out.as_ref())?;
    println!(
        "grew 4 oaks ({} segments, {} deflected) and wrote {out} ({:.1} MB)",
        stand.stats.segments,
        stand.stats.deflected,
        bytes as f64 / 1e6
    );
    Ok(())
}
