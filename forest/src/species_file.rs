//! Species files: `key: value` lines read into a [`Species`], each problem reported at its
//! line and column.

use std::path::{Path, PathBuf};

use glam::Vec3;
use sylva_lsys::{GrammarFileError, LSystem};
use sylva_turtle::{Tropism, TurtleOptions};

use crate::appearance::{BarkPattern, LeafShape};
use crate::error::ForestError;
use crate::ground::{GroundCover, GroundKind};
use crate::species::Species;

/// Largest species file read, in bytes: real ones are a few hundred.
pub const MAX_SPECIES_FILE_BYTES: u64 = 1 << 20;

/// Most characters a species' name may have (it names nodes and meshes in every file).
pub const MAX_SPECIES_NAME_CHARS: usize = 256;

impl Species {
    /// Reads a species file: `key: value` lines, `#` comments. Keys: `name`, `grammar` (a
    /// preset name or a grammar file path relative to the species file), `generations`,
    /// `seedling_generations`, `angle`, `step`, `length_unit`, `width`, `width_unit`, `sides`,
    /// `bark` and `leaf` (three numbers, linear RGB), `weight`, `leaves` (symbols the turtle
    /// draws as leaf cards, such as the apices left at the last generation), `leaf_size`
    /// (length and width), `leaf_facing` (0 to 1: how far cards turn to face the sky, see
    /// [`TurtleOptions::leaf_facing`]), `leaf_shape` (`broadleaf`, `lobed`, `serrated`, `needles`, `needle-tuft`, `rounded`, `deltoid`, `palmate` or `pine-shoot`: the card's texture, [`LeafShape`]),
    /// `bark_texture` (`furrowed`, `smooth` or `scaly`), `ground_cover` (what grows on the
    /// floor near its canopy trees: kinds and items per square metre in full light, such as
    /// `grass 1.5, fern 0.4, rock 0.02`; see [`GroundKind`]), `root_flare` (0 to 3: how much wider
    /// than the trunk its base flares, see [`TurtleOptions::root_flare`]), `branch_collar` (0
    /// to 1: how much a branch swells where it leaves its parent, see
    /// [`TurtleOptions::branch_collar`]), `curve_steps` (1 to 8: pieces a thick stem is drawn
    /// in so the tropism curves it, see [`TurtleOptions::curve_steps`]) and `tropism`
    /// (direction x y z and susceptibility); and its life over the years ([`Life`](crate::Life)):
    /// `max_height` (metres), `growth_rate` (per year) and `growth_shape` (its
    /// Chapman-Richards height curve), `max_age` and `maturity_age` (years),
    /// `shade_tolerance` (0 a pioneer, 1 tolerant), `dispersal` (mean seed distance, metres),
    /// `seeds_per_year` and `leaf_area_index`. Errors name the file, line and column;
    /// errors inside the grammar file name that file.
    ///
    /// ```no_run
    /// let oak = sylva_forest::Species::from_file("oak.species").unwrap();
    /// ```
    pub fn from_file(path: impl AsRef<Path>) -> Result<Self, ForestError> {
        let path = path.as_ref();
        let text = sylva_base::text_file::read(path, MAX_SPECIES_FILE_BYTES)?;
        Self::parse_file(&text, path)
    }

    /// Parses species-file text; `path` names the file in errors and anchors relative paths.
    pub fn parse_file(text: &str, path: &Path) -> Result<Self, ForestError> {
        Self::parse_species(text, path, None)
    }

    /// Parses species-file text that stands on no disk (sent to a server, say): its grammar is
    /// a preset or, whatever name it gives, the grammar text `grammar`; no file is ever read.
    /// `path` names the file in errors.
    ///
    /// ```
    /// use std::path::Path;
    /// use sylva_forest::Species;
    ///
    /// let text = "name: bush\ngrammar: bush.lsys\ngenerations: 3\n";
    /// let grammar = "axiom: A\nA -> F[+A][-A]\n";
    /// let bush = Species::parse_detached(text, Path::new("bush"), Some(grammar))?;
    /// assert_eq!(bush.name, "bush");
    /// // Without the grammar's text, a grammar that is not a preset is an error, not a read.
    /// assert!(Species::parse_detached("grammar: /etc/passwd", Path::new("x"), None).is_err());
    /// # Ok::<(), sylva_forest::ForestError>(())
    /// ```
    pub fn parse_detached(
        text: &str,
        path: &Path,
        grammar: Option<&str>,
    ) -> Result<Self, ForestError> {
        Self::parse_species(text, path, Some(grammar.unwrap_or("")))
    }

