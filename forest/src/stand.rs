//! Stands grown into their environment: species planted on a terrain, grown together in one
//! voxel space with the ground and any obstacles (the voxel growth paper), then meshed.

use std::sync::Arc;

use glam::{Vec2, Vec3};
use sylva_growth::{
    GrownTree, GrowthOptions, GrowthStats, Response, Stand, TreeSpec, VoxelGrid, voxelise_ground,
    voxelise_triangles,
};
use sylva_terrain::HeightField;
use sylva_turtle::{Mesh, MeshBuilder};

use crate::error::ForestError;
use crate::species::Species;

/// One tree to plant: which species, where, its seed and when it starts growing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Planting {
    /// Index into the species.
    pub species: usize,
    /// Position on the ground (x, z).
    pub position: Vec2,
    /// Its own seed.
    pub seed: u64,
    /// Growth iteration at which it starts.
    pub start: u32,
    /// How it answers light.
    pub response: Response,
}

/// Settings of [`grow_stand`].
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct StandOptions {
    /// Side of a voxel, metres. Default: 0.1.
    pub voxel: f32,
    /// Room around the plantings for crowns, metres (horizontally). Default: 6.
    pub margin: f32,
    /// Height of the space above the highest ground, metres. Default: 16.
    pub height: f32,
    /// Obstacles (rocks, buildings): triangle meshes as positions and indices. Default: none.
    pub obstacles: Vec<(Vec<Vec3>, Vec<u32>)>,
    /// Light, collision and query settings. Default: [`GrowthOptions::default`].
    pub growth: GrowthOptions,
}

impl Default for StandOptions {
    fn default() -> Self {
        StandOptions {
            voxel: 0.1,
            margin: 6.0,
            height: 16.0,
            obstacles: Vec::new(),
            growth: GrowthOptions::default(),
        }
    }
}

impl StandOptions {
    /// Sets [`StandOptions::voxel`].
    #[must_use]
    pub fn with_voxel(mut self, voxel: f32) -> Self {
        self.voxel = voxel;
        self
    }

    /// Sets [`StandOptions::margin`].
    #[must_use]
    pub fn with_margin(mut self, margin: f32) -> Self {
        self.margin = margin;
        self
    }

    /// Sets [`StandOptions::height`].
    #[must_use]
    pub fn with_height(mut self, height: f32) -> Self {
        self.height = height;
        self
    }

    /// Sets [`StandOptions::obstacles`].
    #[must_use]
    pub fn with_obstacles(mut self, obstacles: Vec<(Vec<Vec3>, Vec<u32>)>) -> Self {
        self.obstacles = obstacles;
        self
    }

    /// Sets [`StandOptions::growth`].
    #[must_use]
    pub fn with_growth(mut self, growth: GrowthOptions) -> Self {
        self.growth = growth;
        self
    }
}

/// A grown stand: each tree's species, geometry and mesh.
#[derive(Debug, Clone)]
pub struct GrownStand {
    /// Per planting, in order: its species index and its grown tree.
    pub trees: Vec<(usize, GrownTree)>,
    /// What growing cost and did.
    pub stats: GrowthStats,
    /// The voxel space's corners.
    pub bounds: (Vec3, Vec3),
    /// The obstacles it grew around (as given in [`StandOptions::obstacles`]), for export.
    pub obstacles: Vec<(Vec<Vec3>, Vec<u32>)>,
}

impl GrownStand {
    /// Each tree meshed with its species' turtle settings (sides, shape).
    pub fn meshes(&self, species: &[Species]) -> Vec<(usize, Mesh)> {
        self.trees
            .iter()
            .filter_map(|(s, tree)| {
                let sp = species.get(*s)?;
                let mut builder = MeshBuilder::new(&sp.turtle);
                tree.emit(&mut builder);
                Some((*s, builder.finish()))
            })
            .collect()
    }
}

