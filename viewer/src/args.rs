//! The viewer's command line: its flags, their defaults and the checks between them.

use sylva::forest::Constraints;
use sylva::terrain::dem::Window;
use sylva::world::limits::{MAX_SIDE, MIN_SIDE, check_budget_mb};

use crate::error::ViewerError;
use crate::scene::Camera;
use crate::world::{self, SceneOptions, TerrainFile};
use crate::{cli, editor, years};

/// Where the forest's species come from.
pub(crate) enum SpeciesSource {
    /// A grammar preset by name (`--grammar`).
    Preset(String),
    /// Species files (`--species`).
    Files(Vec<String>),
    /// The bundled species.
    Bundled,
}

impl SpeciesSource {
    /// Loads the species, or says which name or file it could not.
    pub(crate) fn load(self) -> Result<Vec<sylva::forest::Species>, ViewerError> {
        Ok(match self {
            SpeciesSource::Preset(name) => {
                let p = sylva::lsys::preset(&name)
                    .ok_or_else(|| ViewerError::Usage(format!("no preset called '{name}'")))?;
                vec![sylva::forest::Species::from_preset(
                    p.name,
                    p.generations.min(6),
                )?]
            }
            SpeciesSource::Files(files) => files
                .iter()
                .map(sylva::forest::Species::from_file)
                .collect::<Result<_, _>>()?,
            SpeciesSource::Bundled => world::default_species()?,
        })
    }
}

/// What the command line asks for.
pub(crate) struct Args {
    /// The world to build, its species still to load from `species`.
    pub(crate) scene: SceneOptions,
    /// Where the species come from (`--grammar`, `--species` or the bundled ones).
    pub(crate) species: SpeciesSource,
    /// The world's seed (`--seed`), which a tour's guided walk takes too.
    pub(crate) scene_seed: u64,
    /// Where the camera starts (`--camera`; none: the view over the whole world).
    pub(crate) camera: Option<Camera>,
    /// Renders headless to this PNG instead of opening a window (`--screenshot`).
    pub(crate) screenshot: Option<String>,
    /// The headless picture's width and height in pixels (`--size`).
    pub(crate) size: (u32, u32),
    /// Flat material colours, with the share of each printed (`--ids`).
    pub(crate) ids: bool,
    /// Every tree at full detail (`--full-detail`).
    pub(crate) full_detail: bool,
    /// Frames after the first, for a median frame time (`--frames`).
    pub(crate) frames: u32,
    /// Metres the camera walks between those frames (`--walk`).
    pub(crate) walk: f32,
    /// The wind's strength (`--wind`).
    pub(crate) wind: f32,
    /// Seconds into the wind's cycle (`--time`).
    pub(crate) time: f32,
    /// The day of the year drawn (`--season`; `None`: the species as given).
    pub(crate) season: Option<f32>,
    /// A headless season strip: the four seasons' frames (`--seasons`).
    pub(crate) seasons: bool,
    /// Frames of a headless guided walk (`--tour`; 0: none).
    pub(crate) tour: u32,
    /// Metres between the tour's frames (`--tour-spacing`).
    pub(crate) tour_spacing: f32,
    /// Views of one tree round a turntable (`--turntable`; 0: none).
    pub(crate) turntable: u32,
    /// The painted masks' folder (`--paint`).
    pub(crate) paint: Option<std::path::PathBuf>,
    /// A time-lapse of a forest over time: the years of its frames, ascending.
    pub(crate) years: Option<Vec<u32>>,
    /// The species editor's panel in the window (`--editor`).
    pub(crate) editor: bool,
    /// Renders the editor's panel alone, headless, to this PNG (`--editor-screenshot`),
    /// showing this tab (`--editor-tab`).
    pub(crate) editor_screenshot: Option<String>,
    /// The tab `--editor-screenshot` shows (`--editor-tab`).
    pub(crate) editor_tab: editor::Tab,
    /// The editor's project folder (`--project`).
    pub(crate) project: std::path::PathBuf,
    /// How often the editor autosaves (`--autosave-seconds`).
    pub(crate) autosave_every: std::time::Duration,
    /// The species files the editor opens (`--species`; none: the bundled species).
    pub(crate) species_files: Vec<std::path::PathBuf>,
}

