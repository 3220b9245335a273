//! A forest streamed block by block and written as binary glTF: `ForestBuilder::stream` for
//! your own engine, `write_glb` for a file. The full main job, with every flag, is
//! `sylva forest`.
//!
//! ```text
//! cargo run --release --example forest [OUT.glb]
//! ```

use sylva::export::{GltfOptions, write_glb};
use sylva::forest::{ForestBuilder, ForestConfig, PlacementBlock, Rect};
use sylva::terrain::HeightField;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "small_forest.glb".into());
    let config = ForestConfig::new(sylva::presets::species()?).with_budget(32 << 20);
    let builder = ForestBuilder::new(config)?;
    let terrain = sylva::presets::terrain(1, 200.0)?;
    let (lo, hi) = terrain.bounds();
    let region = Rect::new(lo, hi);

    // Block by block, on every core, in a fixed order: nothing of the forest is kept.
    let (mut trees, mut placements) = (0, 0);
    builder.stream(&terrain, region, &mut |block: &PlacementBlock| {
        trees += block.trees.len();
        placements += block.placements.len();
        Ok(())
    })?;

    let written = write_glb(
        &builder,
        &terrain,
        region,
        Some(&terrain.mesh(2)?),
        &GltfOptions::default(),
        out.as_ref(),
    )?;
    // The file holds exactly the trees and placements the stream handed on (placements of
    // branches with no geometry yet are counted apart).
    assert_eq!(written.trees, trees);
    assert_eq!(written.placements + written.empty_placements, placements);
    println!(
        "{trees} trees, {placements} placements; wrote {out} ({:.1} MB)",
        written.bytes as f64 / 1e6
    );
    Ok(())
}
