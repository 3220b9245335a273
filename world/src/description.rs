//! A world description: what a world is made of, as JSON (what a client posts to the
//! server, what a project folder's `world.json` holds), checked, completed with defaults and
//! written back in one canonical form whose hash is the world's id.

use std::path::Path;

use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};
use sylva_forest::Species;

use crate::error::WorldError;
use crate::id::WorldId;
use crate::limits::{
    DEFAULT_GROUP, DEFAULT_ORIGIN, DEFAULT_SIDE, DEFAULT_TILE_SIZE, MAX_DENSITY,
    MAX_DESCRIPTION_BYTES, MAX_EROSION, MAX_GROUP, MAX_HEIGHT_RANGE, MAX_SIDE, MAX_SPACING,
    MAX_SPECIES, MAX_YEARS, MIN_SIDE, TILE_SIZE_RANGE, check_budget_mb,
};
use crate::presets::{self, DEFAULT_RELIEF, DEFAULT_ROUGHNESS, DEFAULT_SMOOTHING};

/// What a world is made of. Every field has a default, so `{}` is the default world of
/// `sylva tiles`: the five bundled species on an 800 m diamond-square terrain, seed 1, in
/// 250 m tiles grouped 4 x 4.
///
/// ```
/// use sylva_world::WorldDescription;
///
/// let a = WorldDescription::parse(br#"{"seed": 7, "area": 600}"#)?;
/// let b = WorldDescription::parse(br#"{ "area": 600.0, "seed": 7, "tile_size": 250 }"#)?;
/// assert_eq!(a.id(), b.id()); // the same world, written two ways
/// assert!(WorldDescription::parse(br#"{"area": -1}"#).is_err());
/// # Ok::<(), sylva_world::WorldError>(())
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct WorldDescription {
    /// The species: bundled ones by name, or species files inline. Default: none, which
    /// grows the five default species ([`presets::species`]).
    pub species: Vec<SpeciesEntry>,
    /// The ground: generated, or an elevation model. Default: generated at the default
    /// terrain's settings.
    pub terrain: TerrainDescription,
    /// Side of the square world, metres (for generated terrain; an elevation model's own
    /// extent decides otherwise). Default: [`DEFAULT_SIDE`], 800.
    pub area: f32,
    /// World seed: trees, and generated terrain unless its own seed is given. Default: 1.
    pub seed: u64,
    /// Side of a fine tile, metres. Default: [`DEFAULT_TILE_SIZE`], 250.
    pub tile_size: f32,
    /// Fine tiles along each side of a coarse tile. Default: [`DEFAULT_GROUP`], 4.
    pub group: u32,
    /// Longitude and latitude (degrees) of the world's low corner on the globe. Default:
    /// [`DEFAULT_ORIGIN`], Zürich.
    pub origin: [f64; 2],
    /// Canopy trees per hectare. Default: `None`, the species' own spacing.
    pub density: Option<f32>,
    /// Instance-cache budget, MiB, shared among the species. Default: `None`, sized to the
    /// forest ([`WorldBuilder::budget_for`](crate::WorldBuilder::budget_for)): up to
    /// [`DEFAULT_BUDGET_MB`](crate::limits::DEFAULT_BUDGET_MB), 32, which the default world reaches.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub budget_mb: Option<u32>,
    /// Draw year N of a forest over time grown from bare ground (as `--year`), at most
    /// [`MAX_YEARS`]. Default: `None`, the forest as placed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub year: Option<u32>,
    /// The day of the year (0 to 365) the forest is drawn on (as `--season`): leaves, autumn
    /// colour, bare crowns and snow as that day has them. Default: `None`, summer.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub season: Option<f32>,
}

/// A species of a world.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum SpeciesEntry {
    /// A bundled species by name ([`presets::bundled_names`]: oak, birch, spruce, pine,
    /// hazel...).
    Bundled(String),
    /// A species file's text (the format of `Species::parse_file`), and the text of its
    /// grammar unless it names a preset: nothing is read from the server's disk.
    Inline {
        /// The species file.
        file: String,
        /// The grammar file's text, for a species whose `grammar:` is not a preset.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        grammar: Option<String>,
    },
}

