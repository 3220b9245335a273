//! What never changes while the camera moves: the forest's recipe, the terrain, and the
//! geometry every placement refers to, shared by the streaming, the culling and the drawing.

use bytemuck::{Pod, Zeroable};
use std::sync::{Arc, PoisonError, RwLock};

use rayon::prelude::*;
use sylva::export::Texture;
use sylva::export::lod::{CacheLods, Impostor, LodChain, VariantLods};
use sylva::forest::{
    BarkPattern, Composition, Constraints, FloorOptions, ForestBuilder, ForestConfig, ForestError,
    ForestFloor, GroundKind, LeafShape, Rect, Species,
};
use sylva::instancing::Span;
use sylva::paint::PaintLayer;
use sylva::terrain::Heightmap;
use sylva::terrain::dem::{ElevationModel, ReadOptions, Window};
use sylva::terrain::glam::{Quat, Vec2, Vec3};
use sylva::turtle::Vertex;

use crate::error::ViewerError;

/// One placement as the vertex shader reads it: rotation, then translation and scale.
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
pub(crate) struct InstanceRaw {
    pub(crate) rotation: [f32; 4],
    pub(crate) translation_scale: [f32; 4],
    /// The tree's tint (`sylva_forest::tree_tint`), and 1.
    pub(crate) tint: [f32; 4],
    /// The tree's base and wind phase (`sylva_forest::tree_wind`).
    pub(crate) tree: [f32; 4],
}

impl InstanceRaw {
    /// The base of the tree it belongs to, where its level of detail is measured from.
    pub(crate) fn base(&self) -> Vec3 {
        Vec3::new(self.tree[0], self.tree[1], self.tree[2])
    }
}

/// One species variant's shared buffers: the cache's vertices (and its coarser levels' grown
/// leaf cards), and every level's bark and leaf triangles one after another.
#[derive(Clone)]
pub(crate) struct VariantGeometry {
    pub(crate) vertices: Vec<Vertex>,
    pub(crate) bark: Vec<u32>,
    pub(crate) leaves: Vec<u32>,
    pub(crate) bark_colour: [f32; 3],
    pub(crate) leaf_colour: [f32; 3],
    pub(crate) leaf_shape: LeafShape,
    pub(crate) bark_pattern: BarkPattern,
    /// Whether its leaves are textured cards (grass blades are plain triangles).
    pub(crate) textured_leaves: bool,
}

/// Levels of detail drawn from meshes: the full cache and its two coarser levels.
pub(crate) const MESH_LEVELS: usize = 3;

/// One cached instance drawn with its placements: one instanced draw per level and non-empty
/// index range. Its placements live in the streamed cells.
#[derive(Clone)]
pub(crate) struct Group {
    pub(crate) variant: usize,
    /// Per level of detail, its bark and leaf triangles in the variant's buffers.
    pub(crate) levels: [(Span, Span); MESH_LEVELS],
    /// A sphere around the instance's triangles in its own space (centre, radius), with room
    /// for the wind's sway.
    pub(crate) sphere: (Vec3, f32),
}

/// A variant's impostor card, drawn for trees far from the camera: a quad of corners
/// `(±1, ±1)` that the impostor shader turns to face the camera, whose vertices carry the
/// atlas (normal: the centre of the sphere the views frame; wind: atlas number, views per
/// side, the sphere's radius and the variant's bark material). Empty for variants without an
/// impostor (seedlings, which are not drawn that far).
#[derive(Clone)]
pub(crate) struct Proxy {
    pub(crate) vertices: Vec<Vertex>,
    pub(crate) bark: Vec<u32>,
    pub(crate) leaves: Vec<u32>,
    /// A sphere around it in the tree's own space (centre, radius).
    pub(crate) sphere: (Vec3, f32),
}

/// When a variant's coarser levels are drawn: each level's error in metres (level 1, level 2,
/// the impostor; infinite for a variant without one), turned into distances by the view's
/// pixels per radian.
#[derive(Debug, Clone, Copy)]
pub(crate) struct VariantLod {
    pub(crate) errors: [f32; MESH_LEVELS],
}

/// The levels of detail the viewer draws: `LodChain`'s defaults, with impostors of 8 x 8 views
/// of 96 pixels (the viewer's 720p needs less than 1080p's 128).
pub(crate) fn lod_chain() -> LodChain {
    let mut chain = LodChain::default();
    chain.impostor = chain.impostor.with_view_size(96);
    chain
}

