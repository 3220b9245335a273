//! The world `forest` and `tiles` share: species, terrain (generated or the user's), size,
//! density, paint masks.

use std::path::{Path, PathBuf};
use std::time::Duration;

use clap::Args;
use sylva::base::file::FileError;
use sylva::forest::{ForestBuilder, ForestConfig, Rect, Species};
use sylva::terrain::glam::Vec2;
use sylva::terrain::{HeightRange, Heightmap};

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
    /// Your own heightmap: a 16-bit PNG, or a square RAW of little-endian 16-bit samples
    /// (.raw or .r16, with --spacing and --height-range).
    #[arg(long, value_name = "HEIGHTS")]
    terrain: Option<PathBuf>,
    /// Metres between the heightmap's samples (for --terrain).
    #[arg(long, value_name = "M")]
    spacing: Option<f32>,
    /// Heights of the samples 0 and 65535, in metres (for --terrain).
    #[arg(long, value_name = "LO,HI", value_parser = parse_pair::<f32>)]
    height_range: Option<(f32, f32)>,
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
}

/// A world made from its flags.
pub(crate) struct World {
    pub(crate) builder: ForestBuilder,
    pub(crate) map: Heightmap,
    pub(crate) region: Rect,
    pub(crate) side: f32,
    pub(crate) seed: u64,
    pub(crate) hero_time: Duration,
}

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
        if let Some(a) = self.area.filter(|a| !(*a > 0.0 && *a <= 20_000.0)) {
            return Err(Failure::usage(format!(
                "--area {a}: expected a side length from 0 to 20000 metres"
            )));
        }
        if let Some(n) = self.trees.filter(|n| *n == 0 || *n > 10_000_000) {
            return Err(Failure::usage(format!(
                "--trees {n}: expected 1 to 10000000"
            )));
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
            Some(file) => Some(read_terrain(file, self.spacing, self.height_range)?),
            None => None,
        };
        let mut config = ForestConfig::new(species);
        config.seed = self.seed;
        config.budget = budget;
        config.all_ages = self.year.is_some();
        let (builder, hero_time) = phase(quiet, "building instance caches from hero trees", || {
            ForestBuilder::new(config)
        });
        let mut builder = builder?;
        if let Some(d) = self.density {
            builder.density_mut().patch = (10_000.0 / d).sqrt();
        }
        let (map, side) = match user_map {
            Some(map) => {
                let side = map.spacing() * (map.size() - 1) as f32;
                (map, side)
            }
            None => {
                let side = match (self.area, self.trees) {
                    (Some(a), _) => a,
                    (None, Some(n)) => builder.side_for_canopy_trees(n),
                    (None, None) => 800.0,
                };
                let (map, _) = phase(quiet, "generating terrain", || {
                    sylva::presets::terrain(self.seed, side)
                });
                (map?, side)
            }
        };
        if let Some(dir) = &self.paint {
            builder = sylva::paint::with_masks(&builder, dir, &map)?;
        }
        let region = Rect::new(Vec2::ZERO, Vec2::splat(side));
        if let Some(year) = self.year {
            builder = builder_at_year(&builder, region, year, quiet)?;
        }
        Ok(World {
            builder,
            map,
            region,
            side,
            seed: self.seed,
            hero_time,
        })
    }
}

/// Reads a user's heightmap: a 16-bit PNG, or a square RAW of little-endian 16-bit samples.
fn read_terrain(
    file: &Path,
    spacing: Option<f32>,
    range: Option<(f32, f32)>,
) -> Result<Heightmap, Failure> {
    // A 8193 x 8193 map of 16-bit samples is 134 MB; refuse files well beyond any map.
    const MAX_BYTES: u64 = 512 << 20;
    let name = file.display();
    let size = std::fs::metadata(file).map_err(FileError::at(file))?.len();
    if size > MAX_BYTES {
        return Err(Failure::job(format!(
            "{name}: {size} bytes is more than the limit of {MAX_BYTES}"
        )));
    }
    let fallback = match (range, spacing) {
        (Some((min, max)), Some(s)) => Some((HeightRange { min, max }, s)),
        _ => None,
    };
    let raw = matches!(
        file.extension().and_then(|e| e.to_str()),
        Some("raw" | "r16")
    );
    let map = if raw {
        let (range, spacing) = fallback.ok_or_else(|| {
            Failure::usage(format!(
                "{name}: a RAW heightmap needs --height-range LO,HI and --spacing M"
            ))
        })?;
        let bytes = std::fs::read(file).map_err(FileError::at(file))?;
        Heightmap::from_raw16(&bytes, range, spacing)
    } else {
        let f = std::fs::File::open(file).map_err(FileError::at(file))?;
        Heightmap::read_png16(std::io::BufReader::new(f), fallback)
    };
    let map = map.map_err(|e| Failure::job(format!("{name}: {e}")))?;
    let side = map.spacing() * (map.size() - 1) as f32;
    if !(side > 10.0 && side <= 20_000.0) {
        return Err(Failure::job(format!(
            "{name}: a {} x {} map at {} m spacing is {side} m across; expected 10 to 20000 m",
            map.size(),
            map.size(),
            map.spacing()
        )));
    }
    Ok(map)
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