    /// Parses species-file text; a grammar that is not a preset is read from the file it names
    /// (`detached` `None`) or is the given text (`Some`, empty when none was given).
    fn parse_species(text: &str, path: &Path, detached: Option<&str>) -> Result<Self, ForestError> {
        // Editors on Windows may start the file with a byte-order mark; it is not text.
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let err = |line: usize, column: usize, message: String| ForestError::SpeciesFile {
            file: path.to_path_buf(),
            line,
            column,
            message,
        };
        let mut fields: Vec<(usize, usize, String, String)> = Vec::new();
        for (n, raw) in text.lines().enumerate() {
            let line = raw.split('#').next().unwrap_or("");
            if line.trim().is_empty() {
                continue;
            }
            let Some((key, value)) = line.split_once(':') else {
                let col = raw.len() - raw.trim_start().len() + 1;
                return Err(err(n + 1, col, "expected 'key: value'".into()));
            };
            let value_col = key.chars().count() + 2 + (value.len() - value.trim_start().len());
            fields.push((
                n + 1,
                value_col,
                key.trim().to_string(),
                value.trim().to_string(),
            ));
        }
        let find = |k: &str| fields.iter().find(|f| f.2 == k);
        let Some((gl, gc, _, grammar_ref)) = find("grammar") else {
            return Err(err(
                1,
                1,
                "missing 'grammar:' (a preset name or a grammar file)".into(),
            ));
        };
        let (grammar, angle, tropism) = match sylva_lsys::preset(grammar_ref) {
            Some(p) => (
                p.lsystem()?,
                Some(p.angle as f32),
                TurtleOptions::for_preset(p).tropism,
            ),
            None if detached.is_some() => {
                let given = detached.unwrap_or("");
                if given.trim().is_empty() {
                    return Err(err(
                        *gl,
                        *gc,
                        format!(
                            "grammar '{grammar_ref}' is not a preset, and no grammar text came with the species"
                        ),
                    ));
                }
                if given.len() > sylva_lsys::MAX_GRAMMAR_BYTES {
                    return Err(err(
                        *gl,
                        *gc,
                        format!(
                            "the grammar text is over {} bytes",
                            sylva_lsys::MAX_GRAMMAR_BYTES
                        ),
                    ));
                }
                // In the dialect the text declares, as a grammar file's.
                let g = given
                    .parse::<LSystem>()
                    .map_err(|error| ForestError::SpeciesFile {
                        file: PathBuf::from(format!("{} (grammar)", path.display())),
                        line: error.location.line,
                        column: error.location.column,
                        message: error.message,
                    })?;
                (g, None, None)
            }
            None => {
                let gpath: PathBuf = path.parent().unwrap_or(Path::new(".")).join(grammar_ref);
                // A vlab model (a folder, or a .l file in one) reads the files beside it.
                let model = gpath.is_dir() || gpath.extension().is_some_and(|e| e == "l");
                let read = if model {
                    LSystem::from_model_dir(&gpath)
                } else {
                    LSystem::from_file(&gpath)
                };
                let g = read.map_err(|e| match e {
                    GrammarFileError::Parse { path, error } => ForestError::SpeciesFile {
                        file: path,
                        line: error.location.line,
                        column: error.location.column,
                        message: error.message,
                    },
                    other => err(*gl, *gc, format!("grammar '{grammar_ref}': {other}")),
                })?;
                (g, None, None)
            }
        };
        let name = find("name").map_or_else(|| grammar_ref.clone(), |f| f.3.clone());
        // A name is copied into every node and mesh name of a file (a 1 MB name made a 50 m
        // forest a 1.24 GB GLB): bounded, said with its line.
        if name.chars().count() > MAX_SPECIES_NAME_CHARS {
            let (l, c) = find("name").map_or((*gl, *gc), |f| (f.0, f.1));
            return Err(err(
                l,
                c,
                format!(
                    "the species' name has {} characters, more than the limit of {MAX_SPECIES_NAME_CHARS}",
                    name.chars().count()
                ),
            ));
        }
        let number = |k: &str, default: f32, min: f32, max: f32| -> Result<f32, ForestError> {
            match find(k) {
                None => Ok(default),
                Some((l, c, _, v)) => match v.parse::<f32>() {
                    Ok(x) if x.is_finite() && x >= min && x <= max => Ok(x),
                    _ => Err(err(
                        *l,
                        *c,
                        format!("{k} must be a number from {min} to {max}, not '{v}'"),
                    )),
                },
            }
        };
        let colour = |k: &str, default: [f32; 3]| -> Result<[f32; 3], ForestError> {
            match find(k) {
                None => Ok(default),
                Some((l, c, _, v)) => {
                    let parts = numbers(v);
                    match parts.as_slice() {
                        [r, g, b] if parts.iter().all(|x| (0.0..=1.0).contains(x)) => {
                            Ok([*r, *g, *b])
                        }
                        _ => Err(err(
                            *l,
                            *c,
                            format!("{k} must be three numbers from 0 to 1, not '{v}'"),
                        )),
                    }
                }
            }
        };
        let generations = number("generations", 5.0, 1.0, 24.0)? as u32;
        let mut s = Species::new(name, grammar, generations);
        s.seedling_generations = number(
            "seedling_generations",
            s.seedling_generations as f32,
            1.0,
            generations as f32,
        )? as u32;
        s.turtle.angle = number("angle", angle.unwrap_or(s.turtle.angle), -360.0, 360.0)?;
        s.turtle.tropism = tropism;
        if let Some((l, c, _, v)) = find("tropism") {
            let parts = numbers(v);
            match parts.as_slice() {
                [x, y, z, e]
                    if parts.iter().all(|p| p.is_finite())
                        && (0.0..=10.0).contains(e)
                        && Vec3::new(*x, *y, *z).length() > 1e-6 =>
                {
                    s.turtle.tropism = Some(Tropism {
                        direction: Vec3::new(*x, *y, *z),
                        susceptibility: *e,
                    });
                }
                _ => {
                    return Err(err(
                        *l,
                        *c,
                        format!(
                            "tropism must be a direction x y z (not zero) and a susceptibility from 0 to 10, not '{v}'"
                        ),
                    ));
                }
            }
        }
        s.turtle.step = number("step", s.turtle.step, 1e-4, 1e4)?;
        s.turtle.length_unit = number("length_unit", s.turtle.length_unit, 1e-6, 1e3)?;
        s.turtle.width = number("width", s.turtle.width, 0.0, 1e3)?;
        s.turtle.width_unit = number("width_unit", s.turtle.width_unit, 0.0, 1e3)?;
        s.turtle.radial_segments =
            number("sides", s.turtle.radial_segments as f32, 3.0, 64.0)? as u32;
        s.bark = colour("bark", s.bark)?;
        s.leaf = colour("leaf", s.leaf)?;
        s.weight = number("weight", 1.0, 0.0, 1e6)?;
        if let Some((l, c, _, v)) = find("evergreen") {
            s.phenology.evergreen = match v.as_str() {
                "yes" | "true" => true,
                "no" | "false" => false,
                _ => {
                    return Err(err(
                        *l,
                        *c,
                        format!("evergreen must be 'yes' or 'no', not '{v}'"),
                    ));
                }
            };
        }
        s.phenology.leaf_out = number("leaf_out", s.phenology.leaf_out, 1.0, 365.0)?;
        s.phenology.leaf_fall = number("leaf_fall", s.phenology.leaf_fall, 1.0, 365.0)?;
        if s.phenology.leaf_fall < s.phenology.leaf_out + 60.0 {
            // One of the two was set (the defaults are 190 days apart).
            let (l, c) = find("leaf_fall")
                .or_else(|| find("leaf_out"))
                .map_or((1, 1), |f| (f.0, f.1));
            return Err(err(
                l,
                c,
                "leaf_fall must be at least 60 days after leaf_out".into(),
            ));
        }
        s.phenology.spring = colour("spring_leaf", s.phenology.spring)?;
        s.phenology.autumn = colour("autumn_leaf", s.phenology.autumn)?;
        if let Some((l, c, _, v)) = find("leaves") {
            for ch in v.chars().filter(|c| !c.is_whitespace()) {
                if matches!(ch, '[' | ']') {
                    return Err(err(*l, *c, "brackets cannot be leaves".into()));
                }
                s.turtle.symbols.set(ch, sylva_turtle::Command::Leaf);
            }
        }
        if let Some((l, c, _, v)) = find("leaf_size") {
            let parts = numbers(v);
            match parts.as_slice() {
                [a, b] if parts.iter().all(|x| x.is_finite() && *x > 0.0 && *x < 1e3) => {
                    s.turtle.leaf_size = [*a, *b]
                }
                _ => {
                    return Err(err(
                        *l,
                        *c,
                        format!("leaf_size must be two positive numbers, not '{v}'"),
                    ));
                }
            }
        }
        s.turtle.leaf_facing = number("leaf_facing", s.turtle.leaf_facing, 0.0, 1.0)?;
        s.turtle.root_flare = number("root_flare", s.turtle.root_flare, 0.0, 3.0)?;
        s.turtle.branch_collar = number("branch_collar", s.turtle.branch_collar, 0.0, 1.0)?;
        s.turtle.curve_steps =
            number("curve_steps", s.turtle.curve_steps as f32, 1.0, 8.0)?.round() as u32;
        if let Some((l, c, _, v)) = find("leaf_shape") {
            s.leaf_shape = LeafShape::from_name(v).ok_or_else(|| {
                err(
                    *l,
                    *c,
                    format!(
                    "leaf_shape must be 'broadleaf', 'lobed', 'serrated', 'needles', 'needle-tuft', 'rounded', 'deltoid', 'palmate' or 'pine-shoot', not '{v}'"
                ),
                )
            })?;
        }
        if let Some((l, c, _, v)) = find("bark_texture") {
            s.bark_pattern = BarkPattern::from_name(v).ok_or_else(|| {
                err(
                    *l,
                    *c,
                    format!("bark_texture must be 'furrowed', 'smooth' or 'scaly', not '{v}'"),
                )
            })?;
        }
        let life = &mut s.life;
        life.max_height = number("max_height", life.max_height, 0.2, 150.0)?;
        life.growth_rate = number("growth_rate", life.growth_rate, 1e-4, 2.0)?;
        life.growth_shape = number("growth_shape", life.growth_shape, 0.2, 5.0)?;
        life.max_age = number("max_age", life.max_age, 2.0, 5000.0)?;
        life.maturity_age = number(
            "maturity_age",
            life.maturity_age.min(life.max_age),
            0.0,
            life.max_age,
        )?;
        life.shade_tolerance = number("shade_tolerance", life.shade_tolerance, 0.0, 1.0)?;
        life.dispersal = number("dispersal", life.dispersal, 0.1, 2000.0)?;
        life.seeds_per_year = number("seeds_per_year", life.seeds_per_year, 0.0, 100.0)?;
        life.leaf_area_index = number("leaf_area_index", life.leaf_area_index, 0.0, 20.0)?;
        if let Some((l, c, _, v)) = find("ground_cover") {
            s.ground_cover = parse_ground_cover(v).map_err(|m| err(*l, *c, m))?;
        }
        for (l, c, k, _) in &fields {
            const KNOWN: &[&str] = &[
                "ground_cover",
                "name",
                "grammar",
                "generations",
                "seedling_generations",
                "angle",
                "step",
                "length_unit",
                "width",
                "width_unit",
                "sides",
                "bark",
                "leaf",
                "weight",
                "leaves",
                "leaf_size",
                "leaf_facing",
                "root_flare",
                "branch_collar",
                "curve_steps",
                "tropism",
                "leaf_shape",
                "bark_texture",
                "max_height",
                "growth_rate",
                "growth_shape",
                "max_age",
                "maturity_age",
                "shade_tolerance",
                "dispersal",
                "seeds_per_year",
                "leaf_area_index",
                "evergreen",
                "leaf_out",
                "leaf_fall",
                "spring_leaf",
                "autumn_leaf",
            ];
            if !KNOWN.contains(&k.as_str()) {
                return Err(err(
                    *l,
                    c.saturating_sub(k.len() + 1).max(1),
                    format!("unknown key '{k}'"),
                ));
            }
        }
        Ok(s)
    }
}