/// The forest as it is painted: its builder, how many times it has been repainted (cells
/// remember the version they were generated from) and the layer it is painted with (the
/// builder holds it only as a composition, so the painting tool keeps it here to edit).
struct Recipe {
    builder: Arc<ForestBuilder>,
    version: u64,
    layer: Option<Arc<PaintLayer>>,
}

/// What never changes while the camera moves: the forest's recipe (but for the painting
/// tool's layer), the terrain, and the geometry every placement refers to. Shared with the
/// thread that generates cells.
pub(crate) struct World {
    /// The forest's recipe; swapped whole when the painting tool paints.
    forest: RwLock<Recipe>,
    pub(crate) heightmap: Heightmap,
    pub(crate) side: f32,
    pub(crate) variants: Vec<VariantGeometry>,
    pub(crate) groups: Vec<Group>,
    /// Per variant and cache instance, its index in `groups` (`None`: nothing to draw).
    pub(crate) group_of: Vec<Vec<Option<u32>>>,
    /// Per variant.
    pub(crate) proxies: Vec<Proxy>,
    /// Per variant: when each coarser level takes over.
    pub(crate) lods: Vec<VariantLod>,
    /// The impostor atlases, colour then normals of each (the variants' `atlas` number).
    pub(crate) atlases: Vec<Texture>,
    /// The forest floor (none around a specimen), and the group of its first kind (its
    /// kinds' groups follow the trees', in `GroundKind::ALL`'s order).
    pub(crate) floor: Option<ForestFloor>,
    pub(crate) first_floor_group: Option<u32>,
    /// Per variant: whether it is a seedling form (left out of coarse cells, as coarse tiles
    /// leave it out).
    pub(crate) seedling: Vec<bool>,
    /// The forest over time the trees come from (`--year`, `--years`), if any.
    pub(crate) years: Option<crate::years::Years>,
    /// The density's patch the species give, before any `density` setting.
    own_patch: f32,
    /// The seed the forest floor was grown from.
    seed: u64,
}

/// How to build a [`World`].
#[derive(Debug, Clone)]
pub(crate) struct SceneOptions {
    pub(crate) seed: u64,
    /// The world's side in metres, unless `trees` is given.
    pub(crate) side: f32,
    /// Size the world for this many canopy trees, one per density patch, as the forest
    /// example's `--trees` does.
    pub(crate) trees: Option<u32>,
    pub(crate) species: Vec<Species>,
    pub(crate) budget: usize,
    /// A painted forest's masks (`sylva_forest::load_masks`), if any.
    pub(crate) paint: Option<std::path::PathBuf>,
    /// A turntable's world instead: one canopy tree of the first species in the middle of a
    /// world of at least 80 m, no seedlings (`side` and `trees` are not used).
    pub(crate) specimen: bool,
    /// Whether the forest floor grows (never around a specimen).
    pub(crate) floor: bool,
    /// Draw year N of a forest over time grown from bare ground (trees of every age, dead,
    /// broken and fallen ones) instead of the density model's forest.
    pub(crate) year: Option<u32>,
    /// Where on the terrain trees may stand (slope limit, height range).
    pub(crate) constraints: Constraints,
    /// The user's elevation model instead of generated terrain (`side` and `trees` are not
    /// used): the largest square of its own land.
    pub(crate) terrain: Option<TerrainFile>,
    /// Ground made already (the editor's forest tab): a square heightmap and the extent the
    /// world covers on it, instead of generated terrain or `terrain` (`side` and `trees` are
    /// not used).
    pub(crate) ground: Option<(Heightmap, [f32; 2])>,
    /// Canopy trees per hectare (sets the density's patch size); `None` keeps the species'.
    pub(crate) density: Option<f32>,
}

/// An elevation model from a file, as `--terrain`, `--spacing` and `--crop` give it.
#[derive(Debug, Clone)]
pub(crate) struct TerrainFile {
    pub(crate) path: std::path::PathBuf,
    /// Metres between samples, overriding the file's.
    pub(crate) spacing: Option<f32>,
    /// The window of the model to use.
    pub(crate) crop: Option<Window>,
}

