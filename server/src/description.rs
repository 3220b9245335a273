//! A world description: the JSON a client posts to make a world, checked, completed with
//! defaults and written back in one canonical form whose hash is the world's id.

use std::path::Path;

use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};
use sylva::forest::Species;

use crate::error::ApiError;
use crate::id::WorldId;

/// Most bytes a description may have (inline species files included).
pub const MAX_DESCRIPTION_BYTES: usize = 256 << 10;
/// Most species a world may have.
pub const MAX_SPECIES: usize = 16;
/// Largest side of a world, metres (the batch writer's limit too).
pub const MAX_SIDE: f32 = 20_000.0;

/// What a world is made of. Every field has a default, so `{}` is the default world of
/// `sylva tiles`: the five bundled species on an 800 m diamond-square terrain, seed 1, in
/// 250 m tiles grouped 4 x 4.
///
/// ```
/// use sylva_server::WorldDescription;
///
/// let a = WorldDescription::parse(br#"{"seed": 7, "area": 600}"#)?;
/// let b = WorldDescription::parse(br#"{ "area": 600.0, "seed": 7, "tile_size": 250 }"#)?;
/// assert_eq!(a.id(), b.id()); // the same world, written two ways
/// assert!(WorldDescription::parse(br#"{"area": -1}"#).is_err());
/// # Ok::<(), sylva_server::ApiError>(())
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct WorldDescription {
    /// The species: bundled ones by name, or species files inline.
    pub species: Vec<SpeciesEntry>,
    /// The ground: generated, or an uploaded heightmap.
    pub terrain: TerrainDescription,
    /// Side of the square world, metres (for generated terrain; an uploaded heightmap's own
    /// extent decides otherwise).
    pub area: f32,
    /// World seed: trees, and generated terrain unless its own seed is given.
    pub seed: u64,
    /// Side of a fine tile, metres.
    pub tile_size: f32,
    /// Fine tiles along each side of a coarse tile.
    pub group: u32,
    /// Longitude and latitude (degrees) of the world's low corner on the globe.
    pub origin: [f64; 2],
    /// Canopy trees per hectare; `None` keeps the species' own spacing.
    pub density: Option<f32>,
    /// Instance-cache budget, MiB, shared among the species.
    pub budget_mb: u32,
}

/// A species of a world.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum SpeciesEntry {
    /// A bundled species by name: oak, birch, spruce, pine or hazel.
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
        /// Terrain seed; `None` uses the world seed.
        #[serde(default)]
        seed: Option<u64>,
        /// Diamond-square's roughness (0 to 1).
        #[serde(default = "default_roughness")]
        roughness: f32,
        /// Relief, as a share of the world's side.
        #[serde(default = "default_relief")]
        relief: f32,
        /// Gaussian smoothing, in samples (0 for none).
        #[serde(default = "default_smoothing")]
        smoothing: f32,
        /// Hydraulic erosion after smoothing, as rain droplets per sample (0 for none, up
        /// to 4; 1 cuts gullies). Left out of the canonical form when 0, so worlds described
        /// before erosion keep their ids.
        #[serde(default, skip_serializing_if = "is_zero")]
        erosion: f32,
    },
    /// A heightmap uploaded with `POST /heightmaps`.
    Heightmap {
        /// The id the upload returned.
        id: String,
        /// Metres between samples (when the file does not say).
        #[serde(default)]
        spacing: Option<f32>,
        /// Heights of samples 0 and 65535, metres (when the file does not say).
        #[serde(default)]
        height_range: Option<[f32; 2]>,
    },
}

fn default_roughness() -> f32 {
    0.75
}
fn default_relief() -> f32 {
    0.06
}
fn default_smoothing() -> f32 {
    2.0
}
fn is_zero(x: &f32) -> bool {
    *x == 0.0
}
/// Most hydraulic-erosion droplets per sample.
pub const MAX_EROSION: f32 = 4.0;

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
            area: 800.0,
            seed: 1,
            tile_size: 250.0,
            group: 4,
            origin: [8.54, 47.37],
            density: None,
            budget_mb: 32,
        }
    }
}

/// The names of the bundled species, in their order.
pub const BUNDLED_SPECIES: [&str; 5] = ["oak", "birch", "spruce", "pine", "hazel"];

