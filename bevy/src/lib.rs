//! sylva's forests in Bevy: a plugin that streams a forest in cells around a camera.
//!
//! Give it the forest ([`Forest`]: a `ForestBuilder`, the terrain as any `HeightField`, the
//! region) and mark a camera with [`ForestCamera`]; the plugin generates the cells near the
//! camera off the main thread and drops those left behind. Each cached branch instance is one
//! mesh shared by all its placements, so Bevy batches them into instanced draws; each level
//! of detail (the full instance, two coarser levels, an impostor per canopy tree) is an entity
//! with a [`VisibilityRange`](bevy::camera::visibility::VisibilityRange), so Bevy picks the
//! level by distance and cross-fades between them with its dither. Bark and leaves are drawn
//! with Bevy's PBR over sylva's procedural textures (leaf cards alpha-cut where their coverage
//! survives mipmaps), in a [`WindMaterial`] whose vertex stage sways branches and flutters
//! leaves from the wind data sylva's meshes carry.
//!
//! ```no_run
//! use std::sync::Arc;
//! use bevy::prelude::*;
//! use sylva::forest::{ForestBuilder, ForestConfig, Rect};
//! use sylva::terrain::glam::Vec2;
//! use sylva_bevy::{Forest, ForestCamera, SylvaForestPlugin};
//!
//! let side = 400.0;
//! let terrain = sylva::presets::terrain(1, side).unwrap();
//! let builder = ForestBuilder::new(ForestConfig::new(sylva::presets::species().unwrap())).unwrap();
//! let region = Rect::new(Vec2::ZERO, Vec2::splat(side));
//! App::new()
//!     .add_plugins((DefaultPlugins, SylvaForestPlugin))
//!     .insert_resource(Forest::new(builder, Arc::new(terrain), region))
//!     .add_systems(Startup, |mut commands: Commands| {
//!         commands.spawn((Camera3d::default(), ForestCamera, Transform::from_xyz(200.0, 30.0, 200.0)));
//!     })
//!     .run();
//! ```

mod assets;
mod stream;
mod terrain;
mod wind;

use std::sync::Arc;

use bevy::prelude::*;
use bevy::tasks::{AsyncComputeTaskPool, Task, futures::check_ready};
use sylva::export::lod::{LodChain, VariantLods};
use sylva::forest::{ForestBuilder, ForestError, Rect};
use sylva::terrain::HeightField;

pub use terrain::terrain_mesh;
pub use wind::{ATTRIBUTE_WIND, Wind, WindMaterial};

use assets::ForestAssets;
use stream::Cells;

/// How the forest streams.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct StreamSettings {
    /// Side of a cell, metres.
    pub cell: f32,
    /// Cells farther than this (horizontally, to the cell's nearest point) are not kept.
    pub view_distance: f32,
    /// Cells nearer than this carry every branch; farther ones only impostors. `None`: as far
    /// as any variant's impostor takes over, and a cell more.
    pub fine_distance: Option<f32>,
    /// The levels of detail and their switch distances (screen-space error at 1080p).
    pub chain: LodChain,
    /// Wind strength (1: a breeze; 0: still air).
    pub wind: f32,
    /// Cells generated at once.
    pub tasks: usize,
}

impl Default for StreamSettings {
    fn default() -> Self {
        StreamSettings {
            cell: 100.0,
            view_distance: 1000.0,
            fine_distance: None,
            chain: LodChain::default(),
            wind: 1.0,
            tasks: 2,
        }
    }
}

impl StreamSettings {
    /// Sets [`StreamSettings::view_distance`].
    #[must_use]
    pub fn with_view_distance(mut self, metres: f32) -> Self {
        self.view_distance = metres;
        self
    }

    /// Sets [`StreamSettings::fine_distance`].
    #[must_use]
    pub fn with_fine_distance(mut self, metres: Option<f32>) -> Self {
        self.fine_distance = metres;
        self
    }

    /// Sets [`StreamSettings::wind`].
    #[must_use]
    pub fn with_wind(mut self, strength: f32) -> Self {
        self.wind = strength;
        self
    }
}

/// The forest the plugin streams: its builder (species, caches, density), the terrain it
/// stands on and the region it covers.
#[derive(Resource, Clone)]
pub struct Forest {
    /// The forest's recipe.
    pub builder: Arc<ForestBuilder>,
    /// The ground (any `HeightField`: a sylva heightmap or your own).
    pub terrain: Arc<dyn HeightField + Send + Sync>,
    /// Where trees stand.
    pub region: Rect,
    /// How it streams.
    pub settings: StreamSettings,
}

impl std::fmt::Debug for Forest {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Forest")
            .field("region", &self.region)
            .field("settings", &self.settings)
            .finish_non_exhaustive()
    }
}

impl Forest {
    /// The forest of `builder` on `terrain` over `region`, with default settings.
    pub fn new(
        builder: ForestBuilder,
        terrain: Arc<dyn HeightField + Send + Sync>,
        region: Rect,
    ) -> Forest {
        Forest {
            builder: Arc::new(builder),
            terrain,
            region,
            settings: StreamSettings::default(),
        }
    }

