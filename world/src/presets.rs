//! The forest sylva grows when given nothing else: the bundled species (one folder each under
//! `world/species/`) and a smoothed diamond-square terrain. The CLI, the viewer, the server
//! and the examples start from these, so a user's first forest, the README's pictures and
//! the tools' defaults are one forest.
//!
//! ```
//! use sylva_forest::{ForestBuilder, ForestConfig, Rect};
//! use sylva_terrain::glam::Vec2;
//!
//! let terrain = sylva_world::presets::terrain(7, 200.0)?;
//! let builder = ForestBuilder::new(ForestConfig::new(sylva_world::presets::species()?))?;
//! let trees = builder.trees(&terrain, Rect::new(Vec2::ZERO, Vec2::splat(200.0)));
//! assert!(trees.len() > 100);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::path::Path;

use sylva_forest::{ForestError, Species};
use sylva_terrain::{DiamondSquare, EdgeMode, Heightmap, TerrainError};

/// A species bundled with sylva: a folder `world/species/NAME/` holding `NAME.species` and,
/// unless its grammar is a preset, one `.lsys` grammar file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BundledSpecies {
    /// The species' name (its folder's).
    pub name: &'static str,
    /// The species file's path in the repository.
    pub path: &'static str,
    /// The species file's text (its format is documented on [`Species::parse_file`]).
    pub text: &'static str,
    /// The grammar's text, for a species whose `grammar:` is not a preset.
    pub grammar: Option<&'static str>,
}

impl BundledSpecies {
    /// The species, parsed.
    pub fn species(&self) -> Result<Species, ForestError> {
        match self.grammar {
            Some(grammar) => {
                Species::parse_detached(self.text, Path::new(self.path), Some(grammar))
            }
            None => Species::parse_file(self.text, Path::new(self.path)),
        }
    }
}

/// Every bundled species: the default forest's five first (oak, birch, spruce, pine,
/// hazel), then any other folder by name. Written by the build script from the folders.
pub const BUNDLED: &[BundledSpecies] = include!(concat!(env!("OUT_DIR"), "/species.rs"));

/// How many bundled species the default forest grows: the first of [`BUNDLED`].
pub const DEFAULT_SPECIES: usize = 5;

/// Diamond-square's roughness in the default terrain.
pub const DEFAULT_ROUGHNESS: f32 = 0.75;
/// The default terrain's relief, as a share of its side.
pub const DEFAULT_RELIEF: f32 = 0.06;
/// The default terrain's Gaussian smoothing, in samples.
pub const DEFAULT_SMOOTHING: f32 = 2.0;
/// Samples along a side of generated terrain.
pub const GENERATED_SIZE: usize = 257;

/// The names of the bundled species, in [`BUNDLED`]'s order.
///
/// ```
/// assert_eq!(sylva_world::presets::bundled_names()[..5], ["oak", "birch", "spruce", "pine", "hazel"]);
/// ```
pub fn bundled_names() -> Vec<&'static str> {
    BUNDLED.iter().map(|b| b.name).collect()
}

/// The bundled species named `name`, if there is one.
///
/// ```
/// assert_eq!(sylva_world::presets::bundled("pine").map(|b| b.name), Some("pine"));
/// assert!(sylva_world::presets::bundled("baobab").is_none());
/// ```
pub fn bundled(name: &str) -> Option<&'static BundledSpecies> {
    BUNDLED.iter().find(|b| b.name == name)
}

/// The bundled species called `name` (any folder of `world/species/`, not only the default
/// five), else the species file at the path `name`: how the command line takes `--species`.
///
/// ```
/// let fir = sylva_world::presets::named_or_file("fir")?;
/// assert_eq!(fir.name, "fir");
/// assert!(sylva_world::presets::named_or_file("no/such.species").is_err());
/// // A bare name that is no bundled species, nor a file here, names the bundled ones.
/// let baobab = sylva_world::presets::named_or_file("baobab").unwrap_err().to_string();
/// assert!(baobab.starts_with("unknown species 'baobab': the bundled ones are oak, birch"), "{baobab}");
/// # Ok::<(), sylva_forest::ForestError>(())
/// ```
pub fn named_or_file(name: impl AsRef<Path>) -> Result<Species, ForestError> {
    let name = name.as_ref();
    let text = name.to_string_lossy();
    match bundled(&text) {
        Some(b) => b.species(),
        None if name.components().count() == 1 && name.extension().is_none() && !name.exists() => {
            Err(ForestError::UnknownSpecies {
                name: text.chars().take(80).collect(),
                known: bundled_names().join(", "),
            })
        }
        None => Species::from_file(name),
    }
}

/// The default forest's species: the first [`DEFAULT_SPECIES`] of [`BUNDLED`], parsed.
///
/// ```
/// let names: Vec<String> = sylva_world::presets::species()?.into_iter().map(|s| s.name).collect();
/// assert_eq!(names, ["oak", "birch", "spruce", "pine", "hazel"]);
/// # Ok::<(), sylva_forest::ForestError>(())
/// ```
pub fn species() -> Result<Vec<Species>, ForestError> {
    BUNDLED
        .iter()
        .take(DEFAULT_SPECIES)
        .map(BundledSpecies::species)
        .collect()
}

/// The default terrain over a square of `side` metres: diamond-square with
/// [`GENERATED_SIZE`] samples a side (roughness [`DEFAULT_ROUGHNESS`], relief
/// [`DEFAULT_RELIEF`] of the side) smoothed with a Gaussian of [`DEFAULT_SMOOTHING`] samples,
/// so hills roll without cliffs at any size. A pure function of `seed` and `side`.
///
/// ```
/// let terrain = sylva_world::presets::terrain(1, 400.0)?;
/// assert_eq!(terrain.size(), 257);
/// assert!((terrain.extent() - 400.0).abs() < 1e-3);
/// # Ok::<(), sylva_terrain::TerrainError>(())
/// ```
pub fn terrain(seed: u64, side: f32) -> Result<Heightmap, TerrainError> {
    generated(
        seed,
        side,
        DEFAULT_ROUGHNESS,
        DEFAULT_RELIEF,
        DEFAULT_SMOOTHING,
    )
}

/// Smoothed diamond-square terrain over `side` metres with its settings open: `roughness`
/// (0 to 1), `relief` as a share of the side, `smoothing` in samples (0 for none).
pub fn generated(
    seed: u64,
    side: f32,
    roughness: f32,
    relief: f32,
    smoothing: f32,
) -> Result<Heightmap, TerrainError> {
    let mut map = DiamondSquare::new(GENERATED_SIZE)
        .with_seed(seed)
        .with_spacing(side / (GENERATED_SIZE - 1) as f32)
        .with_roughness(roughness)
        .with_amplitude(side * relief)
        .generate()?;
    if smoothing > 0.0 {
        map.smooth(smoothing, EdgeMode::Mirror)?;
    }
    Ok(map)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every bundled folder parses, and its species carries its folder's name.
    #[test]
    fn every_bundled_species_parses_under_its_folder_name() {
        for b in BUNDLED {
            let s = b.species().unwrap_or_else(|e| panic!("{}: {e}", b.path));
            assert_eq!(s.name, b.name, "{}", b.path);
        }
        assert!(BUNDLED.len() >= DEFAULT_SPECIES);
    }

    /// The open generator at the defaults is the default terrain, bit for bit.
    #[test]
    fn the_default_terrain_is_the_generator_at_its_defaults() {
        let a = terrain(3, 500.0).unwrap();
        let b = generated(3, 500.0, 0.75, 0.06, 2.0).unwrap();
        assert_eq!(a, b);
    }
}
