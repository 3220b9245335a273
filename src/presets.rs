//! The forest sylva grows when given nothing else: five temperate species and a smoothed
//! diamond-square terrain. The examples and the viewer start from these, so a user's first
//! forest, the README's pictures and the tools' defaults are one forest.
//!
//! ```
//! use sylva::forest::{ForestBuilder, ForestConfig, Rect};
//! use sylva::terrain::glam::Vec2;
//!
//! let terrain = sylva::presets::terrain(7, 200.0)?;
//! let builder = ForestBuilder::new(ForestConfig::new(sylva::presets::species()?))?;
//! let trees = builder.trees(&terrain, Rect::new(Vec2::ZERO, Vec2::splat(200.0)));
//! assert!(trees.len() > 100);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::path::Path;

use crate::forest::{ForestError, Species};
use crate::terrain::{DiamondSquare, EdgeMode, Heightmap, TerrainError};

/// The bundled species files: (path in the repository, text). Oak, birch, spruce, pine and
/// hazel, each a `.species` file (its format is documented on
/// [`Species::parse_file`](crate::forest::Species::parse_file)); copy one to start your own.
pub const SPECIES_FILES: [(&str, &str); 5] = [
    (
        "examples/species/oak.species",
        include_str!("../examples/species/oak.species"),
    ),
    (
        "examples/species/birch.species",
        include_str!("../examples/species/birch.species"),
    ),
    (
        "examples/species/spruce.species",
        include_str!("../examples/species/spruce.species"),
    ),
    (
        "examples/species/pine.species",
        include_str!("../examples/species/pine.species"),
    ),
    (
        "examples/species/hazel.species",
        include_str!("../examples/species/hazel.species"),
    ),
];

/// The five bundled species of [`SPECIES_FILES`], parsed, in that order.
///
/// ```
/// let names: Vec<String> = sylva::presets::species()?.into_iter().map(|s| s.name).collect();
/// assert_eq!(names, ["oak", "birch", "spruce", "pine", "hazel"]);
/// # Ok::<(), sylva::forest::ForestError>(())
/// ```
pub fn species() -> Result<Vec<Species>, ForestError> {
    SPECIES_FILES
        .iter()
        .map(|(path, text)| Species::parse_file(text, Path::new(path)))
        .collect()
}

/// The default terrain over a square of `side` metres: diamond-square with 257 samples a
/// side (roughness 0.75, relief 6% of the side) smoothed with a Gaussian of 2 samples, so
/// hills roll without cliffs at any size. A pure function of `seed` and `side`.
///
/// ```
/// let terrain = sylva::presets::terrain(1, 400.0)?;
/// assert_eq!(terrain.size(), 257);
/// assert!((terrain.extent() - 400.0).abs() < 1e-3);
/// # Ok::<(), sylva::terrain::TerrainError>(())
/// ```
pub fn terrain(seed: u64, side: f32) -> Result<Heightmap, TerrainError> {
    let mut map = DiamondSquare::new(257)
        .with_seed(seed)
        .with_spacing(side / 256.0)
        .with_roughness(0.75)
        .with_amplitude(side * 0.06)
        .generate()?;
    map.smooth(2.0, EdgeMode::Mirror)?;
    Ok(map)
}