    /// Sets [`Forest::settings`].
    #[must_use]
    pub fn with_settings(mut self, settings: StreamSettings) -> Forest {
        self.settings = settings;
        self
    }
}

/// Marks every entity the plugin spawns for the forest (branch placements and impostors):
/// hide or query them together.
#[derive(Component, Debug, Default, Clone, Copy)]
pub struct ForestPart;

/// Marks the camera the forest streams around.
#[derive(Component, Debug, Default, Clone, Copy)]
pub struct ForestCamera;

/// How far streaming has got: for progress bars, and for headless captures that wait for the
/// view to fill.
#[derive(Resource, Debug, Default, Clone)]
#[non_exhaustive]
pub struct ForestStatus {
    /// The levels of detail, materials and impostors are built (cells stream from then on).
    pub ready: bool,
    /// What went wrong, if anything did.
    pub error: Option<String>,
    /// Cells spawned.
    pub resident: usize,
    /// Cells wanted and not spawned yet.
    pub pending: usize,
    /// Entities the spawned cells hold.
    pub entities: usize,
    /// Branch placements spawned so far.
    pub placements: usize,
}

/// The levels of detail being built off the main thread.
#[derive(Resource)]
struct Building(Task<Result<Vec<(VariantLods, bool)>, ForestError>>);

/// Streams a [`Forest`] around the [`ForestCamera`].
#[derive(Debug, Default, Clone, Copy)]
pub struct SylvaForestPlugin;

impl Plugin for SylvaForestPlugin {
    fn build(&self, app: &mut App) {
        bevy::asset::embedded_asset!(app, "shaders/wind.wgsl");
        bevy::asset::embedded_asset!(app, "shaders/wind_prepass.wgsl");
        bevy::shader::load_shader_library!(app, "shaders/sway.wgsl");
        app.add_plugins(MaterialPlugin::<WindMaterial>::default())
            .init_resource::<Cells>()
            .init_resource::<ForestStatus>()
            .add_systems(
                Update,
                (
                    start_building,
                    finish_building,
                    stream::stream_cells,
                    stream::spawn_cells,
                    blow,
                )
                    .chain(),
            );
    }
}

/// Starts building the forest's levels of detail when a forest is first given.
fn start_building(
    mut commands: Commands,
    forest: Option<Res<Forest>>,
    building: Option<Res<Building>>,
    built: Option<Res<ForestAssets>>,
) {
    let Some(forest) = forest else { return };
    if building.is_some() || built.is_some() {
        return;
    }
    let (builder, chain) = (Arc::clone(&forest.builder), forest.settings.chain.clone());
    let task = AsyncComputeTaskPool::get().spawn(async move {
        let species = &builder.config().species;
        builder
            .variants()
            .iter()
            .map(|v| {
                let lods = VariantLods::build(v, &species[v.species], &chain)?;
                Ok((lods, v.seedling))
            })
            .collect::<Result<Vec<_>, ForestError>>()
    });
    commands.insert_resource(Building(task));
}

/// Makes the materials, images and impostors once the levels of detail are built.
#[allow(
    clippy::too_many_arguments,
    reason = "a Bevy system takes what it touches"
)]
fn finish_building(
    mut commands: Commands,
    forest: Option<Res<Forest>>,
    building: Option<ResMut<Building>>,
    mut status: ResMut<ForestStatus>,
    mut images: ResMut<Assets<Image>>,
    mut materials: ResMut<Assets<WindMaterial>>,
    mut plain: ResMut<Assets<StandardMaterial>>,
    mut meshes: ResMut<Assets<Mesh>>,
) {
    let (Some(forest), Some(mut building)) = (forest, building) else {
        return;
    };
    let Some(result) = check_ready(&mut building.0) else {
        return;
    };
    commands.remove_resource::<Building>();
    let lods = match result {
        Ok(lods) => lods,
        Err(e) => {
            error!("sylva: the forest's levels of detail could not be built: {e}");
            status.error = Some(e.to_string());
            return;
        }
    };
    let species = &forest.builder.config().species;
    let variant_species: Vec<usize> = forest
        .builder
        .variants()
        .iter()
        .map(|v| v.species)
        .collect();
    let assets = ForestAssets::new(
        lods,
        species,
        &variant_species,
        (&forest.settings.chain, forest.settings.view_distance),
        (&mut images, &mut materials, &mut plain, &mut meshes),
    );
    commands.insert_resource(assets);
    status.ready = true;
}

/// Advances the wind in every sylva material.
fn blow(time: Res<Time>, forest: Option<Res<Forest>>, mut materials: ResMut<Assets<WindMaterial>>) {
    let strength = forest.map_or(1.0, |f| f.settings.wind.max(0.0));
    let direction = Vec2::new(0.8, 0.6) * strength;
    for (_, m) in materials.iter_mut() {
        m.extension.wind = Vec4::new(direction.x, 0.0, direction.y, time.elapsed_secs());
    }
}
