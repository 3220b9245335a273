//! Species: a grammar with its generations, turtle settings, colours and canopy size.

use std::path::{Path, PathBuf};

use glam::Vec3;
use sylva_lsys::{GrammarFileError, LSystem};
use sylva_turtle::{Mesh, MeshBuilder, Skeleton, Tropism, TurtleOptions, interpret};

use crate::appearance::{BarkPattern, LeafShape};
use crate::crown_cover::CrownCover;
use crate::error::ForestError;
use crate::ground::{GroundCover, GroundKind};
use crate::life::Life;
use crate::phenology::Phenology;

/// Largest species file read, in bytes: real ones are a few hundred.
pub const MAX_SPECIES_FILE_BYTES: u64 = 1 << 20;

/// A tree species.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct Species {
    /// Name, for reports and exported node names. No default: the name given to [`Species::new`].
    pub name: String,
    /// The grammar. No default: the grammar given to [`Species::new`].
    pub grammar: LSystem,
    /// Generations of a canopy tree. No default: the generations given to [`Species::new`].
    pub generations: u32,
    /// Generations of a seedling (fewer than `generations`).
    /// Default: two fewer than `generations`, at least 1.
    pub seedling_generations: u32,
    /// Turtle and meshing settings, tropism included.
    /// Default: the grammar's ([`TurtleOptions::for_grammar`]) with a `min_radius` of 0.005.
    pub turtle: TurtleOptions,
    /// Bark colour, linear RGB. Default: [0.30, 0.20, 0.12].
    pub bark: [f32; 3],
    /// Leaf colour, linear RGB (multiplied with the leaf texture). Default: [0.18, 0.42, 0.12].
    pub leaf: [f32; 3],
    /// What its leaf cards show. Default: [`LeafShape::Broadleaf`].
    pub leaf_shape: LeafShape,
    /// What its bark texture shows. Default: [`BarkPattern::Furrowed`].
    pub bark_pattern: BarkPattern,
    /// Relative frequency among the forest's species. Default: 1.
    pub weight: f32,
    /// The ground cover near its canopy trees (empty: the forest floor's default mix).
    /// Default: empty.
    pub ground_cover: Vec<GroundCover>,
    /// How it grows with the years, ages, competes for light and seeds: what a forest over
    /// time ([`Succession`](crate::Succession)) runs on. Default: [`Life::default`].
    pub life: Life,
    /// When its leaves come and go and their colours through the year
    /// ([`Species::in_season`]). Default: [`Phenology::default`] (evergreen).
    pub phenology: Phenology,
}

/// Canopy size of a species, as the thesis bounds it and as measured.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Canopy {
    /// The thesis's bound on the canopy's diameter, 2 D L sin(alpha): D generations, L the
    /// longest branch (a chain of segments between branch points), alpha the widest branching
    /// angle, both measured on the skeleton.
    pub bound: f32,
    /// Twice the widest horizontal reach of the skeletons of a few sample trees.
    pub measured: f32,
    /// The mean area (m²) of ground the sample trees' leaves hide, seen straight down, each
    /// card as opaque as its texture ([`LeafShape::opacity`]): 0 for a species without
    /// leaves. A narrow or open crown hides less of the disc its reach spans than a broad
    /// dense one.
    pub cover: f32,
}

impl Canopy {
    /// The tighter of the two: the canopy diameter used for patches and spacing.
    pub fn diameter(&self) -> f32 {
        self.bound.min(self.measured)
    }

    /// Half of [`Canopy::diameter`].
    pub fn radius(&self) -> f32 {
        0.5 * self.diameter()
    }

    /// The diameter of a disc of the crown's cover ([`Canopy::cover`]), no wider than
    /// [`Canopy::diameter`]; the diameter itself for a species without leaves.
    ///
    /// ```
    /// use sylva_forest::Canopy;
    ///
    /// let open = Canopy { bound: 12.0, measured: 10.0, cover: 25.0 * std::f32::consts::PI };
    /// assert!((open.cover_diameter() - 10.0).abs() < 1e-4);
    /// let leafless = Canopy { cover: 0.0, ..open };
    /// assert_eq!(leafless.cover_diameter(), 10.0);
    /// ```
    pub fn cover_diameter(&self) -> f32 {
        let disc = 2.0 * (self.cover / std::f32::consts::PI).sqrt();
        if disc > 0.0 {
            disc.min(self.diameter())
        } else {
            self.diameter()
        }
    }
}

