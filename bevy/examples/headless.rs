//! A forest streamed by the plugin and rendered headless to a PNG (no window, no GPU needed:
//! Mesa's lavapipe will do), with what the trees cover measured: the frame is rendered again
//! without shadows, and once more with the forest hidden too, and every pixel that changed
//! between those two is forest.
//!
//! ```text
//! cargo run --release --example headless -- [OUT.png] [--size WxH] [--area METRES] [--camera x,y,z,tx,ty,tz]
//! ```
//! The camera's and its target's heights are above the ground below them.

use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use bevy::app::ScheduleRunnerPlugin;
use bevy::camera::RenderTarget;
use bevy::prelude::*;
use bevy::render::RenderPlugin;
use bevy::render::render_resource::TextureFormat;
use bevy::render::settings::WgpuSettings;
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured};
use bevy::window::ExitCondition;
use sylva::forest::{ForestBuilder, ForestConfig, Rect};
use sylva::terrain::glam::Vec2 as SylvaVec2;
use sylva_bevy::{
    Forest, ForestCamera, ForestPart, ForestStatus, StreamSettings, SylvaForestPlugin, terrain_mesh,
};

/// What the example was asked for.
#[derive(Resource, Clone)]
struct Job {
    out: String,
    size: (u32, u32),
    started: Instant,
}

/// The frames captured so far: with the forest, then without.
#[derive(Resource, Default, Clone)]
struct Captures(Arc<Mutex<Vec<Image>>>);

#[derive(Resource)]
struct Target(Handle<Image>);

/// Where the capture stands.
#[derive(Resource, Default)]
enum Step {
    #[default]
    Streaming,
    /// Frames left before capturing the forest (pipelines compile, meshes upload).
    Settling(u32),
    WithForest,
    /// Frames left before capturing without shadows (hiding the forest would move them).
    Unshadowing(u32),
    Unshadowed,
    Hiding(u32),
    WithoutForest,
    Done,
}

fn main() -> AppExit {
    let mut args = std::env::args().skip(1);
    let (mut out, mut size, mut area) = ("bevy.png".to_string(), (960u32, 540u32), 300.0f32);
    let mut camera = [20.0f32, 20.0, 20.0, 150.0, 0.0, 150.0];
    while let Some(a) = args.next() {
        let mut value = || args.next().unwrap_or_else(|| panic!("{a} needs a value"));
        match a.as_str() {
            "--size" => {
                let v = value();
                let (w, h) = v.split_once('x').expect("--size WxH");
                size = (w.parse().expect("width"), h.parse().expect("height"));
            }
            "--area" => area = value().parse().expect("--area METRES"),
            "--camera" => {
                let v: Vec<f32> = value()
                    .split(',')
                    .map(|x| x.parse().expect("a number"))
                    .collect();
                camera.copy_from_slice(&v[..6]);
            }
            other => out = other.to_string(),
        }
    }
    let terrain = sylva::presets::terrain(1, area).expect("terrain");
    {
        use sylva::terrain::HeightField;
        camera[1] += terrain.height(camera[0], camera[2]);
        camera[4] += terrain.height(camera[3], camera[5]);
    }
    let mut config = ForestConfig::new(sylva::presets::species().expect("species"));
    config.budget = 16 << 20;
    let builder = ForestBuilder::new(config).expect("forest");
    let region = Rect::new(SylvaVec2::ZERO, SylvaVec2::splat(area));
    let ground = terrain_mesh(&terrain, 2).expect("terrain mesh");
    let forest = Forest::new(builder, Arc::new(terrain), region)
        .with_settings(StreamSettings::default().with_view_distance(area * 1.5));
    let job = Job {
        out,
        size,
        started: Instant::now(),
    };
    App::new()
        .add_plugins(
            DefaultPlugins
                .set(WindowPlugin {
                    primary_window: None,
                    exit_condition: ExitCondition::DontExit,
                    ..default()
                })
                .set(RenderPlugin {
                    synchronous_pipeline_compilation: true,
                    render_creation: WgpuSettings::default().into(),
                    ..default()
                })
                .disable::<bevy::winit::WinitPlugin>(),
        )
        .add_plugins(ScheduleRunnerPlugin::run_loop(Duration::ZERO))
        .add_plugins(SylvaForestPlugin)
        .insert_resource(forest)
        .insert_resource(job)
        .insert_resource(ClearColor(Color::srgb(0.62, 0.74, 0.86)))
        .init_resource::<Captures>()
        .init_resource::<Step>()
        .add_systems(
            Startup,
            move |mut commands: Commands,
                  mut images: ResMut<Assets<Image>>,
                  mut meshes: ResMut<Assets<Mesh>>,
                  mut materials: ResMut<Assets<StandardMaterial>>,
                  job: Res<Job>| {
                let target = images.add(Image::new_target_texture(
                    job.size.0,
                    job.size.1,
                    TextureFormat::Rgba8UnormSrgb,
                    None,
                ));
                commands.insert_resource(Target(target.clone()));
                let [x, y, z, tx, ty, tz] = camera;
                commands.spawn((
                    Camera3d::default(),
                    RenderTarget::Image(target.into()),
                    Msaa::Off,
                    ForestCamera,
                    Transform::from_xyz(x, y, z).looking_at(Vec3::new(tx, ty, tz), Vec3::Y),
                ));
                commands.spawn((
                    DirectionalLight {
                        illuminance: 12_000.0,
                        shadow_maps_enabled: true,
                        ..default()
                    },
                    Transform::from_xyz(0.45, 0.75, 0.35).looking_at(Vec3::ZERO, Vec3::Y),
                ));
                commands.insert_resource(GlobalAmbientLight {
                    brightness: 600.0,
                    ..default()
                });
                commands.spawn((
                    Mesh3d(meshes.add(ground.clone())),
                    MeshMaterial3d(materials.add(StandardMaterial {
                        perceptual_roughness: 0.95,
                        ..default()
                    })),
                ));
            },
        )
        .add_systems(Update, capture)
        .run()
}

