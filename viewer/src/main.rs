//! A minimal wgpu viewer: walk through the forest, or render one frame headless.
//!
//! ```text
//! cargo run --release -p sylva-viewer -- [--grammar PRESET | --species FILE...] [--seed S]
//!     [--area METRES | --trees N] [--budget-mb MB] [--paint MASKS_DIR] [--no-floor]
//!     [--terrain HEIGHTS [--spacing M] [--crop COL,ROW,W,H]] [--max-slope DEG] [--max-height M]
//!     [--camera x,z,yaw,pitch[,height]] [--screenshot PATH [--size WxH] [--ids] [--full-detail]
//!     [--frames N [--walk M] | --tour N [--tour-spacing M] | --turntable N]
//!     [--wind S] [--time T] [--season DAY | --seasons]] [--editor | --editor-screenshot PATH] [--project DIR]
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
//! The seasons: `--season DAY` (1 to 365, or spring, summer, autumn, winter) draws the forest
//! on that day of the year, the shader playing each species' year from the meshes as they
//! are: deciduous crowns flush in spring, turn in autumn and stand bare in winter, each card
//! going by its order in the year and each tree a few days early or late; snow lies on what
//! faces up. In the window N plays the year (a year a minute) or stops it, Shift+N moves the
//! day on ten days. Headless, `--seasons` with `--screenshot PATH` renders spring, summer,
//! autumn and winter to `PATH_DDDD.png` (by day) and a strip of them at `PATH`.
//!
//! A forest over time: `--year N` draws year N of the forest grown from bare ground
//! (`sylva succession`'s model with this seed: trees of every age, dead standing trees,
//! broken tops and fallen trees), and in the window Y moves it on ten years (Shift+Y one).
//! `--years A..B --every K` with `--screenshot PATH` renders a headless time-lapse, a frame
//! every K years from year A to B (or at the years of a list, `--years 10,50,150,300`), to
//! `PATH_AAAA.png` and on, named by year, and a contact sheet of them at `PATH`.

mod args;
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
mod geometry;
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
mod season;
mod shadow;
mod specimen;
mod textures;
mod timelapse;
mod tour;
mod turntable;
mod window;
mod world;
mod years;

use std::process::ExitCode;
use std::time::Instant;

use args::{SpeciesSource, parse};
use error::ViewerError;
use scene::{Camera, Scene};
use tour::Tour;

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
            offscreen.season = args.season;
            if args.seasons {
                let strip = season::SeasonStrip { size: args.size };
                return strip.run(&mut scene, &mut offscreen, &camera, &path, mode);
            }
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
            args.season,
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

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