impl TerrainFile {
    /// The model's largest square of land as a heightmap, read, cropped and checked.
    fn heightmap(&self) -> Result<Heightmap, ViewerError> {
        let name = self.path.display();
        let options = ReadOptions {
            spacing: self.spacing,
            ..ReadOptions::default()
        };
        let mut model = ElevationModel::read(&self.path, &options)?;
        if !model.spacing_from_file && self.spacing.is_none() {
            return Err(ViewerError::Usage(format!(
                "{name}: the file does not say how far apart its samples are: give --spacing M"
            )));
        }
        if let Some(window) = self.crop {
            model = model.crop(window)?;
        }
        if model.nodata > 0 {
            eprintln!(
                "{name}: {} cells had no data and were filled from their neighbours",
                model.nodata
            );
        }
        let [x, z] = model.extent();
        if x.max(z) > 20_000.0 {
            return Err(ViewerError::Usage(format!(
                "{name}: {x:.0} x {z:.0} m is larger than a world (20000 m a side): give --crop COL,ROW,W,H"
            )));
        }
        Ok(model.square_heightmap()?)
    }
}

#[cfg(test)]
impl SceneOptions {
    /// A small world for tests: the first two bundled species (oak and birch) on `side`
    /// metres, with an 8 MB instance cache.
    pub(crate) fn small(seed: u64, side: f32) -> SceneOptions {
        SceneOptions {
            seed,
            side,
            trees: None,
            species: default_species().expect("bundled species")[..2].to_vec(),
            budget: 8 << 20,
            paint: None,
            specimen: false,
            floor: true,
            year: None,
            constraints: Constraints::default(),
            terrain: None,
            ground: None,
            density: None,
        }
    }
}

/// The bundled species ([`sylva::presets::species`]).
pub(crate) fn default_species() -> Result<Vec<Species>, ForestError> {
    sylva::presets::species()
}