impl Species {
    /// A species from a grammar, with default colours and turtle settings: the grammar's
    /// dialect's symbols, and for a vlab model its surfaces and contours
    /// ([`TurtleOptions::for_grammar`]).
    pub fn new(name: impl Into<String>, grammar: LSystem, generations: u32) -> Self {
        Species {
            name: name.into(),
            turtle: TurtleOptions::for_grammar(&grammar).with_min_radius(0.005),
            grammar,
            generations,
            seedling_generations: generations.saturating_sub(2).max(1),
            bark: [0.30, 0.20, 0.12],
            leaf: [0.18, 0.42, 0.12],
            leaf_shape: LeafShape::Broadleaf,
            bark_pattern: BarkPattern::Furrowed,
            weight: 1.0,
            ground_cover: Vec::new(),
            life: Life::default(),
            phenology: Phenology::default(),
        }
    }

    /// The species as it looks on `day` of the year: its leaves' colour that day, its
    /// cards as many ([`TurtleOptions::leaf_keep`]) and as large as the day has, and snow
    /// on its bark (and on an evergreen's needles) in winter ([`crate::snow`]). Its shape,
    /// canopy and life are the same, so a forest stands in the same places all year.
    ///
    /// ```
    /// let mut oak = sylva_forest::Species::from_preset("sylva-oak", 4)?;
    /// oak.phenology.evergreen = false;
    /// let winter = oak.in_season(20.0);
    /// assert_eq!(winter.turtle.leaf_keep, 0.0);
    /// assert!(winter.bark[0] > oak.bark[0]); // snow on the branches
    /// assert_eq!(oak.in_season(200.0).leaf, oak.leaf);
    /// # Ok::<(), sylva_forest::ForestError>(())
    /// ```
    #[must_use]
    pub fn in_season(&self, day: f32) -> Species {
        let mut s = self.clone();
        let leaves = self.phenology.leaves(day, self.leaf);
        // Snow whitens the wood and an evergreen's needles; a shader that knows which way a
        // surface faces puts it on the upper sides only (the exports' `_PHENOLOGY`).
        let white = crate::snow(day);
        let snowy = |c: [f32; 3], amount: f32| c.map(|x| x + (0.85 - x) * amount * white);
        s.leaf = if self.phenology.evergreen {
            snowy(leaves.colour, 0.35)
        } else {
            leaves.colour
        };
        s.bark = snowy(self.bark, 0.5);
        s.turtle.leaf_keep = self.turtle.leaf_keep.min(leaves.share);
        s.turtle.leaf_size = self.turtle.leaf_size.map(|x| x * leaves.size);
        s
    }

    /// A species from a bundled preset, with its published angle and tropism. Tropism bends
    /// each hero's branches by their absolute direction; an instance reused elsewhere keeps
    /// the bend it had in its hero, which approximates, as in the Kenwood paper.
    pub fn from_preset(name: &str, generations: u32) -> Result<Self, ForestError> {
        let p = sylva_lsys::preset(name)
            .ok_or_else(|| ForestError::UnknownPreset { name: name.into() })?;
        let mut s = Species::new(name, p.lsystem()?, generations);
        s.turtle = s.turtle.with_angle(p.angle as f32);
        s.turtle.tropism = TurtleOptions::for_preset(p).tropism;
        Ok(s)
    }

    /// One tree of the species derived for `generations` from `seed` and meshed with its
    /// turtle settings: bark and leaf cards, with wind data, as a forest's trees are drawn.
    ///
    /// ```
    /// let oak = sylva_forest::Species::from_preset("sylva-oak", 4)?;
    /// let mesh = oak.mesh(4, 1)?;
    /// assert!(mesh.triangle_count() > 100);
    /// assert_eq!(mesh.vertices, oak.mesh(4, 1)?.vertices);
    /// # Ok::<(), sylva_forest::ForestError>(())
    /// ```
    pub fn mesh(&self, generations: u32, seed: u64) -> Result<Mesh, ForestError> {
        let mut builder = MeshBuilder::new(&self.turtle);
        self.draw_into(generations, seed, &mut builder)?;
        Ok(builder.finish())
    }

