//! The world `forest` and `tiles` share: species, terrain (generated or the user's), size,
//! density, paint masks.

use std::path::{Path, PathBuf};
use std::time::Duration;

use clap::Args;
use sylva::forest::{Constraints, ForestBuilder, ForestConfig, Rect, SitingReport, Species};
use sylva::terrain::Heightmap;
use sylva::terrain::dem::{ElevationModel, ReadOptions, Window};
use sylva::terrain::glam::Vec2;

use sylva_server::project::Project;

use crate::Failure;
use crate::progress::{bar, phase};

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
    /// and --raw-size unless square). Georeferencing gives the spacing; nodata is filled.
    #[arg(long, value_name = "HEIGHTS")]
    terrain: Option<PathBuf>,
    /// Metres between the model's samples (for --terrain): overrides the file's.
    #[arg(long, value_name = "M")]
    spacing: Option<f32>,
    /// Width and height of a RAW model (for --terrain).
    #[arg(long, value_name = "W,H", value_parser = parse_pair::<usize>)]
    raw_size: Option<(usize, usize)>,
    /// Use only this window of the model (for --terrain): its north-west sample's column
    /// and row, then its width and height in samples. For models larger than a world.
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
    /// A species file; repeat for several (default: the five bundled species).
    #[arg(long, value_name = "FILE")]
    species: Vec<PathBuf>,
    /// Instance-cache budget in MiB, shared among the species.
    #[arg(long, value_name = "MB", default_value_t = 32)]
    budget_mb: usize,
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
pub(crate) struct World {
    pub(crate) builder: ForestBuilder,
    pub(crate) map: Heightmap,
    pub(crate) region: Rect,
    pub(crate) side: f32,
    pub(crate) seed: u64,
    pub(crate) hero_time: Duration,
    /// What the terrain made of the candidate tree spots.
    pub(crate) siting: SitingReport,
}

/// Longest side of a world, metres (as `--area`'s limit).
const MAX_WORLD_SIDE: f32 = 20_000.0;

/// Most years one forest over time simulates (`--year`, `sylva succession --years`).
pub(crate) const MAX_YEARS: u32 = 10_000;

/// `--budget-mb`'s bytes: an error for 0 or a size beyond memory's reach.
pub(crate) fn budget_bytes(mb: usize) -> Result<usize, Failure> {
    mb.checked_mul(1 << 20)
        .filter(|&b| b > 0)
        .ok_or_else(|| Failure::usage("--budget-mb must be positive"))
}

/// Parses `A,B`.
pub(crate) fn parse_pair<T: std::str::FromStr>(v: &str) -> Result<(T, T), String> {
    v.split_once(',')
        .and_then(|(a, b)| Some((a.trim().parse().ok()?, b.trim().parse().ok()?)))
        .ok_or_else(|| format!("'{v}': expected two numbers, A,B"))
}