impl World {
    /// The forest's caches and the terrain ([`sylva::presets::terrain`], as the forest
    /// example's); no trees are placed until cells are streamed.
    pub(crate) fn build(options: SceneOptions) -> Result<World, ViewerError> {
        let mut config = ForestConfig::new(options.species);
        config.seed = options.seed;
        config.budget = options.budget;
        if options.specimen {
            config.seedlings_per_patch = 0;
        }
        config.all_ages = options.year.is_some();
        config.constraints = options.constraints;
        let mut builder = ForestBuilder::new(config)?;
        let own_patch = builder.density().patch;
        if let Some(d) = options.density {
            builder.density_mut().patch = (10_000.0 / d).sqrt();
        }
        let patch = builder.density().patch;
        // A square world: the larger side of the ground's extent.
        let user_map = match options.ground {
            Some((map, _)) => Some(map),
            None => options
                .terrain
                .as_ref()
                .map(TerrainFile::heightmap)
                .transpose()?,
        };
        let side = match (&user_map, options.trees) {
            (Some(map), _) => (map.size() - 1) as f32 * map.spacing(),
            _ if options.specimen => crate::turntable::world_patches(patch) as f32 * patch,
            (None, Some(n)) => builder.side_for_canopy_trees(n as usize),
            (None, None) => options.side,
        };
        if options.specimen {
            builder = builder.with_composition(Some(crate::turntable::specimen(patch)))?;
        }
        if !(side > 10.0 && side <= 20_000.0) {
            return Err(ViewerError::WorldSize { side });
        }
        let heightmap = match user_map {
            Some(map) => map,
            None => sylva::presets::terrain(options.seed, side)?,
        };
        let mut layer = None;
        if let Some(dir) = &options.paint {
            let loaded = Arc::new(sylva::paint::load_masks_for(&builder, dir, &heightmap)?);
            let composition: Arc<dyn Composition> = loaded.clone();
            builder = builder.with_composition(Some(composition))?;
            layer = Some(loaded);
        }
        let years = match options.year {
            Some(year) => {
                let t = std::time::Instant::now();
                let region = Rect::new(Vec2::ZERO, Vec2::splat(side));
                let (years, drawn) = crate::years::Years::grow(&builder, region, year)?;
                eprintln!(
                    "forest over time: grew {side:.0} m from bare ground to year {year} in {:.1} s",
                    t.elapsed().as_secs_f64()
                );
                builder = drawn;
                Some(years)
            }
            None => None,
        };
        let species = &builder.config().species;
        let chain = lod_chain();
        // Each variant's levels (cards grown to its whole tree's coverage) and, for canopy
        // variants, its impostor: worked out on every core.
        let built: Vec<VariantLods> = builder
            .variants()
            .par_iter()
            .map(|v| VariantLods::build(v, &species[v.species], &chain))
            .collect::<Result<_, _>>()
            .map_err(ForestError::from)?;
        let mut lods: Vec<VariantLod> = built
            .iter()
            .map(|b| VariantLod {
                errors: [0, 1, 2].map(|k| b.errors.get(k).copied().unwrap_or(f32::INFINITY)),
            })
            .collect();
        let (caches, impostors): (Vec<CacheLods>, Vec<Option<Impostor>>) =
            built.into_iter().map(|b| (b.cache, b.impostor)).unzip();
        let mut groups = Vec::new();
        let mut group_of = Vec::new();
        let mut variants = Vec::new();
        for (variant, (v, lod)) in builder.variants().iter().zip(&caches).enumerate() {
            let cache = &v.cache;
            // Every level's triangles one after another in one buffer per material.
            let (mut bark, mut leaves) = (Vec::new(), Vec::new());
            let mut offsets = Vec::new();
            for level in &lod.levels {
                offsets.push((bark.len() as u32, leaves.len() as u32));
                bark.extend_from_slice(&level.bark);
                leaves.extend_from_slice(&level.leaves);
            }
            let mut of = Vec::with_capacity(cache.instances.len());
            for (k, inst) in cache.instances.iter().enumerate() {
                if inst.bark.is_empty() && inst.leaves.is_empty() {
                    of.push(None);
                    continue;
                }
                let corners = cache.bark[inst.bark.range()]
                    .iter()
                    .chain(&cache.leaves[inst.leaves.range()])
                    .filter_map(|&i| cache.vertices.get(i as usize))
                    .map(|v| Vec3::from(v.position));
                let (centre, radius) = bounding_sphere(corners);
                let level = |l: usize| {
                    let (b, f) = lod
                        .levels
                        .get(l)
                        .and_then(|x| x.spans.get(k))
                        .copied()
                        .unwrap_or_default();
                    let (ob, of) = offsets.get(l).copied().unwrap_or_default();
                    (b.offset(ob), f.offset(of))
                };
                of.push(Some(groups.len() as u32));
                groups.push(Group {
                    variant,
                    levels: [level(0), level(1), level(2)],
                    // Grown cards reach a little beyond the full tree's.
                    sphere: (centre, radius * 1.15 + 0.5),
                });
            }
            group_of.push(of);
            let s = &species[v.species];
            variants.push(VariantGeometry {
                vertices: lod.vertices.clone(),
                bark,
                leaves,
                bark_colour: s.bark,
                leaf_colour: s.leaf,
                leaf_shape: s.leaf_shape,
                bark_pattern: s.bark_pattern,
                textured_leaves: true,
            });
        }
        let mut atlases = Vec::new();
        let mut proxies: Vec<Proxy> = impostors
            .into_iter()
            .map(|impostor| match impostor {
                Some(i) => {
                    let number = (atlases.len() / 2) as f32;
                    atlases.push(i.colour.clone());
                    atlases.push(i.normal.clone());
                    Proxy::card(&i, number)
                }
                None => Proxy::none(),
            })
            .collect();
        let mut seedling: Vec<bool> = builder.variants().iter().map(|v| v.seedling).collect();
        // The forest floor: its kinds drawn as variants after the trees' (none around a
        // specimen, which stands alone on its ground).
        let (floor, first_floor_group) = if options.specimen || !options.floor {
            (None, None)
        } else {
            let parts = crate::floor::floor_parts(&chain, variants.len())?;
            let first = groups.len() as u32;
            variants.extend(parts.variants);
            groups.extend(parts.groups);
            lods.extend(parts.lods);
            proxies.extend(parts.proxies);
            seedling.extend(std::iter::repeat_n(false, GroundKind::ALL.len()));
            let floor = floor_of(&builder, options.seed);
            (Some(floor), Some(first))
        };
        Ok(World {
            forest: RwLock::new(Recipe {
                builder: Arc::new(builder),
                version: 0,
                layer,
            }),
            heightmap,
            side,
            variants,
            groups,
            group_of,
            proxies,
            lods,
            atlases,
            seedling,
            floor,
            first_floor_group,
            years,
            own_patch,
            seed: options.seed,
        })
    }

