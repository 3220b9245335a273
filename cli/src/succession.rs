//! `sylva succession`: a forest over time. A region grown from bare ground year by year, its
//! statistics per year as CSV and JSON, plots of species shares and self-thinning, and
//! snapshots of chosen years as binary glTF.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

use clap::Args;
use serde::Serialize;
use sylva::base::file::AtomicFile;
use sylva::export::{GltfOptions, write_glb};
use sylva::forest::succession::{
    Succession, SuccessionOptions, YearStats, thinning_phase, thinning_slope,
};
use sylva::forest::{ForestBuilder, ForestConfig, Rect, Species};
use sylva::terrain::Heightmap;
use sylva::terrain::glam::Vec2;

use crate::Failure;
use crate::progress::{bar, ms, peak_rss_mb, phase, print_stats};
use sylva::world::limits::MAX_YEARS;

/// `sylva succession`'s flags.
#[derive(Debug, Args)]
#[command(
    after_help = "With no flags: a 1 km square grown from bare ground for 300 years \
    with the five bundled species, storms, lightning and disease; writes succession/ with \
    succession.csv and succession.json (a row per year: stems per hectare by species, basal \
    area, mean height and diameter, deaths by cause, events), species_shares.png and \
    self_thinning.png. --snapshots 10,50,150,300 adds year_0010.glb and so on; \
    `sylva forest --year N` draws one year as the forest."
)]
pub(crate) struct SuccessionArgs {
    /// Side of the square region in metres.
    #[arg(
        long,
        value_name = "METRES",
        default_value_t = 1000.0,
        conflicts_with = "region"
    )]
    area: f32,
    /// A tile of a larger world instead: the rectangle X0,Z0,X1,Z1 (metres), simulated with
    /// its halo so that tiles simulated apart agree near their borders.
    #[arg(long, value_name = "X0,Z0,X1,Z1", value_parser = parse_rect, allow_hyphen_values = true)]
    region: Option<Rect>,
    /// Years to simulate.
    #[arg(long, default_value_t = 300)]
    years: u32,
    /// Metres simulated beyond the region on every side.
    #[arg(long, value_name = "METRES", default_value_t = SuccessionOptions::default().halo)]
    halo: f32,
    /// Storms per year.
    #[arg(long, default_value_t = SuccessionOptions::default().storm_rate)]
    storm_rate: f32,
    /// Lightning strikes per hectare and year.
    #[arg(long, default_value_t = SuccessionOptions::default().lightning_rate)]
    lightning_rate: f32,
    /// Disease outbreaks per year.
    #[arg(long, default_value_t = SuccessionOptions::default().disease_rate)]
    disease_rate: f32,
    /// Seedlings arriving from beyond the region, per hectare and year.
    #[arg(long, default_value_t = SuccessionOptions::default().seed_rain)]
    seed_rain: f32,
    /// Start from a planted stand instead of bare ground: SPECIES (its name) at
    /// TREES_PER_HA (at most 2500), seed from beyond still arriving.
    #[arg(long, value_name = "SPECIES,TREES_PER_HA", value_parser = parse_planting)]
    plant: Option<(String, f32)>,
    /// A species file; repeat for several (default: the five bundled species).
    #[arg(long, value_name = "FILE")]
    species: Vec<PathBuf>,
    /// World seed.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// The folder to write.
    #[arg(long, value_name = "DIR", default_value = "succession")]
    out: PathBuf,
    /// Years to write as binary glTF (year_NNNN.glb, the region's trees on the default
    /// terrain of the world from the origin to its far corner), comma-separated.
    #[arg(long, value_name = "YEARS", value_delimiter = ',')]
    snapshots: Vec<u32>,
    /// Instance-cache budget in MiB for the snapshots, shared among the species and forms.
    #[arg(long, value_name = "MB", default_value_t = 48)]
    budget_mb: usize,
    /// Print one JSON line of figures instead of the summary.
    #[arg(long)]
    stats: bool,
    /// Print nothing but errors.
    #[arg(long, short)]
    quiet: bool,
}

/// Parses `NAME,DENSITY`.
fn parse_planting(v: &str) -> Result<(String, f32), String> {
    v.split_once(',')
        .and_then(|(name, d)| Some((name.trim().to_string(), d.trim().parse().ok()?)))
        .ok_or_else(|| format!("'{v}': expected SPECIES,TREES_PER_HA, such as spruce,2500"))
}

