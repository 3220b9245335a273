//! Helpers shared by the forest crate's integration tests.
#![allow(dead_code, reason = "each test file uses only some of these helpers")]

use sylva_forest::{ForestBuilder, ForestConfig, Rect, Species};
use sylva_terrain::glam::Vec2;
use sylva_terrain::{DiamondSquare, FlatPlane, HeightField};

pub(crate) fn small_species() -> Vec<Species> {
    let mut leafy = Species::from_preset("kenwood-leafy", 4).unwrap();
    leafy.turtle.step = 0.6;
    leafy.weight = 2.0;
    let mut plant = Species::from_preset("abop-1.24e", 4).unwrap();
    plant.turtle.step = 0.5;
    vec![leafy, plant]
}

pub(crate) fn builder(seed: u64) -> ForestBuilder {
    let mut config = ForestConfig::new(small_species());
    config.budget = 2 << 20;
    config.seed = seed;
    ForestBuilder::new(config).unwrap()
}

pub(crate) fn plane(side: f32) -> FlatPlane {
    FlatPlane {
        height: 0.0,
        min: Vec2::splat(-side),
        max: Vec2::splat(side),
    }
}

/// A file path in a fresh temporary directory of this test.
pub(crate) fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("sylva-export-test-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join("forest.glb")
}

pub(crate) fn export_case() -> (ForestBuilder, sylva_terrain::Heightmap, Rect) {
    let map = DiamondSquare::new(65)
        .with_spacing(3.0)
        .with_seed(1)
        .with_amplitude(10.0)
        .generate()
        .unwrap();
    let (lo, hi) = map.bounds();
    (builder(7), map, Rect::new(lo, hi))
}

/// A species whose grammar never moves the turtle: its trees draw nothing.
pub(crate) fn bare_species() -> Species {
    let text = "name: bare\ngrammar: bare.lsys\ngenerations: 3\n";
    let dir = std::env::temp_dir().join(format!("sylva-bare-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("bare.lsys"), "axiom: A\nA -> [+A][-A]A").unwrap();
    Species::parse_file(text, &dir.join("bare.species")).unwrap()
}
