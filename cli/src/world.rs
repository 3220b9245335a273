//! The world `forest`, `tiles` and `pack` share, from their flags: species, terrain
//! (generated or the user's), size, density, paint masks, year. The flags are read here; the
//! world is assembled by the world layer (`sylva::world`), as the viewer's and the server's.

use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::Duration;

use clap::Args;
use indicatif::ProgressBar;
use sylva::forest::{Constraints, ForestBuilder, Rect, SitingReport};
use sylva::terrain::Heightmap;
use sylva::terrain::dem::{ElevationModel, ReadOptions, Window};
use sylva::world::limits::{
    DEFAULT_SIDE, MAX_DENSITY, MAX_SIDE, MAX_SPECIES, MAX_TREES, check_budget_mb,
};
use sylva::world::{Fit, Ground, Progress, Project, Stage, WorldBuilder, WorldError};

use crate::Failure;
use crate::progress::{bar, phase, spinner};

/// The world's flags.
#[derive(Debug, Args)]
pub(crate) struct WorldArgs {
    /// Side of the square world in metres (default 800).
    #[arg(long, value_name = "METRES", conflicts_with_all = ["trees", "terrain"])]
    area: Option<f32>,
    /// About this many canopy trees: the world's side follows from the patch size.
    #[arg(long, value_name = "N", conflicts_with = "terrain")]
    trees: Option<usize>,
    /// Your own elevation model, of any size: GeoTIFF, SRTM .hgt, ESRI ASCII grid (.asc),
    /// 16-bit PNG, or RAW of little-endian 16-bit samples (.raw or .r16, with --height-range,
    /// and --raw-size unless square). Georeferencing gives the spacing; nodata is filled. A
    /// forest takes the model's middle 1000 m (and says which window: --crop names another,
    /// `forest --whole` writes the whole model as 3D Tiles); a tileset takes it whole, up to
    /// 20 km a side.
    #[arg(long, value_name = "HEIGHTS")]
    terrain: Option<PathBuf>,
    /// Metres between the model's samples (for --terrain): overrides the file's.
    #[arg(long, value_name = "M")]
    spacing: Option<f32>,
    /// Width and height of a RAW model (for --terrain).
    #[arg(long, value_name = "W,H", value_parser = parse_pair::<usize>)]
    raw_size: Option<(usize, usize)>,
    /// Use this window of the model (for --terrain) instead of the default region: its
    /// north-west sample's column and row, then its width and height in samples.
    #[arg(long, value_name = "COL,ROW,W,H")]
    crop: Option<Window>,
    /// Heights of the samples 0 and 65535, in metres (for --terrain).
    #[arg(long, value_name = "LO,HI", value_parser = parse_pair::<f32>)]
    height_range: Option<(f32, f32)>,
    /// Steepest ground with trees, in degrees.
    #[arg(long, value_name = "DEGREES", default_value_t = 35.0)]
    max_slope: f32,
    /// No trees below this terrain height, in metres (a shore, a valley floor).
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    min_height: Option<f32>,
    /// No trees above this terrain height, in metres (a treeline).
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    max_height: Option<f32>,
    /// Canopy trees per hectare (sets the patch size).
    #[arg(long, value_name = "TREES_PER_HA")]
    density: Option<f32>,
    /// A species file or a bundled species by name (oak, birch, spruce, pine, hazel, fir,
    /// larch, beech, sycamore, aspen, alder); repeat for several (default: oak, birch,
    /// spruce, pine and hazel).
    #[arg(long, value_name = "FILE")]
    species: Vec<PathBuf>,
    /// Instance-cache budget in MiB, shared among the species (default: sized to the
    /// forest, 2 KiB a canopy tree from 6 MiB up to 32 MiB, which the default forest
    /// reaches; at least one hero tree per species and form).
    #[arg(long, value_name = "MB")]
    budget_mb: Option<usize>,
    /// World seed.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Grow a painted forest: the masks in this folder (as `sylva paint` and the viewer save
    /// them) decide where each species grows.
    #[arg(long, value_name = "MASKS_DIR")]
    paint: Option<PathBuf>,
    /// Draw the forest as it stands in year N of a forest over time: grown from bare ground
    /// year by year (`sylva succession`'s defaults, this seed), trees of every age, dead
    /// standing trees, broken tops and fallen trees, instead of placed at two ages.
    #[arg(long, value_name = "N", conflicts_with = "paint")]
    year: Option<u32>,
    /// The day of the year to draw the forest on, 1 to 365, or spring (day 135), summer
    /// (200), autumn (290) or winter (20): each species' leaves as that day has them (spring
    /// flush, autumn colour, bare deciduous crowns) and snow in winter. The trees stand in
    /// the same places every day. Summer by default.
    #[arg(long, value_name = "DAY", value_parser = season_day)]
    season: Option<f32>,
    /// A project folder as the viewer's editor saves it: its world.json (species, terrain,
    /// area, seed, density: the description `sylva serve` takes), the elevation model it
    /// names, and its painted masks if it has them.
    #[arg(
        long,
        value_name = "DIR",
        conflicts_with_all = ["area", "trees", "terrain", "species", "seed", "density", "paint", "budget_mb"]
    )]
    project: Option<PathBuf>,
}