    /// This world's forest (its recipe and geometry, kept) on other ground and at another
    /// density: milliseconds where [`World::build`] takes seconds of hero trees, levels of
    /// detail and impostors. `None` for a world it cannot carry over: a forest over time, a
    /// specimen's, or a painted one (whose painting is carried over apart).
    pub(crate) fn on_ground(
        &self,
        heightmap: Heightmap,
        density: Option<f32>,
    ) -> Result<Option<World>, ViewerError> {
        if self.years.is_some() || self.layer().is_some() {
            return Ok(None);
        }
        // A square world over the whole map, as `build` makes one on a map given.
        let side = (heightmap.size() - 1) as f32 * heightmap.spacing();
        if !(side > 10.0 && side <= 20_000.0) {
            return Err(ViewerError::WorldSize { side });
        }
        let mut builder = ForestBuilder::clone(&self.forest().0);
        builder.density_mut().patch = density.map_or(self.own_patch, |d| (10_000.0 / d).sqrt());
        let floor = self.floor.as_ref().map(|_| floor_of(&builder, self.seed));
        Ok(Some(World {
            forest: RwLock::new(Recipe {
                builder: Arc::new(builder),
                version: 0,
                layer: None,
            }),
            heightmap,
            side,
            variants: self.variants.clone(),
            groups: self.groups.clone(),
            group_of: self.group_of.clone(),
            proxies: self.proxies.clone(),
            lods: self.lods.clone(),
            atlases: self.atlases.clone(),
            floor,
            first_floor_group: self.first_floor_group,
            seedling: self.seedling.clone(),
            years: None,
            own_patch: self.own_patch,
            seed: self.seed,
        }))
    }
}

impl Proxy {
    /// Nothing: a variant with no impostor.
    pub(crate) fn none() -> Proxy {
        Proxy {
            vertices: Vec::new(),
            bark: Vec::new(),
            leaves: Vec::new(),
            sphere: (Vec3::ZERO, -1.0),
        }
    }

    /// The card of `impostor`, atlas number `number`; its bark material is filled in by the
    /// renderer, which knows the materials.
    fn card(impostor: &Impostor, number: f32) -> Proxy {
        let vertex = |x: f32, y: f32| Vertex {
            position: [x, y, 0.0],
            normal: impostor.centre,
            uv: [0.5 * x + 0.5, 0.5 - 0.5 * y],
            wind: [number, impostor.grid as f32, impostor.radius, 0.0],
        };
        Proxy {
            vertices: vec![
                vertex(-1.0, -1.0),
                vertex(1.0, -1.0),
                vertex(1.0, 1.0),
                vertex(-1.0, 1.0),
            ],
            bark: Vec::new(),
            leaves: vec![0, 1, 2, 0, 2, 3],
            sphere: (Vec3::from(impostor.centre), impostor.radius),
        }
    }
}

impl World {
    /// How many kinds of instanced draw the world has: every group's levels (group `k`'s
    /// level `l` is `k * MESH_LEVELS + l`), then every variant's impostor cards.
    pub(crate) fn slots(&self) -> usize {
        self.groups.len() * MESH_LEVELS + self.proxies.len()
    }

    /// The forest's recipe as it stands, and its version.
    pub(crate) fn forest(&self) -> (Arc<ForestBuilder>, u64) {
        let recipe = self.forest.read().unwrap_or_else(PoisonError::into_inner);
        (Arc::clone(&recipe.builder), recipe.version)
    }

    /// The layer the forest is painted with, if any.
    pub(crate) fn layer(&self) -> Option<Arc<PaintLayer>> {
        let recipe = self.forest.read().unwrap_or_else(PoisonError::into_inner);
        recipe.layer.clone()
    }

    /// The year its forest over time has reached, if it has one.
    pub(crate) fn year(&self) -> Option<u32> {
        self.years.as_ref().map(crate::years::Years::year)
    }

    /// Moves the forest over time on by `years` and draws the year reached from now on;
    /// returns the new version (`None` without a forest over time).
    pub(crate) fn advance_years(&self, years: u32) -> Result<Option<u64>, ForestError> {
        let Some(over_time) = &self.years else {
            return Ok(None);
        };
        let (builder, _) = self.forest();
        let drawn = over_time.advance(&builder, years)?;
        let mut recipe = self.forest.write().unwrap_or_else(PoisonError::into_inner);
        recipe.version += 1;
        recipe.builder = Arc::new(drawn);
        Ok(Some(recipe.version))
    }