    /// Derives its tree at `generations` from `seed` and has the turtle draw it into `sink`.
    fn draw_into(
        &self,
        generations: u32,
        seed: u64,
        sink: &mut impl sylva_turtle::GeometrySink,
    ) -> Result<(), ForestError> {
        let word = self
            .grammar
            .derive(generations, seed)
            .and_then(|w| self.grammar.interpretation(&w, seed))
            .map_err(|source| ForestError::Derive {
                species: self.name.clone(),
                source,
            })?;
        interpret(&word, &self.turtle, sink).map_err(|source| ForestError::Turtle {
            species: self.name.clone(),
            source,
        })?;
        Ok(())
    }

    /// Measures the canopy on three sample trees (seeds 0 to 2): their skeletons, and the
    /// ground their leaves hide.
    pub fn canopy(&self) -> Result<Canopy, ForestError> {
        let (mut longest, mut widest, mut reach, mut cover) = (0.0f32, 0.0f32, 0.0f32, 0.0f32);
        for seed in 0..3 {
            let mut crown = CrownCover::new(self.leaf_shape.opacity());
            self.draw_into(self.generations, seed, &mut crown)?;
            cover += crown.area() / 3.0;
            let skeleton = crown.skeleton;
            reach = reach.max(skeleton.horizontal_extent());
            // A branch runs from one branch point to the next: chains of bones whose parent
            // has no other child. L is the longest such chain.
            let mut children = vec![0u32; skeleton.bones.len()];
            for b in &skeleton.bones {
                if let Some(p) = b.parent {
                    children[p as usize] += 1;
                }
            }
            let mut chain = vec![0.0f32; skeleton.bones.len()];
            for (i, bone) in skeleton.bones.iter().enumerate() {
                let dir = bone.end - bone.start;
                let parent = bone
                    .parent
                    .and_then(|p| skeleton.bones.get(p as usize).map(|b| (p as usize, b)));
                chain[i] = dir.length()
                    + match parent {
                        Some((p, _)) if children[p] == 1 => chain[p],
                        _ => 0.0,
                    };
                longest = longest.max(chain[i]);
                if let Some((_, pb)) = parent {
                    widest = widest.max(angle_between(dir, pb.end - pb.start));
                }
            }
        }
        let bound =
            2.0 * self.generations as f32 * longest * widest.min(std::f32::consts::FRAC_PI_2).sin();
        Ok(Canopy {
            bound: if bound > 0.0 { bound } else { 2.0 * reach },
            measured: (2.0 * reach).max(1e-3),
            cover,
        })
    }

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
    /// (direction x y z and susceptibility); and its life over the years ([`Life`]):
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

impl Species {
    /// The skeleton of its tree at `generations` from `seed`.
    pub(crate) fn sample_skeleton(
        &self,
        generations: u32,
        seed: u64,
    ) -> Result<Skeleton, ForestError> {
        let mut skeleton = Skeleton::default();
        self.draw_into(generations, seed, &mut skeleton)?;
        Ok(skeleton)
    }

    /// The mean skeleton top of `samples` of its trees at `generations`: how tall it is
    /// drawn.
    pub(crate) fn drawn_height(&self, generations: u32, samples: u64) -> Result<f32, ForestError> {
        let mut sum = 0.0;
        for seed in 0..samples {
            sum += skeleton_top(&self.sample_skeleton(generations, seed)?);
        }
        Ok((sum / samples as f32).max(1e-3))
    }
}

/// The top of a skeleton.
pub(crate) fn skeleton_top(skeleton: &Skeleton) -> f32 {
    skeleton
        .bones
        .iter()
        .map(|b| b.end.y.max(b.start.y))
        .fold(0.0f32, f32::max)
}

fn angle_between(a: Vec3, b: Vec3) -> f32 {
    let d = a
        .normalize_or_zero()
        .dot(b.normalize_or_zero())
        .clamp(-1.0, 1.0);
    d.acos()
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
