//! A minimal wgpu viewer: walk through the forest, or render one frame headless.
//!
//! ```text
//! cargo run --release -p sylva-viewer -- [--grammar PRESET | --species FILE...] [--seed S]
//!     [--area METRES | --trees N] [--budget-mb MB] [--paint MASKS_DIR] [--no-floor]
//!     [--terrain HEIGHTS [--spacing M] [--crop COL,ROW,W,H]] [--max-slope DEG] [--max-height M]
//!     [--camera x,z,yaw,pitch[,height]] [--screenshot PATH [--size WxH] [--ids] [--full-detail]
//!     [--frames N [--walk M] | --tour N [--tour-spacing M] | --turntable N]
//!     [--wind S] [--time T]] [--editor | --editor-screenshot PATH] [--project DIR]
//!     [--autosave-seconds S]
//! ```
//!
//! The world is streamed: only the cells of it near the camera are generated and kept, fine
//! (every branch) within 250 m and as whole-tree proxies to 1,500 m, so a world of millions
//! of trees is walked like a small one. `--trees N` sizes the world as `sylva forest`
//! does, for about N canopy trees (`--trees 1000000`: 7.7 km a side, 5 million trees with
//! the seedlings). `--terrain` walks your own elevation model instead (GeoTIFF, SRTM `.hgt`,
//! ESRI ASCII grid, 16-bit PNG; any size): the largest square of its land, `--crop` choosing
//! a window of samples of a model larger than a world.
//!
//! Windowed: the camera stays at eye height (1.7 m) above the terrain; drag or move the mouse
//! to look (click to capture the cursor, Escape to release), WASD to walk, Shift to run; the
//! trees sway in a breeze. The title shows draw calls, instances, triangles and frame time;
//! `--frames N` closes the window after N frames and prints the median frame time.
//!
//! P turns the painting tool on (Carey's): the left button paints the species chosen with 1
//! to 9 onto the terrain under the cursor, E erases, T turns trees into the species, `[` `]`
//! size the brush, `-` `=` set its strength, Ctrl+Z and Ctrl+Y undo and redo, Ctrl+S saves
//! the masks (to `--paint DIR`, or `paint_masks/`); the right button looks around. G starts
//! the guided walk (the Garden of Eden's): the camera is led from target to target around
//! the trunks; the mouse looks around, A and D lean a little off the way. `--paint DIR`
//! opens a painted forest (the masks `sylva paint`, the tool or you wrote).
//!
//! Headless (`--screenshot`): renders one frame offscreen and writes a PNG, in a wind of
//! strength `--wind` (1, a breeze, by default; 0 for still air) at `--time` seconds into its
//! cycle; `--frames N` renders N more frames and prints the median frame time, and with
//! `--walk M` the camera walks M metres along its heading between them, streaming as it
//! goes. With `--ids` the picture shows flat material colours and the viewer prints what
//! share of it terrain, bark, leaves and sky cover. Trees are drawn at the level of detail
//! their distance asks for (two pixels of error), down to impostors; `--full-detail` draws
//! every branch of every tree instead, to measure against. The forest floor (grass, ferns,
//! shrubs, fallen branches and rocks, thickest in the light gaps) grows around the camera;
//! `--no-floor` leaves the ground bare. `--tour N` renders N frames along a
//! guided walk from the camera's position, `--tour-spacing` metres apart (0.5 by default),
//! to `PATH_0000.png` and on, and prints what the walk did. `--turntable N` grows one canopy
//! tree of the first species alone on its ground and renders it from N directions evenly
//! round it, level with its middle, to `PATH_0000.png` and on, with a contact sheet of the
//! views (four a row, half size) at `PATH`. Without a GPU it runs on Mesa's
//! software drivers (lavapipe, or `WGPU_BACKEND=gl`).
//!
//! The editor (Carey's tool): `--editor` opens a panel at the left of the window (F2 hides
//! or shows it) with three tabs. Species: the forest's species (the `--species` files, the
//! project's, or the bundled ones), the selected one's grammar in a text editor whose
//! problems are shown at their line and column as you type, its settings as sliders, a seed
//! and "Next seed" for the preview tree (its triangles and build time in the panel and the
//! window's title). Forest: the world's seed and side, its terrain (generated: roughness,
//! relief, smoothing, erosion, a seed of its own; or an elevation model's file) and its
//! density. Paint and walk: the painting tool's brush and the guided walk. A change of the
//! species or the forest builds the world again in the background once the edits pause;
//! the walk goes on in the old one until the new one, with the cells around the camera, is
//! swapped in. Undo and redo span species edits, forest settings and strokes. Saves write
//! each species file and its grammar (`NAME.species`, `NAME.lsys`), the world file
//! (`world.json`: the description `sylva serve` takes, species inline, the elevation model
//! beside it) and the painted masks (`masks/`) atomically into the project folder
//! (`--project DIR`, `sylva_project` by default), which `sylva forest --project DIR` reads
//! whole; the viewer opens it again as it was. Species and grammar files changed in your
//! own editor are read again while the viewer runs, their problems shown in the panel. The
//! project is autosaved every 30 s (`--autosave-seconds`) and on quit into `DIR/.autosave`;
//! after a crash, or a quit with edits never saved, the next start offers it back.
//! `--editor-screenshot PATH [--editor-tab species|forest|tools]` renders the panel alone,
//! headless.
//!
//! A forest over time: `--year N` draws year N of the forest grown from bare ground
//! (`sylva succession`'s model with this seed: trees of every age, dead standing trees,
//! broken tops and fallen trees), and in the window Y moves it on ten years (Shift+Y one).
//! `--years A..B --every K` with `--screenshot PATH` renders a headless time-lapse, a frame
//! every K years from year A to B (or at the years of a list, `--years 10,50,150,300`), to
//! `PATH_AAAA.png` and on, named by year, and a contact sheet of them at `PATH`.