    /// Paints the forest with `layer` from now on; returns the new version.
    pub(crate) fn repaint(&self, layer: Arc<PaintLayer>) -> Result<u64, ForestError> {
        let (builder, _) = self.forest();
        let composition: Arc<dyn Composition> = layer.clone();
        let painted = builder.with_composition(Some(composition))?;
        let mut recipe = self.forest.write().unwrap_or_else(PoisonError::into_inner);
        recipe.version += 1;
        recipe.builder = Arc::new(painted);
        recipe.layer = Some(layer);
        Ok(recipe.version)
    }
}

/// The forest floor of `builder`'s forest, drawn from the world's `seed`.
fn floor_of(builder: &ForestBuilder, seed: u64) -> ForestFloor {
    ForestFloor::of(
        builder,
        FloorOptions::default().with_seed(seed ^ 0xf100_5eed),
    )
}

/// A sphere given in an instance's own space, placed in the world by the instance.
pub(crate) fn world_sphere(i: &InstanceRaw, (centre, radius): (Vec3, f32)) -> (Vec3, f32) {
    let [x, y, z, scale] = i.translation_scale;
    let rotation = Quat::from_array(i.rotation);
    (
        Vec3::new(x, y, z) + rotation * (centre * scale),
        radius * scale,
    )
}

/// A bounding sphere in an instance's own space, as (centre, radius).
pub(crate) fn bounding_sphere(points: impl Iterator<Item = Vec3>) -> (Vec3, f32) {
    let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
    let mut all = Vec::new();
    for p in points {
        lo = lo.min(p);
        hi = hi.max(p);
        all.push(p);
    }
    if all.is_empty() {
        return (Vec3::ZERO, 0.0);
    }
    let centre = (lo + hi) * 0.5;
    let radius = all
        .iter()
        .map(|p| p.distance(centre))
        .fold(0.0f32, f32::max);
    (centre, radius)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sphere_holds_every_point() {
        let points = [
            Vec3::ZERO,
            Vec3::new(4.0, 1.0, 0.0),
            Vec3::new(-1.0, 6.0, 2.0),
        ];
        let (c, r) = bounding_sphere(points.into_iter());
        assert!(points.iter().all(|p| p.distance(c) <= r + 1e-5));
    }

    /// A real elevation model of any size is walked: the world is its largest square of
    /// land, at its heights, and a treeline keeps trees below it.
    #[test]
    fn a_real_model_is_the_world() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../terrain/tests/data/dems/west_bijou_escarpment.asc"
        );
        let model = ElevationModel::read(path, &ReadOptions::default()).unwrap();
        let [x, z] = model.extent();
        let cropped = Window {
            column: 10,
            row: 5,
            width: 60,
            height: 40,
        };
        let options = SceneOptions {
            terrain: Some(TerrainFile {
                path: path.into(),
                spacing: None,
                crop: Some(cropped),
            }),
            ..SceneOptions::small(2, 100.0)
        };
        let world = World::build(options.clone()).unwrap();
        let part = model.crop(cropped).unwrap();
        let side = part.extent()[0].min(part.extent()[1]);
        assert!((world.side - side).abs() < 1e-2, "{} {side}", world.side);
        assert!(world.side < x.min(z));
        let map = &world.heightmap;
        let stats = map.stats();
        let (lo, hi) = part
            .heights
            .iter()
            .fold((f32::MAX, f32::MIN), |(a, b), &h| (a.min(h), b.max(h)));
        assert!(stats.min >= lo - 0.01 && stats.max <= hi + 0.01);
        // A treeline at the middle height: every tree stands below it.
        let treeline = (stats.min + stats.max) / 2.0;
        let below = World::build(SceneOptions {
            constraints: Constraints::default().with_height_range(f32::NEG_INFINITY, treeline),
            ..options
        })
        .unwrap();
        let whole = Rect::new(Vec2::ZERO, Vec2::splat(below.side));
        let trees = below.forest().0.trees(&below.heightmap, whole);
        assert!(!trees.is_empty());
        assert!(trees.iter().all(|t| t.position[1] <= treeline));
    }

    #[test]
    fn a_model_larger_than_a_world_asks_for_a_crop() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../terrain/tests/data/dems/N44W072.hgt"
        );
        let file = |crop| TerrainFile {
            path: path.into(),
            spacing: None,
            crop,
        };
        let message = file(None).heightmap().unwrap_err().to_string();
        assert!(message.contains("--crop"), "{message}");
        assert!(
            file(Some(Window {
                column: 0,
                row: 0,
                width: 100,
                height: 100
            }))
            .heightmap()
            .is_ok()
        );
    }
}