/// A world made from its flags.
pub(crate) struct BuiltWorld {
    pub(crate) builder: ForestBuilder,
    pub(crate) map: Heightmap,
    pub(crate) region: Rect,
    pub(crate) side: f32,
    pub(crate) seed: u64,
    pub(crate) hero_time: Duration,
    /// What the terrain made of the candidate tree spots.
    pub(crate) siting: SitingReport,
}

/// `--budget-mb`'s bytes: an error outside the range every front end checks
/// ([`check_budget_mb`]).
pub(crate) fn budget_bytes(mb: usize) -> Result<usize, Failure> {
    check_budget_mb(mb as u64).map_err(|e| Failure::usage(format!("--budget-mb {e}")))?;
    Ok(mb << 20)
}

/// Parses `A,B`.
pub(crate) fn parse_pair<T: std::str::FromStr>(v: &str) -> Result<(T, T), String> {
    v.split_once(',')
        .and_then(|(a, b)| Some((a.trim().parse().ok()?, b.trim().parse().ok()?)))
        .ok_or_else(|| format!("'{v}': expected two numbers, A,B"))
}

/// A world layer's error as the command's failure: a setting or file the user gave is a
/// usage mistake (exit status 2), a failure to make the world the job's (1).
pub(crate) fn failure(e: WorldError) -> Failure {
    match e {
        WorldError::Invalid(_) | WorldError::NoSpacing { .. } => Failure::usage(e.to_string()),
        _ => Failure::job(e.to_string()),
    }
}

/// The world layer's stages as spinners and a bar of years on stderr; keeps how long the
/// hero trees took.
struct Bars {
    hidden: bool,
    spinner: Mutex<Option<ProgressBar>>,
    years: Mutex<Option<ProgressBar>>,
    hero_time: Mutex<Duration>,
}

impl Bars {
    fn new(hidden: bool) -> Bars {
        Bars {
            hidden,
            spinner: Mutex::new(None),
            years: Mutex::new(None),
            hero_time: Mutex::new(Duration::ZERO),
        }
    }
}

impl Progress for Bars {
    fn begin(&self, stage: Stage) {
        // Years count on a bar of their own; other stages spin.
        if stage != Stage::Years {
            let bar = spinner(self.hidden, stage.describe());
            *self.spinner.lock().unwrap_or_else(|p| p.into_inner()) = Some(bar);
        }
    }

    fn end(&self, stage: Stage, elapsed: Duration) {
        if let Some(bar) = self
            .spinner
            .lock()
            .unwrap_or_else(|p| p.into_inner())
            .take()
        {
            bar.finish_and_clear();
        }
        if let Some(bar) = self.years.lock().unwrap_or_else(|p| p.into_inner()).take() {
            bar.finish_and_clear();
        }
        if stage == Stage::HeroTrees {
            *self.hero_time.lock().unwrap_or_else(|p| p.into_inner()) = elapsed;
        }
    }

    fn years(&self, done: u32, total: u32) {
        let mut years = self.years.lock().unwrap_or_else(|p| p.into_inner());
        years
            .get_or_insert_with(|| bar(self.hidden, u64::from(total), Stage::Years.describe()))
            .set_position(u64::from(done));
    }
}