impl WorldArgs {
    /// Builds the caches, the terrain and, with --paint, the painted builder. Flags and the
    /// user's files are checked first, so a mistake is reported before seconds of hero trees.
    pub(crate) fn world(&self, quiet: bool) -> Result<World, Failure> {
        if let Some(d) = self.density.filter(|d| !(*d > 0.0 && *d <= 10_000.0)) {
            return Err(Failure::usage(format!(
                "--density {d}: expected 0 < trees per hectare <= 10000"
            )));
        }
        if let Some(a) = self.area.filter(|a| !(*a > 0.0 && *a <= MAX_WORLD_SIDE)) {
            return Err(Failure::usage(format!(
                "--area {a}: expected a side length from 0 to {MAX_WORLD_SIDE} metres"
            )));
        }
        if let Some(n) = self.trees.filter(|n| *n == 0 || *n > 10_000_000) {
            return Err(Failure::usage(format!(
                "--trees {n}: expected 1 to 10000000"
            )));
        }
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
        if let Some(dir) = &self.project {
            return self.project_world(dir, lowest, highest, quiet);
        }
        let budget = budget_bytes(self.budget_mb)?;
        let species = if self.species.is_empty() {
            sylva::presets::species()?
        } else {
            self.species
                .iter()
                .map(Species::from_file)
                .collect::<Result<Vec<_>, _>>()?
        };
        let user_map = match &self.terrain {
            Some(file) => Some(read_terrain(self, file, quiet)?),
            None => None,
        };
        let mut config = ForestConfig::new(species);
        config.seed = self.seed;
        config.budget = budget;
        self.adjust(&mut config, lowest, highest);
        let (builder, hero_time) = phase(quiet, "building instance caches from hero trees", || {
            ForestBuilder::new(config)
        });
        let mut builder = builder?;
        if let Some(d) = self.density {
            builder.density_mut().patch = (10_000.0 / d).sqrt();
        }
        let (map, extent) = match user_map {
            Some((map, extent)) => (map, extent),
            None => {
                let side = match (self.area, self.trees) {
                    (Some(a), _) => a,
                    (None, Some(n)) => builder.side_for_canopy_trees(n),
                    (None, None) => 800.0,
                };
                let (map, _) = phase(quiet, "generating terrain", || {
                    sylva::presets::terrain(self.seed, side)
                });
                (map?, [side, side])
            }
        };
        self.finish(
            (builder, hero_time),
            (map, extent),
            self.paint.as_deref(),
            self.seed,
            quiet,
        )
    }

    /// What the flags add to a forest's configuration: where trees may stand (the slope
    /// limit, heights from `lowest` to `highest`) and whether trees of every age are drawn.
    fn adjust(&self, config: &mut ForestConfig, lowest: f32, highest: f32) {
        config.all_ages = self.year.is_some();
        config.constraints = Constraints::default()
            .with_max_slope_degrees(self.max_slope)
            .with_height_range(lowest, highest);
    }

    /// The world of `builder` on `map` over `extent`: painted with the masks in `masks`,
    /// drawn in `--year`'s year, its siting reported unless `quiet`.
    fn finish(
        &self,
        (mut builder, hero_time): (ForestBuilder, Duration),
        (map, extent): (Heightmap, [f32; 2]),
        masks: Option<&Path>,
        seed: u64,
        quiet: bool,
    ) -> Result<World, Failure> {
        if let Some(dir) = masks {
            builder = sylva::paint::with_masks(&builder, dir, &map)?;
        }
        let region = Rect::new(Vec2::ZERO, Vec2::new(extent[0], extent[1]));
        if let Some(year) = self.year {
            builder = builder_at_year(&builder, region, year, quiet)?;
        }
        let siting = builder.siting(&map, region)?;
        if !quiet && let Some(note) = siting_note(&siting, &builder.config().constraints) {
            eprintln!("{note}");
        }
        Ok(World {
            builder,
            map,
            region,
            // A model longer than wide is drawn over its own extent, not the square map's.
            side: extent[0].max(extent[1]),
            seed,
            hero_time,
            siting,
        })
    }
}

