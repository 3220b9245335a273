//! Fixtures the forest, paint and export crates' integration tests share: two small species
//! that derive and mesh in milliseconds, builders over them, flat and fractal ground, and
//! scratch files.
//!
//! Test code: these unwrap, as a failing fixture should fail the test that called it.

use sylva_forest::{ForestBuilder, ForestConfig, Life, Rect, Species};
use sylva_terrain::glam::Vec2;
use sylva_terrain::{DiamondSquare, FlatPlane, HeightField};

/// A leafy tree (weight 2) and an ABOP plant, four generations each, small steps.
pub fn small_species() -> Vec<Species> {
    let mut leafy = Species::from_preset("kenwood-leafy", 4).unwrap();
    leafy.turtle.step = 0.6;
    leafy.weight = 2.0;
    let mut plant = Species::from_preset("abop-1.24e", 4).unwrap();
    plant.turtle.step = 0.5;
    vec![leafy, plant]
}

/// [`small_species`] with the lives of a pioneer (the leafy tree: fast, short-lived,
/// wanting light, seeds blown far) and a shade-tolerant tree (the plant: slow, taller,
/// long-lived), for forests over time.
pub fn succession_species() -> Vec<Species> {
    let mut species = small_species();
    species[0].life = Life::default()
        .with_max_height(16.0)
        .with_growth_rate(0.07)
        .with_growth_shape(1.2)
        .with_max_age(100.0)
        .with_maturity_age(10.0)
        .with_shade_tolerance(0.1)
        .with_dispersal(60.0)
        .with_seeds_per_year(8.0)
        .with_leaf_area_index(3.0);
    species[1].life = Life::default()
        .with_max_height(22.0)
        .with_growth_rate(0.025)
        .with_growth_shape(1.5)
        .with_max_age(300.0)
        .with_maturity_age(25.0)
        .with_shade_tolerance(0.9)
        .with_dispersal(30.0)
        .with_seeds_per_year(4.0)
        .with_leaf_area_index(6.0);
    species
}

/// A builder over [`small_species`] with 2 MiB of cache and `seed`.
pub fn builder(seed: u64) -> ForestBuilder {
    let mut config = ForestConfig::new(small_species());
    config.budget = 2 << 20;
    config.seed = seed;
    ForestBuilder::new(config).unwrap()
}

/// Flat ground at height 0 from `-side` to `side` in x and z.
pub fn plane(side: f32) -> FlatPlane {
    FlatPlane {
        height: 0.0,
        min: Vec2::splat(-side),
        max: Vec2::splat(side),
    }
}

/// A file path (`forest.glb`) in a fresh temporary directory named after the test binary
/// (its hash included) and `name`, emptied first: each run reuses its folders rather than
/// leaving a new set behind (the export tests' come to tens of megabytes a run).
pub fn scratch(name: &str) -> std::path::PathBuf {
    let binary = std::env::current_exe()
        .ok()
        .and_then(|p| p.file_stem().map(|s| s.to_string_lossy().into_owned()))
        .unwrap_or_else(|| "test".into());
    let dir = std::env::temp_dir().join(format!("sylva-test-{binary}-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir.join("forest.glb")
}

/// A builder (seed 7) over a 65 x 65 fractal heightmap 3 m apart, and the heightmap's
/// rectangle.
pub fn export_case() -> (ForestBuilder, sylva_terrain::Heightmap, Rect) {
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
pub fn bare_species() -> Species {
    let text = "name: bare\ngrammar: bare.lsys\ngenerations: 3\n";
    let dir = std::env::temp_dir().join("sylva-bare");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("bare.lsys"), "axiom: A\nA -> [+A][-A]A").unwrap();
    Species::parse_file(text, &dir.join("bare.species")).unwrap()
}

/// FNV-1a, 64 bits: a pin for a file's bytes in known-answer tests.
pub fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}