impl WorldArgs {
    /// Builds the caches, the terrain and, with --paint, the painted builder. Flags and the
    /// user's files are checked first, so a mistake is reported before seconds of hero
    /// trees. A model given with --terrain is taken as `fit` says unless --crop names a
    /// window. `hidden` hides progress (--stats, --quiet); `quiet` also the notes on what was
    /// made of a model and why a forest is thin (--quiet: --stats keeps them, on stderr).
    pub(crate) fn world(&self, hidden: bool, quiet: bool, fit: Fit) -> Result<BuiltWorld, Failure> {
        if let Some(a) = self.area.filter(|a| !(*a > 0.0 && *a <= MAX_SIDE)) {
            return Err(Failure::usage(format!(
                "--area {a}: expected a side length from 0 to {MAX_SIDE} metres"
            )));
        }
        if let Some(n) = self.trees.filter(|n| *n == 0 || *n > MAX_TREES) {
            return Err(Failure::usage(format!(
                "--trees {n}: expected 1 to {MAX_TREES}"
            )));
        }
        if let Some(d) = self.density.filter(|d| !(*d > 0.0 && *d <= MAX_DENSITY)) {
            return Err(Failure::usage(format!(
                "--density {d}: expected 0 < trees per hectare <= {MAX_DENSITY}"
            )));
        }
        let constraints = self.constraints()?;
        let bars = Bars::new(hidden);
        let (recipe, ground) = match &self.project {
            Some(dir) => {
                let project = Project::read(dir).map_err(failure)?;
                // The ground first: a missing model is reported before seconds of hero trees.
                let ground = project.ground().map_err(failure)?;
                self.tell(&ground, &project.folder.display().to_string(), quiet, false);
                let recipe = project
                    .description
                    .world_builder()
                    .map_err(failure)?
                    .with_masks(project.masks());
                (recipe, Some(ground))
            }
            None => {
                if self.species.len() > MAX_SPECIES {
                    return Err(Failure::usage(format!(
                        "{} --species: a world has at most {MAX_SPECIES}",
                        self.species.len()
                    )));
                }
                let species = if self.species.is_empty() {
                    sylva::presets::species()?
                } else {
                    self.species
                        .iter()
                        .map(sylva::presets::named_or_file)
                        .collect::<Result<Vec<_>, _>>()?
                };
                let ground = match &self.terrain {
                    Some(file) => Some(self.model_ground(file, fit, hidden, quiet)?),
                    None => None,
                };
                let mut recipe = WorldBuilder::new(species)
                    .with_seed(self.seed)
                    .with_density(self.density)
                    .with_masks(self.paint.clone());
                recipe.budget = self.budget_mb.map(budget_bytes).transpose()?;
                (recipe, ground)
            }
        };
        let recipe = recipe
            .with_constraints(constraints)
            .with_year(self.year)
            .with_season(self.season);
        recipe.check().map_err(failure)?;
        // The budget follows the forest's canopy trees (`WorldBuilder::budget_for`); an
        // area given wins over a tree count, as it does for the side below.
        let trees = self.trees.filter(|_| self.area.is_none());
        let side = self.area.unwrap_or(DEFAULT_SIDE);
        let canopy_trees = recipe.canopy_trees_expected(ground.as_ref(), trees, side);
        let forest = recipe.forest(canopy_trees, &bars).map_err(failure)?;
        let ground = match ground {
            Some(ground) => ground,
            None => {
                let side = match (self.area, self.trees) {
                    (Some(a), _) => a,
                    (None, Some(n)) => forest.side_for_canopy_trees(n),
                    (None, None) => DEFAULT_SIDE,
                };
                let (ground, _) = phase(hidden, "generating terrain", || {
                    Ground::generated(self.seed, side)
                });
                ground.map_err(failure)?
            }
        };
        let world = recipe.finish(forest, ground, &bars).map_err(failure)?;
        let siting = world.siting().map_err(failure)?;
        if !quiet && let Some(note) = siting_note(&siting, &world.forest.config().constraints) {
            eprintln!("{note}");
        }
        let hero_time = *bars.hero_time.lock().unwrap_or_else(|p| p.into_inner());
        Ok(BuiltWorld {
            region: world.region(),
            // A model longer than wide is drawn over its own extent, not the square map's.
            side: world.side(),
            seed: world.seed,
            builder: world.forest,
            map: world.ground.map,
            hero_time,
            siting,
        })
    }

    /// The world's region when the flags alone say it (a generated world of `--area`, or of
    /// the default side): what can be checked before any work. `None` when a model, a tree
    /// count, a painting or a project decides it.
    pub(crate) fn known_region(&self) -> Option<Rect> {
        if self.terrain.is_some()
            || self.project.is_some()
            || self.paint.is_some()
            || (self.trees.is_some() && self.area.is_none())
        {
            return None;
        }
        let side = self.area.unwrap_or(DEFAULT_SIDE);
        Some(Rect::new(
            sylva::terrain::glam::Vec2::ZERO,
            sylva::terrain::glam::Vec2::splat(side),
        ))
    }

    /// Where trees may stand: the slope limit and the height range.
    fn constraints(&self) -> Result<Constraints, Failure> {
        if !(0.0..=90.0).contains(&self.max_slope) {
            return Err(Failure::usage(format!(
                "--max-slope {}: expected 0 to 90 degrees",
                self.max_slope
            )));
        }
        let lowest = self.min_height.unwrap_or(f32::NEG_INFINITY);
        let highest = self.max_height.unwrap_or(f32::INFINITY);
        if lowest.is_nan() || highest.is_nan() || lowest > highest {
            return Err(Failure::usage(format!(
                "--min-height {lowest} --max-height {highest}: expected the lower below the higher"
            )));
        }
        Ok(Constraints::default()
            .with_max_slope_degrees(self.max_slope)
            .with_height_range(lowest, highest))
    }