/// Grows `plantings` of `species` together on `terrain`: the ground and the obstacles are
/// voxelised, every tree is derived from its own seed and grown branch by branch with light
/// and collision, competing with the others.
///
/// ```
/// use sylva_forest::{Planting, Species, StandOptions, grow_stand};
/// use sylva_growth::Response;
/// use sylva_terrain::{FlatPlane, glam::Vec2};
///
/// let oak = Species::from_preset("sylva-oak", 5)?;
/// let ground = FlatPlane { height: 0.0, min: Vec2::splat(-20.0), max: Vec2::splat(20.0) };
/// let plantings: Vec<Planting> = [-1.5f32, 1.5]
///     .iter()
///     .enumerate()
///     .map(|(i, &x)| Planting { species: 0, position: Vec2::new(x, 0.0), seed: i as u64, start: 0, response: Response::default() })
///     .collect();
/// let stand = grow_stand(&[oak.clone()], &plantings, &ground, &StandOptions::default())?;
/// assert_eq!(stand.trees.len(), 2);
/// assert!(stand.meshes(&[oak]).iter().all(|(_, m)| m.triangle_count() > 0));
/// # Ok::<(), sylva_forest::ForestError>(())
/// ```
pub fn grow_stand(
    species: &[Species],
    plantings: &[Planting],
    terrain: &dyn HeightField,
    options: &StandOptions,
) -> Result<GrownStand, ForestError> {
    if plantings.is_empty() {
        return Err(ForestError::NoPlantings);
    }
    if let Some(p) = plantings.iter().find(|p| p.species >= species.len()) {
        return Err(ForestError::PlantingSpecies {
            species: p.species,
            count: species.len(),
        });
    }
    let (mut lo, mut hi) = (Vec2::splat(f32::INFINITY), Vec2::splat(f32::NEG_INFINITY));
    let mut ground = (f32::INFINITY, f32::NEG_INFINITY);
    for p in plantings {
        lo = lo.min(p.position);
        hi = hi.max(p.position);
        let h = terrain.height(p.position.x, p.position.y);
        ground = (ground.0.min(h), ground.1.max(h));
    }
    let margin = options.margin.max(0.0);
    let (lo, hi) = (lo - margin, hi + margin);
    // The lowest ground under the space, sampled on a coarse lattice.
    for i in 0..=16 {
        for j in 0..=16 {
            let q = lo + (hi - lo) * Vec2::new(i as f32, j as f32) / 16.0;
            let h = terrain.height(q.x, q.y);
            if h.is_finite() {
                ground = (ground.0.min(h), ground.1.max(h));
            }
        }
    }
    if !(ground.0.is_finite() && ground.1.is_finite()) {
        return Err(ForestError::NoGround);
    }
    let min = Vec3::new(lo.x, ground.0 - options.voxel, lo.y);
    let max = Vec3::new(hi.x, ground.1 + options.height.max(options.voxel), hi.y);
    let mut grid = VoxelGrid::new(min, max, options.voxel)?;
    voxelise_ground(&mut grid, terrain);
    for (positions, indices) in &options.obstacles {
        voxelise_triangles(&mut grid, positions, indices);
    }
    let mut stand = Stand::new(grid, options.growth.clone());
    let grammars: Vec<Arc<sylva_lsys::LSystem>> = species
        .iter()
        .map(|s| Arc::new(s.grammar.clone()))
        .collect();
    for p in plantings {
        let s = &species[p.species];
        // The trunk starts a voxel above the ground voxels it stands on.
        let y = terrain.height(p.position.x, p.position.y) + options.voxel;
        stand.add(TreeSpec {
            base: Vec3::new(p.position.x, y, p.position.y),
            grammar: grammars[p.species].clone(),
            generations: s.generations,
            seed: p.seed,
            start: p.start,
            turtle: s.turtle.clone(),
            response: p.response,
        });
    }
    let (trees, stats) = stand.grow()?;
    Ok(GrownStand {
        trees: plantings.iter().map(|p| p.species).zip(trees).collect(),
        stats,
        bounds: (min, max),
        obstacles: options.obstacles.clone(),
    })
}