/// Where the trees stand.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, rename_all = "snake_case")]
pub enum TerrainDescription {
    /// Diamond-square, smoothed: the batch tools' default terrain with its settings open.
    Generated {
        /// Terrain seed. Default: `None`, the world seed.
        #[serde(default)]
        seed: Option<u64>,
        /// Diamond-square's roughness (0 to 1). Default: [`DEFAULT_ROUGHNESS`], 0.75.
        #[serde(default = "default_roughness")]
        roughness: f32,
        /// Relief, as a share of the world's side. Default: [`DEFAULT_RELIEF`], 0.06.
        #[serde(default = "default_relief")]
        relief: f32,
        /// Gaussian smoothing, in samples (0 for none). Default: [`DEFAULT_SMOOTHING`], 2.
        #[serde(default = "default_smoothing")]
        smoothing: f32,
        /// Hydraulic erosion after smoothing, as rain droplets per sample (0 for none, up
        /// to [`MAX_EROSION`]; 1 cuts gullies). Default: 0. Left out of the canonical form when 0, so worlds described
        /// before erosion keep their ids.
        #[serde(default, skip_serializing_if = "is_zero")]
        erosion: f32,
    },
    /// An elevation model: uploaded with `POST /heightmaps`, or a project's `heightmap.*`.
    Heightmap {
        /// The model's id ([`crate::model_id`] of its bytes; what the upload returned).
        id: String,
        /// Metres between samples (when the file does not say). Default: the file's.
        #[serde(default)]
        spacing: Option<f32>,
        /// Heights of samples 0 and 65535, metres (when the file does not say). Default: the
        /// file's.
        #[serde(default)]
        height_range: Option<[f32; 2]>,
        /// The window of the model the world stands on: its north-west sample's column and
        /// row, then its width and height in samples. Default: `None`, the whole model when it
        /// is at most [`MAX_SIDE`] a side, else its middle [`MAX_SIDE`] square. Left out of
        /// the canonical form when `None`, so worlds described before it keep their ids.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        crop: Option<[usize; 4]>,
    },
}

fn default_roughness() -> f32 {
    DEFAULT_ROUGHNESS
}
fn default_relief() -> f32 {
    DEFAULT_RELIEF
}
fn default_smoothing() -> f32 {
    DEFAULT_SMOOTHING
}
fn is_zero(x: &f32) -> bool {
    *x == 0.0
}

impl Default for TerrainDescription {
    fn default() -> Self {
        TerrainDescription::Generated {
            seed: None,
            roughness: default_roughness(),
            relief: default_relief(),
            smoothing: default_smoothing(),
            erosion: 0.0,
        }
    }
}

impl Default for WorldDescription {
    fn default() -> Self {
        WorldDescription {
            species: Vec::new(),
            terrain: TerrainDescription::default(),
            area: DEFAULT_SIDE,
            seed: 1,
            tile_size: DEFAULT_TILE_SIZE,
            group: DEFAULT_GROUP,
            origin: DEFAULT_ORIGIN,
            density: None,
            budget_mb: None,
            year: None,
            season: None,
        }
    }
}

impl WorldDescription {
    /// Parses and checks a description: JSON of at most [`MAX_DESCRIPTION_BYTES`], no field
    /// unknown, every number in its range. The error says which field is wrong and why.
    pub fn parse(bytes: &[u8]) -> Result<WorldDescription, WorldError> {
        if bytes.len() > MAX_DESCRIPTION_BYTES {
            return Err(WorldError::TooLarge(format!(
                "a world description of {} bytes is over the limit of {MAX_DESCRIPTION_BYTES}",
                bytes.len()
            )));
        }
        let invalid =
            |m: String| WorldError::Invalid(format!("the world description is not valid: {m}"));
        let mut json = serde_json::Deserializer::from_slice(bytes);
        let description: WorldDescription =
            serde_path_to_error::deserialize(&mut json).map_err(|e| {
                let at = e.path().to_string();
                let field = if at == "." {
                    String::new()
                } else {
                    format!("{at}: ")
                };
                invalid(format!("{field}{}", e.inner()))
            })?;
        // Nothing may follow the description but white space.
        json.end().map_err(|e| invalid(e.to_string()))?;
        description.check()?;
        Ok(description)
    }