/// Parses `X0,Z0,X1,Z1`.
fn parse_rect(v: &str) -> Result<Rect, String> {
    let n: Vec<f32> = v
        .split(',')
        .map(|p| p.trim().parse::<f32>())
        .collect::<Result<_, _>>()
        .map_err(|_| format!("'{v}': expected four numbers, X0,Z0,X1,Z1"))?;
    match n.as_slice() {
        [x0, z0, x1, z1] if x1 > x0 && z1 > z0 && n.iter().all(|x| x.is_finite()) => {
            Ok(Rect::new(Vec2::new(*x0, *z0), Vec2::new(*x1, *z1)))
        }
        _ => Err(format!(
            "'{v}': expected X0,Z0,X1,Z1 with X1 > X0 and Z1 > Z0"
        )),
    }
}

/// The figures `--stats` prints.
#[derive(Debug, Serialize)]
struct SuccessionFigures {
    years: u32,
    area_ha: f64,
    /// Trees held at the end, the halo's included.
    stems_held: usize,
    stems_per_ha: f32,
    basal_area_m2_per_ha: f32,
    mean_height_m: f32,
    mean_diameter_cm: f32,
    storms: usize,
    lightning_strikes: usize,
    outbreaks: usize,
    /// Slope of log stems against log mean diameter over the self-thinning years.
    thinning_slope: Option<f32>,
    /// Those years: the densest, and the last while the mean diameter grew.
    thinning_years: [u32; 2],
    simulate_ms: f64,
    ms_per_year: f64,
    peak_rss_mb: f64,
    threads: usize,
}

pub(crate) fn run(args: SuccessionArgs) -> Result<(), Failure> {
    let hidden = args.quiet || args.stats;
    if !(args.area > 0.0 && args.area <= 20_000.0) {
        return Err(Failure::usage(format!(
            "--area {}: expected 0 to 20000 metres",
            args.area
        )));
    }
    if args.years == 0 || args.years > MAX_YEARS {
        return Err(Failure::usage(format!(
            "--years {}: expected 1 to {MAX_YEARS}",
            args.years
        )));
    }
    if let Some(y) = args.snapshots.iter().find(|&&y| y > args.years) {
        return Err(Failure::usage(format!(
            "--snapshots: year {y} is after the last simulated ({})",
            args.years
        )));
    }
    let budget = crate::world::budget_bytes(args.budget_mb)?;
    let species = load_species(&args.species)?;
    let region = args
        .region
        .unwrap_or_else(|| Rect::new(Vec2::ZERO, Vec2::splat(args.area)));
    let options = SuccessionOptions::default()
        .with_seed(args.seed)
        .with_halo(args.halo)
        .with_storm_rate(args.storm_rate)
        .with_lightning_rate(args.lightning_rate)
        .with_disease_rate(args.disease_rate)
        .with_seed_rain(args.seed_rain);
    let names: Vec<String> = species.iter().map(|s| s.name.clone()).collect();
    let mut forest = Succession::new(species.clone(), region, options)?;
    if let Some((name, density)) = &args.plant {
        let k = names.iter().position(|n| n == name).ok_or_else(|| {
            Failure::usage(format!(
                "--plant: no species '{name}' (the species are {})",
                names.join(", ")
            ))
        })?;
        forest.plant(k, *density)?;
    }
    std::fs::create_dir_all(&args.out).map_err(sylva::base::file::FileError::at(&args.out))?;
    // The snapshots' caches and terrain, built only when asked for.
    let snapshots = if args.snapshots.is_empty() {
        None
    } else {
        let config = ForestConfig::new(species)
            .with_seed(args.seed)
            .with_budget(budget)
            .with_all_ages(true);
        let (builder, _) = phase(hidden, "building every age's instance caches", || {
            ForestBuilder::new(config)
        });
        // The default terrain of the world the region is part of: from the origin to its far
        // corner, as `sylva forest --area` would make it.
        if region.min.min_element() < 0.0 {
            return Err(Failure::usage(
                "--snapshots: the world's terrain starts at the origin; give --region in positive coordinates",
            ));
        }
        let side = region.max.max_element();
        let (map, _) = phase(hidden, "generating terrain", || {
            sylva::presets::terrain(args.seed, side)
        });
        Some((builder?, map?))
    };
    let progress = bar(hidden, u64::from(args.years), "years");
    let mut simulated = std::time::Duration::ZERO;
    for _ in 0..args.years {
        let t = Instant::now();
        forest.step()?;
        simulated += t.elapsed();
        progress.inc(1);
        if let Some((builder, map)) = &snapshots
            && args.snapshots.contains(&forest.year())
        {
            write_snapshot(&args.out, &forest, builder, map, region)?;
        }
    }
    progress.finish_and_clear();
    let years = forest.stats();
    write_tables(&args.out, years, &names)?;
    let phase_years = thinning_phase(years);
    let slope = thinning_slope(phase_years);
    crate::plots::species_shares(&args.out.join("species_shares.png"), years, &names)?;
    crate::plots::self_thinning(
        &args.out.join("self_thinning.png"),
        years,
        phase_years,
        slope,
    )?;
    let last = years.last().cloned().unwrap_or_default();
    let count = |kind: &str| {
        years
            .iter()
            .flat_map(|y| &y.events)
            .filter(|e| e.kind() == kind)
            .count()
    };
    let size = region.max - region.min;
    let figures = SuccessionFigures {
        years: args.years,
        area_ha: f64::from(size.x) * f64::from(size.y) / 10_000.0,
        stems_held: forest.stems().len(),
        stems_per_ha: last.stems_per_ha,
        basal_area_m2_per_ha: last.basal_area,
        mean_height_m: last.mean_height,
        mean_diameter_cm: last.mean_diameter,
        storms: count("storm"),
        lightning_strikes: count("lightning"),
        outbreaks: count("disease"),
        thinning_slope: slope,
        thinning_years: [
            phase_years.first().map_or(0, |y| y.year),
            phase_years.last().map_or(0, |y| y.year),
        ],
        simulate_ms: ms(simulated),
        ms_per_year: ms(simulated) / f64::from(args.years),
        peak_rss_mb: peak_rss_mb(),
        threads: rayon::current_num_threads(),
    };
    if args.stats {
        return print_stats(&figures);
    }
    if !args.quiet {
        println!(
            "{} years over {:.0} ha in {:.1} s: {:.0} stems/ha ({:.1} m2/ha, {:.1} m mean height) at the end; {} storms, {} strikes, {} outbreaks; self-thinning slope {}",
            args.years,
            figures.area_ha,
            simulated.as_secs_f64(),
            last.stems_per_ha,
            last.basal_area,
            last.mean_height,
            figures.storms,
            figures.lightning_strikes,
            figures.outbreaks,
            slope.map_or("n/a".into(), |s| format!("{s:.2} (Reineke -1.605)")),
        );
        println!("wrote {}", args.out.display());
    }
    Ok(())
}