/// The flags, as `--help` and a command line that does not parse print them.
pub(crate) const USAGE: &str = "usage: sylva-viewer [--grammar PRESET | --species FILE...] [--seed S] [--area METRES | --trees N] [--budget-mb MB] \
                     [--terrain HEIGHTS [--spacing M] [--crop COL,ROW,W,H]] [--max-slope DEG] [--max-height M] [--paint MASKS_DIR] [--no-floor] [--camera x,z,yaw,pitch[,height]] \
                     [--screenshot PATH [--size WxH] [--ids] [--full-detail] [--frames N [--walk M] | --tour N [--tour-spacing M] | --turntable N] [--wind S] [--time T] [--season DAY | --seasons]] \
                     [--year N | --years A..B [--every K] | --years Y1,Y2,...] \
                     [--editor | --editor-screenshot PATH [--editor-tab species|forest|tools]] [--project DIR] [--autosave-seconds S]";

/// The command line's flags, checked against each other; an error names the flag and what it
/// expects.
pub(crate) fn parse() -> Result<Args, String> {
    let mut seed = 1u64;
    let mut side = 800.0f32;
    let mut trees: Option<u32> = None;
    let mut budget_mb: Option<usize> = None;
    let mut grammar: Option<String> = None;
    let mut files: Vec<String> = Vec::new();
    let mut camera = None;
    let mut screenshot = None;
    let mut size = (1280u32, 720u32);
    let mut ids = false;
    let mut full_detail = false;
    let mut no_floor = false;
    let mut frames = 0u32;
    let mut walk = 0.0f32;
    let mut wind = 1.0f32;
    let mut time = 0.0f32;
    let mut season: Option<f32> = None;
    let mut seasons = false;
    let mut tour = 0u32;
    let mut tour_spacing = 0.5f32;
    let mut turntable = 0u32;
    let mut paint: Option<std::path::PathBuf> = None;
    let mut year: Option<u32> = None;
    let mut years: Option<Vec<u32>> = None;
    let mut every = 10u32;
    let mut span = false;
    let mut terrain: Option<std::path::PathBuf> = None;
    let mut spacing: Option<f32> = None;
    let mut crop: Option<Window> = None;
    let mut max_slope = 35.0f32;
    let mut max_height = f32::INFINITY;
    let mut editor = false;
    let mut editor_screenshot: Option<String> = None;
    let mut editor_tab = editor::Tab::Species;
    let mut project = std::path::PathBuf::from("sylva_project");
    let mut autosave_seconds = editor::AUTOSAVE_EVERY.as_secs_f64();
    let mut flags = cli::Flags::from_env();
    while let Some(a) = flags.next_flag() {
        match a.as_str() {
            "--seed" => seed = flags.value("--seed")?,
            "--area" => side = flags.value("--area")?,
            "--trees" => trees = Some(flags.value("--trees")?),
            "--budget-mb" => budget_mb = Some(flags.value("--budget-mb")?),
            "--grammar" => grammar = Some(flags.value("--grammar")?),
            "--species" => files.push(flags.value("--species")?),
            "--camera" => camera = Some(Camera::parse(&flags.value::<String>("--camera")?)?),
            "--screenshot" => screenshot = Some(flags.value("--screenshot")?),
            "--size" => {
                let s: String = flags.value("--size")?;
                let (w, h) = s
                    .split_once('x')
                    .ok_or(format!("--size '{s}': expected WxH"))?;
                size = (
                    w.parse().map_err(|e| format!("--size '{s}': {e}"))?,
                    h.parse().map_err(|e| format!("--size '{s}': {e}"))?,
                );
                if size.0 == 0 || size.1 == 0 || size.0 > 8192 || size.1 > 8192 {
                    return Err(format!("--size '{s}': each side must be 1 to 8192 pixels"));
                }
            }
            "--ids" => ids = true,
            "--full-detail" => full_detail = true,
            "--no-floor" => no_floor = true,
            "--frames" => frames = flags.value("--frames")?,
            "--walk" => walk = flags.value("--walk")?,
            "--wind" => wind = flags.value("--wind")?,
            "--time" => time = flags.value("--time")?,
            "--season" => {
                let text: String = flags.value("--season")?;
                season = Some(sylva::forest::parse_day(&text).ok_or_else(|| {
                    format!("--season {text}: expected a day of the year (1 to 365) or spring, summer, autumn or winter")
                })?);
            }
            "--seasons" => seasons = true,
            "--tour" => tour = flags.value("--tour")?,
            "--tour-spacing" => tour_spacing = flags.value("--tour-spacing")?,
            "--turntable" => turntable = flags.value("--turntable")?,
            "--paint" => paint = Some(flags.value::<String>("--paint")?.into()),
            "--year" => year = Some(flags.value("--year")?),
            "--years" => {
                let s: String = flags.value("--years")?;
                let number = |t: &str| {
                    t.trim()
                        .parse::<u32>()
                        .map_err(|e| format!("--years '{s}': {e}"))
                };
                years = Some(match s.split_once("..") {
                    // A..B, filled in with --every below.
                    Some((a, b)) => vec![number(a)?, number(b)?],
                    None => s.split(',').map(number).collect::<Result<_, _>>()?,
                });
                span = s.contains("..");
            }
            "--every" => every = flags.value("--every")?,
            "--terrain" => terrain = Some(flags.value::<String>("--terrain")?.into()),
            "--spacing" => spacing = Some(flags.value("--spacing")?),
            "--crop" => crop = Some(flags.value("--crop")?),
            "--max-slope" => max_slope = flags.value("--max-slope")?,
            "--max-height" => max_height = flags.value("--max-height")?,
            "--editor" => editor = true,
            "--editor-screenshot" => editor_screenshot = Some(flags.value("--editor-screenshot")?),
            "--editor-tab" => editor_tab = flags.value("--editor-tab")?,
            "--project" => project = flags.value::<String>("--project")?.into(),
            "--autosave-seconds" => autosave_seconds = flags.value("--autosave-seconds")?,
            "--help" | "-h" => cli::print_help(USAGE),
            s => return Err(format!("unknown argument {s}\n{USAGE}")),
        }
    }
    if !(0.0..=10.0).contains(&wind) {
        return Err(format!("--wind {wind}: expected a strength from 0 to 10"));
    }
    if !(-1000.0..=1000.0).contains(&walk) {
        return Err(format!(
            "--walk {walk}: expected metres per frame, -1000 to 1000"
        ));
    }
    if tour > 100_000 {
        return Err(format!("--tour {tour}: expected at most 100000 frames"));
    }
    if !(tour_spacing > 0.0 && tour_spacing <= 100.0) {
        return Err(format!(
            "--tour-spacing {tour_spacing}: expected metres between frames, above 0 and at most 100"
        ));
    }
    if tour > 0 && screenshot.is_none() {
        return Err(format!(
            "--tour renders headless: give --screenshot PATH (frames go to PATH_0000.png ...)\n{USAGE}"
        ));
    }
    if turntable > 64 {
        return Err(format!(
            "--turntable {turntable}: expected at most 64 views"
        ));
    }
    if turntable > 0 && (screenshot.is_none() || tour > 0 || paint.is_some()) {
        return Err(format!(
            "--turntable renders headless one tree of the first species: give --screenshot PATH \
             (views go to PATH_0000.png ..., a sheet of them to PATH), without --tour or --paint\n{USAGE}"
        ));
    }
    if !time.is_finite() {
        return Err(format!("--time {time}: expected a number of seconds"));
    }
    if trees.is_some_and(|n| n == 0 || n > 10_000_000) {
        return Err(format!(
            "--trees {}: expected 1 to 10000000",
            trees.unwrap_or(0)
        ));
    }
    if !(MIN_SIDE..=MAX_SIDE).contains(&side) {
        return Err(format!(
            "--area {side}: expected {MIN_SIDE} to {MAX_SIDE} metres"
        ));
    }
    if let Some(Err(e)) = budget_mb.map(|mb| check_budget_mb(mb as u64)) {
        return Err(format!("--budget-mb {e}"));
    }
    if spacing.is_some_and(|s: f32| !(s > 0.0 && s <= 100_000.0)) {
        return Err("--spacing: expected metres between samples, above 0".to_owned());
    }
    if !(0.0..=90.0).contains(&max_slope) || max_height.is_nan() {
        return Err(format!(
            "--max-slope {max_slope} --max-height {max_height}: expected 0 to 90 degrees and a height in metres"
        ));
    }
    if terrain.is_none() && (spacing.is_some() || crop.is_some()) {
        return Err(format!(
            "--spacing and --crop are for --terrain FILE\n{USAGE}"
        ));
    }
    if terrain.is_some() && turntable > 0 {
        return Err(format!(
            "--turntable stands one tree on flat ground: not with --terrain\n{USAGE}"
        ));
    }
    if seasons
        && (screenshot.is_none()
            || tour > 0
            || turntable > 0
            || years.is_some()
            || season.is_some())
    {
        return Err(format!(
            "--seasons renders a headless season strip (spring, summer, autumn, winter): give --screenshot PATH, without --season, --tour, --turntable or --years\n{USAGE}"
        ));
    }
    if year.is_some() && years.is_some() {
        return Err(format!("give --year or --years, not both\n{USAGE}"));
    }
    if let (Some(list), true) = (&mut years, span) {
        let (a, b) = (list[0], list[1]);
        // Checked before the years are listed, so a huge span is an error, not a huge list.
        if a > b || b > years::MAX_YEARS || every == 0 {
            return Err(format!(
                "--years {a}..{b} --every {every}: expected A <= B <= {}, every at least 1",
                years::MAX_YEARS
            ));
        }
        *list = (a..=b).step_by(every as usize).collect();
    }
    if let Some(list) = &years {
        if list.is_empty()
            || list.windows(2).any(|w| w[0] >= w[1])
            || list.iter().any(|&y| y > years::MAX_YEARS)
            || list.len() > 1000
        {
            return Err(format!(
                "--years: expected ascending years up to {}, at most 1000 frames",
                years::MAX_YEARS
            ));
        }
        if screenshot.is_none() || tour > 0 || turntable > 0 {
            return Err(format!(
                "--years renders a headless time-lapse: give --screenshot PATH (frames go to PATH_0000.png ... by year), without --tour or --turntable\n{USAGE}"
            ));
        }
    }
    if year.is_some_and(|y| y > years::MAX_YEARS) {
        return Err(format!("--year: expected at most {}", years::MAX_YEARS));
    }
    let start_year = years.as_ref().map(|y| y[0]).or(year);
    if start_year.is_some() && (paint.is_some() || turntable > 0) {
        return Err(format!(
            "a forest over time (--year, --years) is grown, not painted: not with --paint or --turntable\n{USAGE}"
        ));
    }
    if (editor || editor_screenshot.is_some()) && grammar.is_some() {
        return Err(format!(
            "the editor edits species files (--species, or the bundled species), not --grammar\n{USAGE}"
        ));
    }
    if editor && screenshot.is_some() {
        return Err(format!(
            "--editor opens the panel in the window; headless, render it with --editor-screenshot PATH\n{USAGE}"
        ));
    }
    if !(0.5..=3600.0).contains(&autosave_seconds) {
        return Err(format!(
            "--autosave-seconds {autosave_seconds}: expected 0.5 to 3600"
        ));
    }
    let species_files: Vec<std::path::PathBuf> = files.iter().map(Into::into).collect();
    let species = match (grammar, files.is_empty()) {
        (Some(_), false) => return Err(format!("give --grammar or --species, not both\n{USAGE}")),
        (Some(name), true) => SpeciesSource::Preset(name),
        (None, false) => SpeciesSource::Files(files),
        (None, true) => SpeciesSource::Bundled,
    };
    Ok(Args {
        scene_seed: seed,
        scene: SceneOptions {
            seed,
            side,
            trees,
            species: Vec::new(),
            budget: budget_mb.map(|mb| mb << 20),
            paint: paint.clone(),
            specimen: turntable > 0,
            floor: !no_floor,
            year: start_year,
            constraints: Constraints::default()
                .with_max_slope_degrees(max_slope)
                .with_height_range(f32::NEG_INFINITY, max_height),
            terrain: terrain.map(|path| TerrainFile {
                path,
                spacing,
                crop,
            }),
            ground: None,
            density: None,
        },
        species,
        camera,
        screenshot,
        size,
        ids,
        full_detail,
        frames,
        walk,
        wind,
        time,
        season,
        seasons,
        tour,
        tour_spacing,
        turntable,
        paint,
        years,
        editor,
        editor_screenshot,
        editor_tab,
        project,
        autosave_every: std::time::Duration::from_secs_f64(autosave_seconds),
        species_files,
    })
}