    /// Every field in its range (the checks `parse` makes).
    pub fn check(&self) -> Result<(), WorldError> {
        let bad = |m: String| Err(WorldError::Invalid(m));
        if self.species.len() > MAX_SPECIES {
            return bad(format!(
                "{} species: a world has at most {MAX_SPECIES}",
                self.species.len()
            ));
        }
        for s in &self.species {
            if let SpeciesEntry::Bundled(name) = s
                && presets::bundled(name).is_none()
            {
                return Err(unknown_species(name));
            }
        }
        if !(self.area >= MIN_SIDE && self.area <= MAX_SIDE) {
            return bad(format!(
                "area {}: expected a side from {MIN_SIDE} to {MAX_SIDE} metres",
                self.area
            ));
        }
        let (small, large) = TILE_SIZE_RANGE;
        if !(self.tile_size >= small && self.tile_size <= large) {
            return bad(format!(
                "tile_size {}: expected {small} to {large} metres",
                self.tile_size
            ));
        }
        if !(1..=MAX_GROUP).contains(&self.group) {
            return bad(format!("group {}: expected 1 to {MAX_GROUP}", self.group));
        }
        let [lon, lat] = self.origin;
        if !(lon.abs() <= 180.0 && lat.abs() <= 90.0) {
            return bad(format!(
                "origin [{lon}, {lat}]: expected longitude and latitude in degrees"
            ));
        }
        if let Some(d) = self.density
            && !(d > 0.0 && d <= MAX_DENSITY)
        {
            return bad(format!(
                "density {d}: expected 0 < trees per hectare <= {MAX_DENSITY}"
            ));
        }
        if let Some(Err(e)) = self.budget_mb.map(|mb| check_budget_mb(mb.into())) {
            return bad(format!("budget_mb {e}"));
        }
        if let Some(year) = self.year.filter(|&y| y > MAX_YEARS) {
            return bad(format!("year {year}: expected 0 to {MAX_YEARS}"));
        }
        if let Some(day) = self.season.filter(|d| !(0.0..=365.0).contains(d)) {
            return bad(format!(
                "season {day}: expected a day of the year, 0 to 365"
            ));
        }
        match &self.terrain {
            TerrainDescription::Generated {
                roughness,
                relief,
                smoothing,
                erosion,
                ..
            } => {
                if !(0.0..=1.0).contains(roughness) {
                    return bad(format!("terrain roughness {roughness}: expected 0 to 1"));
                }
                if !(0.0..=1.0).contains(relief) {
                    return bad(format!("terrain relief {relief}: expected 0 to 1"));
                }
                if !(0.0..=64.0).contains(smoothing) {
                    return bad(format!("terrain smoothing {smoothing}: expected 0 to 64"));
                }
                if !(0.0..=MAX_EROSION).contains(erosion) {
                    return bad(format!(
                        "terrain erosion {erosion}: expected 0 to {MAX_EROSION} droplets per sample"
                    ));
                }
            }
            TerrainDescription::Heightmap {
                id,
                spacing,
                height_range,
                crop,
            } => {
                if !WorldId::is_valid(id) {
                    return bad(format!(
                        "heightmap id '{}': expected the id POST /heightmaps returned",
                        id.chars().take(80).collect::<String>()
                    ));
                }
                if let Some(s) = spacing
                    && !(*s > 0.0 && *s <= MAX_SPACING)
                {
                    return bad(format!(
                        "terrain spacing {s}: expected 0 to {MAX_SPACING} metres"
                    ));
                }
                if let Some([lo, hi]) = height_range
                    && !(lo.is_finite()
                        && hi.is_finite()
                        && lo < hi
                        && (hi - lo) <= MAX_HEIGHT_RANGE)
                {
                    return bad(format!(
                        "terrain height_range [{lo}, {hi}]: expected low < high, within {MAX_HEIGHT_RANGE} m"
                    ));
                }
                if let Some([_, _, w, h]) = crop
                    && (*w < 2 || *h < 2)
                {
                    return bad(format!(
                        "terrain crop {w} x {h} samples: expected at least 2 x 2"
                    ));
                }
            }
        }
        Ok(())
    }

    /// The world's species, parsed: the bundled ones by name (the default five for none), inline
    /// files as written with their grammars (a mistake in one is a 400 with its line and
    /// column); an inline species never reads a file.
    ///
    /// ```
    /// use sylva_world::WorldDescription;
    /// let d = WorldDescription::parse(br#"{"species": ["pine", "oak"]}"#)?;
    /// let names: Vec<String> = d.species()?.into_iter().map(|s| s.name).collect();
    /// assert_eq!(names, ["pine", "oak"]);
    /// # Ok::<(), sylva_world::WorldError>(())
    /// ```
    pub fn species(&self) -> Result<Vec<Species>, WorldError> {
        if self.species.is_empty() {
            return presets::species().map_err(WorldError::Species);
        }
        self.species
            .iter()
            .enumerate()
            .map(|(k, entry)| match entry {
                SpeciesEntry::Bundled(name) => presets::bundled(name)
                    .ok_or_else(|| unknown_species(name))?
                    .species()
                    .map_err(WorldError::Species),
                SpeciesEntry::Inline { file, grammar } => {
                    let name = format!("species[{k}]");
                    Species::parse_detached(file, Path::new(&name), grammar.as_deref())
                        .map_err(WorldError::Species)
                }
            })
            .collect()
    }

