//! Painting a forest: a stroke of one species onto bare ground, the painted trees, and the
//! masks saved and loaded back. `sylva paint` runs a whole timed session.
//!
//! ```text
//! cargo run --release --example paint [MASKS_DIR]
//! ```

use sylva::forest::{ForestBuilder, ForestConfig, Rect};
use sylva::paint::{Brush, BrushAction, ForestPainter, PaintLayer, load_masks, save_masks};
use sylva::terrain::HeightField;
use sylva::terrain::glam::Vec2;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let dir = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "example_masks".into());
    let config = ForestConfig::new(sylva::presets::species()?).with_budget(32 << 20);
    let builder = ForestBuilder::new(config)?;
    let terrain = sylva::presets::terrain(1, 300.0)?;
    let (lo, hi) = terrain.bounds();
    let bounds = Rect::new(lo, hi);
    let names: Vec<String> = builder
        .config()
        .species
        .iter()
        .map(|s| s.name.clone())
        .collect();
    let layer = PaintLayer::new(bounds, 1.0, names.len())?;
    let mut painter = ForestPainter::new(builder, terrain, layer)?;
    assert_eq!(painter.tree_count(), 0, "bare ground grows nothing");

    // A stand of the first species (oak) along a 100 m stroke, 25 m wide.
    let brush = Brush::new(BrushAction::Add { species: 0 }, 25.0);
    let report = painter.stroke(brush, &[Vec2::new(100.0, 150.0), Vec2::new(200.0, 150.0)])?;
    let painted = painter.tree_count();
    assert!(painted > 0);
    painter.undo();
    assert_eq!(painter.tree_count(), 0);
    painter.redo();
    assert_eq!(painter.tree_count(), painted);

    let names: Vec<&str> = names.iter().map(String::as_str).collect();
    save_masks(painter.layer(), &names, dir.as_ref())?;
    assert_eq!(&load_masks(dir.as_ref(), &names, bounds)?, painter.layer());
    println!(
        "painted {painted} trees in {:.1} ms; masks saved to {dir}/ (sylva forest --area 300 --paint {dir})",
        report.elapsed.as_secs_f64() * 1e3
    );
    Ok(())
}