mod cell;
mod cells;
mod cli;
mod coverage;
mod cull;
mod draw;
mod editor;
mod error;
mod floor;
mod gather;
#[cfg(test)]
mod golden;
mod gpu;
mod guide;
mod instances;
mod loader;
mod materials;
mod meshes;
mod offscreen;
mod painting;
mod pipelines;
mod pool;
mod rebuild;
mod render;
mod scene;
mod shadow;
mod textures;
mod timelapse;
mod turntable;
mod window;
mod world;
mod years;

use std::process::ExitCode;
use std::time::Instant;

use error::ViewerError;
use scene::{Camera, Scene};
use sylva::forest::Constraints;
use sylva::terrain::dem::Window;
use world::{SceneOptions, TerrainFile};

/// Where the forest's species come from.
enum SpeciesSource {
    /// A grammar preset by name (`--grammar`).
    Preset(String),
    /// Species files (`--species`).
    Files(Vec<String>),
    /// The bundled species.
    Bundled,
}

impl SpeciesSource {
    fn load(self) -> Result<Vec<sylva::forest::Species>, ViewerError> {
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

struct Args {
    /// The world to build, its species still to load from `species`.
    scene: SceneOptions,
    species: SpeciesSource,
    scene_seed: u64,
    camera: Option<Camera>,
    screenshot: Option<String>,
    size: (u32, u32),
    ids: bool,
    full_detail: bool,
    frames: u32,
    walk: f32,
    wind: f32,
    time: f32,
    tour: u32,
    tour_spacing: f32,
    turntable: u32,
    paint: Option<std::path::PathBuf>,
    /// A time-lapse of a forest over time: the years of its frames, ascending.
    years: Option<Vec<u32>>,
    /// The species editor's panel in the window (`--editor`).
    editor: bool,
    /// Renders the editor's panel alone, headless, to this PNG (`--editor-screenshot`),
    /// showing this tab (`--editor-tab`).
    editor_screenshot: Option<String>,
    editor_tab: editor::Tab,
    /// The editor's project folder (`--project`).
    project: std::path::PathBuf,
    /// How often the editor autosaves (`--autosave-seconds`).
    autosave_every: std::time::Duration,
    /// The species files the editor opens (`--species`; none: the bundled species).
    species_files: Vec<std::path::PathBuf>,
}

const USAGE: &str = "usage: sylva-viewer [--grammar PRESET | --species FILE...] [--seed S] [--area METRES | --trees N] [--budget-mb MB] \
                     [--terrain HEIGHTS [--spacing M] [--crop COL,ROW,W,H]] [--max-slope DEG] [--max-height M] [--paint MASKS_DIR] [--no-floor] [--camera x,z,yaw,pitch[,height]] \
                     [--screenshot PATH [--size WxH] [--ids] [--full-detail] [--frames N [--walk M] | --tour N [--tour-spacing M] | --turntable N] [--wind S] [--time T]] \
                     [--year N | --years A..B [--every K] | --years Y1,Y2,...] \
                     [--editor | --editor-screenshot PATH [--editor-tab species|forest|tools]] [--project DIR] [--autosave-seconds S]";

fn parse() -> Result<Args, String> {
    let mut seed = 1u64;
    let mut side = 800.0f32;
    let mut trees: Option<u32> = None;
    let mut budget_mb = 32usize;
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
            "--budget-mb" => budget_mb = flags.value("--budget-mb")?,
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
    if !(side > 10.0 && side <= 20_000.0) {
        return Err(format!("--area {side}: expected 10 to 20000 metres"));
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
            budget: budget_mb.max(1) << 20,
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

fn run() -> Result<(), ViewerError> {
    let mut args = parse().map_err(ViewerError::Usage)?;
    if let Some(path) = &args.editor_screenshot {
        return editor::launch::screenshot(
            &args.species_files,
            &args.project,
            &args.scene,
            (args.editor_tab, args.size),
            path,
        );
    }
    // The editor opens first: a species it cannot read is an error before the world is built.
    let editor = if args.editor {
        let (editor, scene) = editor::launch::session(
            &args.species_files,
            &args.project,
            args.autosave_every,
            &args.scene,
        )?;
        args.scene = scene;
        Some(editor)
    } else {
        args.scene.species = std::mem::replace(&mut args.species, SpeciesSource::Bundled).load()?;
        None
    };
    let base = args.scene.clone();
    let start = Instant::now();
    let mut scene = Scene::build(args.scene)?;
    eprintln!(
        "world: {0:.0} x {0:.0} m, {1} instance groups, built in {2:.0} ms; trees are streamed in \
         {3} m cells, fine within {4} m of the camera, proxies to {5} m",
        scene.side(),
        scene.world.groups.len(),
        start.elapsed().as_secs_f64() * 1e3,
        cell::CELL,
        cells::LOD_DISTANCE,
        cells::VIEW_DISTANCE,
    );
    match args.screenshot {
        Some(path) => {
            let camera = args
                .camera
                .unwrap_or_else(|| Camera::overview(scene.side(), 40.0));
            let mode = if args.ids {
                render::Mode::Ids
            } else {
                render::Mode::Shaded
            };
            let t = Instant::now();
            let mut offscreen =
                pollster::block_on(offscreen::Offscreen::new(&scene, args.size.0, args.size.1))?;
            offscreen.wind = args.wind;
            offscreen.full_detail = args.full_detail;
            offscreen.time = args.time;
            if args.turntable > 0 {
                let turntable = turntable::Turntable {
                    views: args.turntable,
                    size: args.size,
                };
                return turntable.run(&mut scene, &mut offscreen, &path, mode);
            }
            if let Some(years) = args.years {
                let lapse = timelapse::TimeLapse {
                    years,
                    size: args.size,
                };
                return lapse.run(&mut scene, &mut offscreen, &camera, &path, mode);
            }
            if args.tour > 0 {
                let pitch = if args.camera.is_some() {
                    camera.pitch
                } else {
                    -0.05
                };
                let tour = Tour {
                    frames: args.tour,
                    spacing: args.tour_spacing,
                    seed: args.scene_seed,
                    size: args.size,
                    pitch,
                };
                return tour.run(&mut scene, &mut offscreen, camera, &path, mode);
            }
            let (pixels, stats) = offscreen.frame(&mut scene, &camera, mode)?;
            let first_ms = t.elapsed().as_secs_f64() * 1e3;
            let s = stats.streamed;
            println!(
                "streamed {} cells in {:.0} ms: {} trees in the cells drawn ({} in coarse cells), {} cells and {:.0} MB of instances held",
                s.generated,
                s.milliseconds,
                s.trees,
                s.coarse,
                s.resident,
                s.bytes as f64 / 1e6
            );
            // Steady frame time: the median of further frames, read back like the first;
            // with --walk the camera moves between them and cells stream in and out.
            let mut times = Vec::new();
            let mut streaming = Vec::new();
            let mut culling = Vec::new();
            let mut walker = camera;
            for _ in 0..args.frames {
                walker.step(args.walk, scene.side());
                let t = Instant::now();
                let (_, stats) = offscreen.frame(&mut scene, &walker, mode)?;
                times.push(t.elapsed().as_secs_f64() * 1e3);
                streaming.push((stats.streamed.milliseconds, stats.streamed.generated));
                culling.push(stats.cpu_ms + stats.streamed.milliseconds);
            }
            if let Some(cpu) = median(&mut culling) {
                // The CPU's part of a frame, which the window pays too: streaming the cells
                // in and out, culling and choosing levels of detail, uploading placements,
                // recording the draws.
                let placements = if stats.picked {
                    "picked on the GPU"
                } else {
                    "copied on the CPU"
                };
                println!(
                    "CPU per frame: {cpu:.1} ms (median of {}; streaming, culling, upload and recording the draws; placements {placements})",
                    culling.len()
                );
            }
            if args.walk != 0.0 && !streaming.is_empty() {
                let generated: usize = streaming.iter().map(|s| s.1).sum();
                let most = streaming.iter().map(|s| s.0).fold(0.0, f64::max);
                let mut ms: Vec<f64> = streaming.iter().map(|s| s.0).collect();
                println!(
                    "walked {:.0} m in {} frames: {generated} cells streamed in, streaming {:.0} ms per frame (median), {most:.0} ms at most",
                    args.walk * streaming.len() as f32,
                    streaming.len(),
                    median(&mut ms).unwrap_or(0.0)
                );
            }
            let adapter = &offscreen.adapter;
            write_png(&path, args.size, &pixels)?;
            println!(
                "wrote {path} ({}x{}) on {adapter}: {} draw calls, {} instances, {} triangles; first frame {first_ms:.0} ms{}",
                args.size.0,
                args.size.1,
                stats.draws,
                stats.instances,
                stats.triangles,
                median(&mut times).map_or(String::new(), |m| format!(
                    ", steady frame {m:.0} ms (median of {})",
                    times.len()
                ))
            );
            if args.ids {
                println!("coverage: {}", coverage::Coverage::of_ids(&pixels));
            }
            Ok(())
        }
        None => window::run(
            scene,
            base,
            args.camera,
            args.frames,
            args.paint.unwrap_or_else(|| "paint_masks".into()),
            editor,
        ),
    }
}

/// The median of `values` (the upper one of an even count), sorting them; `None` when empty.
fn median(values: &mut [f64]) -> Option<f64> {
    values.sort_by(f64::total_cmp);
    values.get(values.len() / 2).copied()
}

/// Writes RGBA pixels as an 8-bit PNG.
pub(crate) fn write_png(path: &str, size: (u32, u32), pixels: &[u8]) -> Result<(), ViewerError> {
    let encode = || -> Result<(), png::EncodingError> {
        let file = std::fs::File::create(path)?;
        let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), size.0, size.1);
        encoder.set_color(png::ColorType::Rgba);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header()?;
        writer.write_image_data(pixels)?;
        writer.finish()
    };
    encode().map_err(|source| ViewerError::Image {
        path: path.into(),
        source,
    })
}

/// `PATH` with the frame number before its extension: `tour.png` -> `tour_0007.png`.
pub(crate) fn numbered(path: &str, frame: u32) -> String {
    match path.rsplit_once('.') {
        Some((stem, ext)) if !ext.contains('/') => format!("{stem}_{frame:04}.{ext}"),
        _ => format!("{path}_{frame:04}.png"),
    }
}

/// A headless tour: `frames` frames along a guided walk from the camera's position,
/// `spacing` metres apart, each written as a numbered PNG.
struct Tour {
    frames: u32,
    spacing: f32,
    seed: u64,
    size: (u32, u32),
    pitch: f32,
}

impl Tour {
    fn run(
        &self,
        scene: &mut Scene,
        offscreen: &mut offscreen::Offscreen,
        camera: Camera,
        path: &str,
        mode: render::Mode,
    ) -> Result<(), ViewerError> {
        let start = sylva::terrain::glam::Vec2::new(camera.x, camera.z);
        let mut guide = guide::Guide::new(&scene.world, start, self.seed)?;
        let pitch = self.pitch;
        let mut times = Vec::new();
        for frame in 0..self.frames {
            if frame > 0 {
                guide.advance(self.spacing, 0.0);
            }
            let t = Instant::now();
            let (pixels, stats) = offscreen.frame(scene, &guide.camera(0.0, pitch), mode)?;
            times.push(t.elapsed().as_secs_f64() * 1e3);
            let file = numbered(path, frame);
            write_png(&file, self.size, &pixels)?;
            let c = guide.camera(0.0, pitch);
            println!(
                "wrote {file}: camera {:.1},{:.1},{:.0},{:.0}; {} instances, {} triangles",
                c.x,
                c.z,
                c.yaw.to_degrees(),
                c.pitch.to_degrees(),
                stats.instances,
                stats.triangles
            );
        }
        println!(
            "tour of {} frames {} m apart on {}: {}; median frame {:.0} ms",
            self.frames,
            self.spacing,
            offscreen.adapter,
            guide.summary(),
            median(&mut times).unwrap_or(0.0)
        );
        Ok(())
    }
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