    /// The canonical form: compact JSON with every field, in a fixed order, numbers as
    /// serde_json writes them. Two descriptions of one world have one canonical form.
    pub fn canonical(&self) -> String {
        // A struct of plain fields, strings and numbers cannot fail to serialize.
        serde_json::to_string(self).unwrap_or_default()
    }

    /// The world's id: the first 128 bits of the SHA-256 of its canonical form, in hex.
    pub fn id(&self) -> WorldId {
        WorldId::of(&Sha256::digest(self.canonical().as_bytes()))
    }
}

/// The error for a species name no folder bundles.
fn unknown_species(name: &str) -> WorldError {
    WorldError::UnknownSpecies {
        name: name.chars().take(80).collect(),
        known: presets::bundled_names().join(", "),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_fill_an_empty_description() {
        let d = WorldDescription::parse(b"{}").unwrap();
        assert_eq!(d, WorldDescription::default());
        assert_eq!(d.id(), WorldDescription::default().id());
    }

    #[test]
    fn canonical_form_round_trips() {
        let d = WorldDescription::parse(
            br#"{"species": ["oak", {"file": "name x\n"}], "terrain": {"generated": {"seed": 3}}, "density": 120}"#,
        )
        .unwrap();
        let again = WorldDescription::parse(d.canonical().as_bytes()).unwrap();
        assert_eq!(d, again);
        assert_eq!(d.canonical(), again.canonical());
    }

    #[test]
    fn the_year_and_the_season_reach_the_builder() {
        let d = WorldDescription::parse(br#"{"year": 80, "season": 290, "species": ["birch"]}"#)
            .unwrap();
        let b = d.world_builder().unwrap();
        assert_eq!((b.year, b.season), (Some(80), Some(290.0)));
        // Absent, they leave a description's canonical form (and its world's id) as before.
        assert!(!WorldDescription::default().canonical().contains("year"));
    }

    #[test]
    fn mistakes_name_their_field() {
        for (json, field) in [
            (r#"{"area": 0}"#, "area"),
            (r#"{"area": 1e9}"#, "area"),
            (r#"{"tile_size": 1}"#, "tile_size"),
            (r#"{"group": 0}"#, "group"),
            (r#"{"origin": [200, 0]}"#, "origin"),
            (r#"{"budget_mb": 100000}"#, "budget_mb"),
            (r#"{"year": 100000}"#, "year"),
            (r#"{"season": 400}"#, "season"),
            (r#"{"density": -3}"#, "density"),
            (r#"{"colour": 1}"#, "colour"),
            (r#"{"seed": -1}"#, "seed"),
            (r#"{"seed": 1e400}"#, "description"),
            (
                r#"{"terrain": {"heightmap": {"id": "../../etc"}}}"#,
                "heightmap id",
            ),
            (
                r#"{"terrain": {"generated": {"roughness": 3}}}"#,
                "roughness",
            ),
            (r#"{"terrain": {"generated": {"erosion": 9}}}"#, "erosion"),
            (r#"[1, 2"#, "description"),
        ] {
            let e = WorldDescription::parse(json.as_bytes()).unwrap_err();
            assert!(e.is_user_mistake(), "{json}");
            assert!(e.to_string().contains(field), "{json}: {e}");
        }
    }

    #[test]
    fn unknown_species_and_oversize_are_refused() {
        let e = WorldDescription::parse(br#"{"species": ["baobab"]}"#).unwrap_err();
        assert_eq!(e.code(), "unknown_species");
        assert!(e.to_string().contains("oak, birch"), "{e}");
        let big = vec![b' '; MAX_DESCRIPTION_BYTES + 1];
        assert_eq!(
            WorldDescription::parse(&big).unwrap_err().code(),
            "too_large"
        );
    }

    #[test]
    fn no_erosion_keeps_the_ids_of_worlds_described_before_it() {
        let before = r#"{"terrain": {"generated": {"seed": 3}}}"#;
        let zero = r#"{"terrain": {"generated": {"seed": 3, "erosion": 0}}}"#;
        let some = r#"{"terrain": {"generated": {"seed": 3, "erosion": 1}}}"#;
        let id = |j: &str| WorldDescription::parse(j.as_bytes()).unwrap().id();
        assert_eq!(id(before), id(zero));
        assert_ne!(id(before), id(some));
        assert!(!WorldDescription::default().canonical().contains("erosion"));
    }

    #[test]
    fn ids_differ_by_any_field() {
        let a = WorldDescription::default();
        let mut b = a.clone();
        b.seed = 2;
        assert_ne!(a.id(), b.id());
        assert_eq!(a.id().as_str().len(), 32);
    }
}