/// The numbers in a species-file value, in order (words that are not numbers are passed
/// over; the caller checks how many there must be).
fn numbers(value: &str) -> Vec<f32> {
    value
        .split_whitespace()
        .filter_map(|word| word.parse().ok())
        .collect()
}

/// A `ground_cover` value: comma-separated `KIND DENSITY` pairs.
fn parse_ground_cover(value: &str) -> Result<Vec<GroundCover>, String> {
    let mut out = Vec::new();
    for part in value.split(',').map(str::trim).filter(|p| !p.is_empty()) {
        let mut words = part.split_whitespace();
        let (Some(name), Some(density), None) = (words.next(), words.next(), words.next()) else {
            return Err(format!(
                "ground_cover must be comma-separated 'KIND DENSITY' pairs (such as 'grass 1.5, fern 0.4'), not '{part}'"
            ));
        };
        let kind = GroundKind::from_name(name).ok_or_else(|| {
            format!(
                "ground_cover: '{name}' is not a kind of cover (grass, fern, shrub, branch or rock)"
            )
        })?;
        let density = density
            .parse::<f32>()
            .ok()
            .filter(|d| d.is_finite() && (0.0..=20.0).contains(d))
            .ok_or_else(|| {
                format!("ground_cover: the density of {name} must be items per square metre from 0 to 20, not '{density}'")
            })?;
        out.push(GroundCover { kind, density });
    }
    Ok(out)
}