impl WorldDescription {
    /// Parses and checks a description: JSON of at most [`MAX_DESCRIPTION_BYTES`], no field
    /// unknown, every number in its range. The error says which field is wrong and why.
    pub fn parse(bytes: &[u8]) -> Result<WorldDescription, ApiError> {
        if bytes.len() > MAX_DESCRIPTION_BYTES {
            return Err(ApiError::too_large(format!(
                "a world description of {} bytes is over the limit of {MAX_DESCRIPTION_BYTES}",
                bytes.len()
            )));
        }
        let invalid = |m: String| {
            ApiError::bad_request(
                "bad_description",
                format!("the world description is not valid: {m}"),
            )
        };
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
    pub fn check(&self) -> Result<(), ApiError> {
        let bad = |m: String| Err(ApiError::bad_request("bad_description", m));
        if self.species.len() > MAX_SPECIES {
            return bad(format!(
                "{} species: a world has at most {MAX_SPECIES}",
                self.species.len()
            ));
        }
        for s in &self.species {
            if let SpeciesEntry::Bundled(name) = s
                && !BUNDLED_SPECIES.contains(&name.as_str())
            {
                return Err(ApiError::bad_request(
                    "unknown_species",
                    format!(
                        "unknown species '{}': the bundled ones are {}; or give a species file inline as {{\"file\": \"...\"}}",
                        name.chars().take(80).collect::<String>(),
                        BUNDLED_SPECIES.join(", ")
                    ),
                ));
            }
        }
        if !(self.area >= 10.0 && self.area <= MAX_SIDE) {
            return bad(format!(
                "area {}: expected a side from 10 to {MAX_SIDE} metres",
                self.area
            ));
        }
        if !(self.tile_size >= 10.0 && self.tile_size <= 5_000.0) {
            return bad(format!(
                "tile_size {}: expected 10 to 5000 metres",
                self.tile_size
            ));
        }
        if !(1..=64).contains(&self.group) {
            return bad(format!("group {}: expected 1 to 64", self.group));
        }
        let [lon, lat] = self.origin;
        if !(lon.abs() <= 180.0 && lat.abs() <= 90.0) {
            return bad(format!(
                "origin [{lon}, {lat}]: expected longitude and latitude in degrees"
            ));
        }
        if let Some(d) = self.density
            && !(d > 0.0 && d <= 10_000.0)
        {
            return bad(format!(
                "density {d}: expected 0 < trees per hectare <= 10000"
            ));
        }
        if !(1..=128).contains(&self.budget_mb) {
            return bad(format!("budget_mb {}: expected 1 to 128", self.budget_mb));
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
            } => {
                if !WorldId::is_valid(id) {
                    return bad(format!(
                        "heightmap id '{}': expected the id POST /heightmaps returned",
                        id.chars().take(80).collect::<String>()
                    ));
                }
                if let Some(s) = spacing
                    && !(*s > 0.0 && *s <= 1_000.0)
                {
                    return bad(format!("terrain spacing {s}: expected 0 to 1000 metres"));
                }
                if let Some([lo, hi]) = height_range
                    && !(lo.is_finite() && hi.is_finite() && lo < hi && (hi - lo) <= 20_000.0)
                {
                    return bad(format!(
                        "terrain height_range [{lo}, {hi}]: expected low < high, within 20000 m"
                    ));
                }
            }
        }
        Ok(())
    }

    /// The world's species, parsed: the bundled ones by name (all five for none), inline
    /// files as written with their grammars (a mistake in one is a 400 with its line and
    /// column); an inline species never reads a file.
    ///
    /// ```
    /// use sylva_server::WorldDescription;
    /// let d = WorldDescription::parse(br#"{"species": ["pine", "oak"]}"#)?;
    /// let names: Vec<String> = d.species()?.into_iter().map(|s| s.name).collect();
    /// assert_eq!(names, ["pine", "oak"]);
    /// # Ok::<(), sylva_server::ApiError>(())
    /// ```
    pub fn species(&self) -> Result<Vec<Species>, ApiError> {
        let bundled = sylva::presets::species().map_err(|e| ApiError::internal(e.to_string()))?;
        if self.species.is_empty() {
            return Ok(bundled);
        }
        self.species
            .iter()
            .enumerate()
            .map(|(k, entry)| match entry {
                SpeciesEntry::Bundled(name) => BUNDLED_SPECIES
                    .iter()
                    .position(|b| b == name)
                    .map(|i| bundled[i].clone())
                    .ok_or_else(|| {
                        ApiError::bad_request(
                            "unknown_species",
                            format!("unknown species '{name}'"),
                        )
                    }),
                SpeciesEntry::Inline { file, grammar } => {
                    let name = format!("species[{k}]");
                    Species::parse_detached(file, Path::new(&name), grammar.as_deref())
                        .map_err(|e| ApiError::bad_request("bad_species", e.to_string()))
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
    fn mistakes_name_their_field() {
        for (json, field) in [
            (r#"{"area": 0}"#, "area"),
            (r#"{"area": 1e9}"#, "area"),
            (r#"{"tile_size": 1}"#, "tile_size"),
            (r#"{"group": 0}"#, "group"),
            (r#"{"origin": [200, 0]}"#, "origin"),
            (r#"{"budget_mb": 100000}"#, "budget_mb"),
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
            assert_eq!(e.status.as_u16(), 400, "{json}");
            assert!(e.message.contains(field), "{json}: {}", e.message);
        }
    }

    #[test]
    fn unknown_species_and_oversize_are_refused() {
        let e = WorldDescription::parse(br#"{"species": ["baobab"]}"#).unwrap_err();
        assert_eq!((e.status.as_u16(), e.code), (400, "unknown_species"));
        let big = vec![b' '; MAX_DESCRIPTION_BYTES + 1];
        assert_eq!(
            WorldDescription::parse(&big).unwrap_err().status.as_u16(),
            413
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