/// Waits for the view to fill, captures it, hides the forest, captures again, and measures.
#[allow(
    clippy::too_many_arguments,
    reason = "a Bevy system takes what it touches"
)]
fn capture(
    mut commands: Commands,
    mut step: ResMut<Step>,
    status: Res<ForestStatus>,
    target: Option<Res<Target>>,
    captures: Res<Captures>,
    job: Res<Job>,
    mut forest: Query<&mut Visibility, With<ForestPart>>,
    mut lights: Query<&mut DirectionalLight>,
    mut exit: MessageWriter<AppExit>,
) {
    let Some(target) = target else { return };
    if let Some(e) = &status.error {
        eprintln!("sylva-bevy: {e}");
        exit.write(AppExit::error());
        return;
    }
    if job.started.elapsed() > Duration::from_secs(600) {
        eprintln!("the forest did not finish streaming in 600 s: {status:?}");
        exit.write(AppExit::error());
        return;
    }
    let shoot = |commands: &mut Commands| {
        let store = captures.0.clone();
        commands.spawn(Screenshot::image(target.0.clone())).observe(
            move |captured: On<ScreenshotCaptured>| {
                if let Ok(mut list) = store.lock() {
                    list.push(captured.image.clone());
                }
            },
        );
    };
    let taken = captures.0.lock().map_or(0, |l| l.len());
    *step = match std::mem::take(&mut *step) {
        Step::Streaming if status.ready && status.resident > 0 && status.pending == 0 => {
            println!(
                "streamed {} cells: {} entities, {} branch placements, in {:.1} s",
                status.resident,
                status.entities,
                status.placements,
                job.started.elapsed().as_secs_f64()
            );
            Step::Settling(6)
        }
        Step::Settling(0) => {
            shoot(&mut commands);
            Step::WithForest
        }
        Step::Settling(n) => Step::Settling(n - 1),
        Step::WithForest if taken >= 1 => {
            for mut light in &mut lights {
                light.shadow_maps_enabled = false;
            }
            Step::Unshadowing(3)
        }
        Step::Unshadowing(0) => {
            shoot(&mut commands);
            Step::Unshadowed
        }
        Step::Unshadowing(n) => Step::Unshadowing(n - 1),
        Step::Unshadowed if taken >= 2 => {
            for mut v in &mut forest {
                *v = Visibility::Hidden;
            }
            Step::Hiding(3)
        }
        Step::Hiding(0) => {
            shoot(&mut commands);
            Step::WithoutForest
        }
        Step::Hiding(n) => Step::Hiding(n - 1),
        Step::WithoutForest if taken >= 3 => {
            let list = captures.0.lock().map(|l| l.clone()).unwrap_or_default();
            match measure(&list[0], (&list[1], &list[2]), &job.out) {
                Ok(share) => {
                    println!(
                        "wrote {} ({}x{}): the forest covers {:.1}% of the picture",
                        job.out,
                        job.size.0,
                        job.size.1,
                        100.0 * share
                    );
                    exit.write(if share > 0.2 {
                        AppExit::Success
                    } else {
                        eprintln!("expected the forest to cover more than 20% of the picture");
                        AppExit::error()
                    });
                }
                Err(e) => {
                    eprintln!("{e}");
                    exit.write(AppExit::error());
                }
            }
            Step::Done
        }
        other => other,
    };
}

/// Writes `picture` as a PNG at `out` and returns the share of the pixels of `with` (the view
/// without shadows) that differ from `without` (the same with the forest hidden).
fn measure(picture: &Image, (with, without): (&Image, &Image), out: &str) -> Result<f64, String> {
    let (a, b) = (
        with.data.as_ref().ok_or("the capture has no pixels")?,
        without.data.as_ref().ok_or("the capture has no pixels")?,
    );
    let shown = picture.data.as_ref().ok_or("the capture has no pixels")?;
    let (w, h) = (with.width(), with.height());
    let changed = a
        .chunks_exact(4)
        .zip(b.chunks_exact(4))
        .filter(|(p, q)| p[..3].iter().zip(&q[..3]).any(|(x, y)| x.abs_diff(*y) > 8))
        .count();
    let png = sylva::export::Texture {
        width: w,
        height: h,
        rgba: shown
            .chunks_exact(4)
            .flat_map(|p| [p[0], p[1], p[2], 255])
            .collect(),
    };
    std::fs::write(out, png.png()).map_err(|e| format!("{out}: {e}"))?;
    Ok(changed as f64 / f64::from(w * h).max(1.0))
}