/// The bundled species, or the user's files.
pub(crate) fn load_species(files: &[PathBuf]) -> Result<Vec<Species>, Failure> {
    if files.is_empty() {
        return Ok(sylva::presets::species()?);
    }
    Ok(files
        .iter()
        .map(Species::from_file)
        .collect::<Result<Vec<_>, _>>()?)
}

/// succession.csv and succession.json.
fn write_tables(out: &Path, years: &[YearStats], names: &[String]) -> Result<(), Failure> {
    let csv_path = out.join("succession.csv");
    let mut csv = AtomicFile::create(&csv_path)?;
    let at = |p: &Path| {
        let p = p.to_path_buf();
        move |e: std::io::Error| Failure::job(format!("{}: {e}", p.display()))
    };
    writeln!(csv, "{}", YearStats::csv_header(names)).map_err(at(&csv_path))?;
    for y in years {
        writeln!(csv, "{}", y.csv_row()).map_err(at(&csv_path))?;
    }
    csv.commit()?;
    let json_path = out.join("succession.json");
    let mut json = AtomicFile::create(&json_path)?;
    let names_json: Vec<String> = names
        .iter()
        .map(|n| serde_json::to_string(n).unwrap_or_default())
        .collect();
    write!(json, "{{\"species\":[{}],\"years\":[", names_json.join(",")).map_err(at(&json_path))?;
    for (k, y) in years.iter().enumerate() {
        let sep = if k == 0 { "" } else { "," };
        write!(json, "{sep}\n{}", y.to_json(names)).map_err(at(&json_path))?;
    }
    writeln!(json, "\n]}}").map_err(at(&json_path))?;
    json.commit()?;
    Ok(())
}

/// year_NNNN.glb: the region's trees this year on the terrain (placed at its origin).
fn write_snapshot(
    out: &Path,
    forest: &Succession,
    builder: &ForestBuilder,
    map: &Heightmap,
    region: Rect,
) -> Result<(), Failure> {
    let trees = builder.drawing(forest)?;
    let path = out.join(format!("year_{:04}.glb", forest.year()));
    let (lo, hi) = sylva::terrain::HeightField::bounds(map);
    let drawn = region.intersect(&Rect::new(lo, hi));
    write_glb(
        &trees,
        map,
        drawn,
        Some(&map.mesh(2)?),
        &GltfOptions::default(),
        &path,
    )?;
    Ok(())
}