    /// The ground of `--terrain`'s model: `--crop`'s window, or what `fit` takes; says what
    /// was filled and chosen unless `quiet`.
    fn model_ground(
        &self,
        file: &Path,
        fit: Fit,
        hidden: bool,
        quiet: bool,
    ) -> Result<Ground, Failure> {
        let options = ReadOptions {
            spacing: self.spacing,
            height_range: self.height_range.map(|(lo, hi)| [lo, hi]),
            raw_size: self.raw_size.map(|(w, h)| [w, h]),
        };
        let (ground, _) = phase(hidden, "reading the elevation model", || {
            Ground::read(file, &options, self.crop, fit, "--spacing M")
        });
        let ground = ground.map_err(failure)?;
        // A single file's region can grow to the whole model as tiles; a tileset is whole.
        let whole = fit != Fit::WHOLE;
        self.tell(&ground, &file.display().to_string(), quiet, whole);
        Ok(ground)
    }

    /// Prints what was made of a model, unless `quiet`: cells filled, the window chosen, and
    /// with `whole` the flag that writes the whole model.
    fn tell(&self, ground: &Ground, name: &str, quiet: bool, whole: bool) {
        if quiet {
            return;
        }
        let naming = |window| {
            let crop = sylva::world::crop_flag(window);
            if whole {
                format!("{crop}, --whole writes the whole model as 3D Tiles")
            } else {
                crop
            }
        };
        for note in ground.notes_naming(name, naming) {
            eprintln!("{note}");
        }
    }
}

/// Share of candidate spots refused above which a forest says why it is thin.
const THIN_FOREST_SHARE: f64 = 0.25;

/// Why a thin forest is thin: each constraint that refused spots, with its count, its limit
/// and the flag that moves it; `None` when at most a quarter of the spots were refused.
pub(crate) fn siting_note(report: &SitingReport, constraints: &Constraints) -> Option<String> {
    if report.refused_share() <= THIN_FOREST_SHARE {
        return None;
    }
    let share = |n: u64| 100.0 * n as f64 / report.candidates.max(1) as f64;
    let mut lines = vec![format!(
        "note: {:.0}% of {} candidate tree spots were refused ({} trees placed):",
        100.0 * report.refused_share(),
        report.candidates,
        report.placed
    )];
    let reasons = [
        (
            report.too_steep,
            format!(
                "steeper than {:.0} degrees (--max-slope)",
                constraints.max_slope_degrees
            ),
        ),
        (
            report.above_max_height,
            format!("above {:.0} m (--max-height)", constraints.max_height),
        ),
        (
            report.below_min_height,
            format!("below {:.0} m (--min-height)", constraints.min_height),
        ),
        (report.masked, "refused by the density mask".to_owned()),
    ];
    for (n, why) in reasons.iter().filter(|(n, _)| *n > 0) {
        lines.push(format!("  {n} ({:.0}%) {why}", share(*n)));
    }
    Some(lines.join("\n"))
}

/// Reads an elevation model (not a world's ground: `sylva grow`'s stand samples it); an
/// error when the spacing is neither in the file nor in `options` (it names
/// `spacing_flag`). The count of cells without data is reported unless `quiet`.
pub(crate) fn read_model(
    file: &Path,
    options: &ReadOptions,
    spacing_flag: &str,
    quiet: bool,
) -> Result<ElevationModel, Failure> {
    let name = file.display();
    let model =
        ElevationModel::read(file, options).map_err(|e| Failure::job(format!("{name}: {e}")))?;
    if !model.spacing_from_file && options.spacing.is_none() {
        return Err(failure(WorldError::NoSpacing {
            name: name.to_string(),
            hint: format!("{spacing_flag} M"),
        }));
    }
    if model.nodata > 0 && !quiet {
        eprintln!(
            "{name}: {} of {} cells had no data and were filled from their neighbours",
            model.nodata,
            model.width * model.height
        );
    }
    Ok(model)
}

/// `--season`: a day of the year (1 to 365) or a season's name.
pub(crate) fn season_day(text: &str) -> Result<f32, String> {
    sylva::forest::parse_day(text).ok_or_else(|| {
        format!("'{text}' is not a day of the year (1 to 365) or spring, summer, autumn or winter")
    })
}