impl WorldArgs {
    /// The world of a project folder (`--project`), with the flags that say where trees may
    /// stand and which year to draw.
    fn project_world(
        &self,
        dir: &Path,
        lowest: f32,
        highest: f32,
        quiet: bool,
    ) -> Result<World, Failure> {
        let project = Project::read(dir).map_err(|e| Failure::job(e.to_string()))?;
        let description = &project.description;
        // The ground first: a missing model is reported before seconds of hero trees.
        let (ground, _) = phase(quiet, "making the project's terrain", || project.ground());
        let (map, extent) = ground.map_err(|e| Failure::job(e.to_string()))?;
        let (builder, hero_time) = phase(quiet, "building instance caches from hero trees", || {
            description.builder_with(|config| self.adjust(config, lowest, highest))
        });
        let builder =
            builder.map_err(|e| Failure::job(format!("{}: {}", dir.display(), e.message)))?;
        self.finish(
            (builder, hero_time),
            (map, extent),
            project.masks().as_deref(),
            description.seed,
            quiet,
        )
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

/// Reads a user's elevation model of any size (GeoTIFF, SRTM .hgt, ESRI ASCII grid, 16-bit
/// PNG or RAW) onto a square heightmap; answers it with the model's own extent.
fn read_terrain(
    args: &WorldArgs,
    file: &Path,
    quiet: bool,
) -> Result<(Heightmap, [f32; 2]), Failure> {
    let name = file.display();
    let options = ReadOptions {
        spacing: args.spacing,
        height_range: args.height_range.map(|(lo, hi)| [lo, hi]),
        raw_size: args.raw_size.map(|(w, h)| [w, h]),
    };
    let model = read_model(file, &options, args.crop, "--spacing", quiet)?;
    let [x, z] = model.extent();
    if !(x > 10.0 && z > 10.0 && x <= MAX_WORLD_SIDE && z <= MAX_WORLD_SIDE) {
        // The largest window a world holds, about the model's middle.
        let fit = |n: usize, spacing: f32| n.min((MAX_WORLD_SIDE / spacing) as usize + 1);
        let (w, h) = (
            fit(model.width, model.spacing[0]),
            fit(model.height, model.spacing[1]),
        );
        let hint = if x > MAX_WORLD_SIDE || z > MAX_WORLD_SIDE {
            format!(
                "; --crop {},{},{w},{h} takes the middle {:.0} x {:.0} m",
                (model.width - w) / 2,
                (model.height - h) / 2,
                (w - 1) as f32 * model.spacing[0],
                (h - 1) as f32 * model.spacing[1]
            )
        } else {
            String::new()
        };
        return Err(Failure::job(format!(
            "{name}: {} x {} samples at {:.2} x {:.2} m cover {x:.0} x {z:.0} m; a world is 10 to {MAX_WORLD_SIDE:.0} m a side (--spacing sets the samples' distance){hint}",
            model.width, model.height, model.spacing[0], model.spacing[1]
        )));
    }
    let (map, extent) = model
        .to_heightmap()
        .map_err(|e| Failure::job(format!("{name}: {e}")))?;
    Ok((map, extent))
}

/// Reads an elevation model and takes `crop`'s window of it; an error when the spacing is
/// neither in the file nor in `options` (it names `spacing_flag`). The count of cells without data is reported unless
/// `quiet`.
pub(crate) fn read_model(
    file: &Path,
    options: &ReadOptions,
    crop: Option<Window>,
    spacing_flag: &str,
    quiet: bool,
) -> Result<ElevationModel, Failure> {
    let name = file.display();
    let mut model =
        ElevationModel::read(file, options).map_err(|e| Failure::job(format!("{name}: {e}")))?;
    if !model.spacing_from_file && options.spacing.is_none() {
        return Err(Failure::usage(format!(
            "{name}: the file does not say how far apart its samples are: give {spacing_flag} M"
        )));
    }
    if model.nodata > 0 && !quiet {
        eprintln!(
            "{name}: {} of {} cells had no data and were filled from their neighbours",
            model.nodata,
            model.width * model.height
        );
    }
    if let Some(window) = crop {
        model = model
            .crop(window)
            .map_err(|e| Failure::usage(format!("--crop: {name}: {e}")))?;
    }
    Ok(model)
}

/// The builder drawing the forest over time of `region` in `year`, grown from bare ground
/// with `builder`'s species and seed (`sylva forest --year`, `sylva tiles --year`).
pub(crate) fn builder_at_year(
    builder: &ForestBuilder,
    region: Rect,
    year: u32,
    quiet: bool,
) -> Result<ForestBuilder, Failure> {
    if year > MAX_YEARS {
        return Err(Failure::usage(format!(
            "--year {year}: expected 0 to {MAX_YEARS}"
        )));
    }
    let mut forest = builder.succession(region)?;
    let progress = bar(quiet, u64::from(year), "years of the forest over time");
    for _ in 0..year {
        forest.step()?;
        progress.inc(1);
    }
    progress.finish_and_clear();
    Ok(builder.drawing(&forest)?)
}
