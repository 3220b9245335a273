//! A walk through a forest in a window: the camera strolls across the world at eye height
//! while the plugin streams the cells around it.
//!
//! ```text
//! cargo run --release --example walk -- [--area METRES] [--frames N]
//! ```
//! `--frames N` closes the window after N frames (for a display driven by a script).

use std::sync::Arc;

use bevy::prelude::*;
use sylva::forest::{ForestBuilder, ForestConfig, Rect};
use sylva::terrain::HeightField;
use sylva::terrain::glam::Vec2 as SylvaVec2;
use sylva_bevy::{Forest, ForestCamera, ForestStatus, SylvaForestPlugin, terrain_mesh};

/// Frames to run before closing (0: until the window is closed).
#[derive(Resource)]
struct Frames(u32);

/// The ground the camera walks on.
#[derive(Resource)]
struct Ground(Arc<dyn HeightField + Send + Sync>, f32);

fn main() {
    let mut args = std::env::args().skip(1);
    let (mut area, mut frames) = (400.0f32, 0u32);
    while let Some(a) = args.next() {
        let value = args.next().unwrap_or_default();
        match a.as_str() {
            "--area" => area = value.parse().expect("--area METRES"),
            "--frames" => frames = value.parse().expect("--frames N"),
            other => panic!("unknown argument {other}"),
        }
    }
    let terrain = sylva::presets::terrain(1, area).expect("terrain");
    let mut config = ForestConfig::new(sylva::presets::species().expect("species"));
    config.budget = 16 << 20;
    let builder = ForestBuilder::new(config).expect("forest");
    let ground = terrain_mesh(&terrain, 2).expect("terrain mesh");
    let terrain: Arc<dyn HeightField + Send + Sync> = Arc::new(terrain);
    let region = Rect::new(SylvaVec2::ZERO, SylvaVec2::splat(area));
    App::new()
        .add_plugins((DefaultPlugins, SylvaForestPlugin))
        .insert_resource(Forest::new(builder, Arc::clone(&terrain), region))
        .insert_resource(Ground(terrain, area))
        .insert_resource(Frames(frames))
        .insert_resource(ClearColor(Color::srgb(0.62, 0.74, 0.86)))
        .add_systems(
            Startup,
            move |mut commands: Commands,
                  mut meshes: ResMut<Assets<Mesh>>,
                  mut materials: ResMut<Assets<StandardMaterial>>| {
                commands.spawn((Camera3d::default(), ForestCamera, Transform::default()));
                commands.spawn((
                    DirectionalLight {
                        illuminance: 12_000.0,
                        shadow_maps_enabled: true,
                        ..default()
                    },
                    Transform::from_xyz(0.45, 0.75, 0.35).looking_at(Vec3::ZERO, Vec3::Y),
                ));
                commands.spawn((
                    Mesh3d(meshes.add(ground.clone())),
                    MeshMaterial3d(materials.add(StandardMaterial {
                        perceptual_roughness: 0.95,
                        ..default()
                    })),
                ));
            },
        )
        .add_systems(Update, (walk, close_after))
        .run();
}

/// Strolls diagonally across the world at 1.5 m/s, 1.7 m above the ground, and back.
fn walk(
    time: Res<Time>,
    ground: Res<Ground>,
    mut camera: Query<&mut Transform, With<ForestCamera>>,
) {
    let Ok(mut t) = camera.single_mut() else {
        return;
    };
    let side = ground.1;
    let span = side * 0.8;
    let s = (time.elapsed_secs() * 1.5) % (2.0 * span);
    let along = if s < span { s } else { 2.0 * span - s };
    let (x, z) = (side * 0.1 + along, side * 0.1 + along * 0.8);
    let y = ground.0.height(x, z) + 1.7;
    let ahead = Vec3::new(0.78, -0.05, 0.62) * if s < span { 1.0 } else { -1.0 };
    *t = Transform::from_xyz(x, y, z).looking_to(ahead, Vec3::Y);
}

/// Closes the app after the frames asked for, printing how far streaming got.
fn close_after(
    mut frames: ResMut<Frames>,
    status: Res<ForestStatus>,
    mut exit: MessageWriter<AppExit>,
    mut seen: Local<u32>,
) {
    *seen += 1;
    if frames.0 > 0 && *seen >= frames.0 {
        println!("{} frames: {status:?}", *seen);
        frames.0 = 0;
        exit.write(AppExit::Success);
    }
}
