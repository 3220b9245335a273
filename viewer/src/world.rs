//! What never changes while the camera moves: the forest's recipe, the terrain, and the
//! geometry every placement refers to, shared by the streaming, the culling and the drawing.
//! The world itself (species, ground, paint, year) is assembled by the world layer
//! (`sylva::world`), as the CLI's and the server's are; this adds what the GPU draws.

use std::sync::{Arc, PoisonError, RwLock};

use rayon::prelude::*;
use sylva::export::Texture;
use sylva::export::lod::{CacheLods, Impostor, VariantLods};
use sylva::forest::{
    Composition, Constraints, FloorOptions, ForestBuilder, ForestError, ForestFloor, GroundKind,
    Rect, Species,
};
use sylva::paint::PaintLayer;
use sylva::terrain::Heightmap;
use sylva::terrain::dem::{ReadOptions, Window};
use sylva::terrain::glam::Vec3;
use sylva::world::limits::{DEFAULT_REGION_SIDE, MAX_SIDE, MIN_SIDE};
use sylva::world::{Fit, Ground, Progress, Stage, WorldBuilder, density_patch};

use crate::error::ViewerError;
use crate::floor::FloorParts;
use crate::geometry::{
    Group, InstanceRaw, MESH_LEVELS, Proxy, VariantGeometry, VariantLod, bounding_sphere, lod_chain,
};

/// The world layer's stages as lines on stderr, for those that take over a second.
struct Lines;

impl Progress for Lines {
    fn end(&self, stage: Stage, elapsed: std::time::Duration) {
        if stage == Stage::Years || elapsed.as_secs_f32() > 1.0 {
            eprintln!("{}: {:.1} s", stage.describe(), elapsed.as_secs_f64());
        }
    }
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
    /// Instance-cache bytes; none: sized to the forest (`WorldBuilder::budget_for`).
    pub(crate) budget: Option<usize>,
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
    /// used): its middle square of at most 1000 m (the world layer's default region), or
    /// the window its crop names.
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
    /// The model's ground: the window its crop names, else its middle square of at most
    /// [`DEFAULT_REGION_SIDE`] (land on every side of the viewer's square world); says what
    /// was filled and chosen.
    pub(crate) fn ground(&self) -> Result<Ground, ViewerError> {
        let options = ReadOptions {
            spacing: self.spacing,
            ..ReadOptions::default()
        };
        let fit = Fit::MiddleSquare {
            side: DEFAULT_REGION_SIDE,
        };
        let ground = Ground::read(&self.path, &options, self.crop, fit, "--spacing M")?;
        for note in ground.notes(&self.path.display().to_string()) {
            eprintln!("{note}");
        }
        Ok(ground)
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
            budget: Some(8 << 20),
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
        // The ground first: a model's mistake is reported before seconds of hero trees.
        let ground = match options.ground {
            Some((map, extent)) => Some(Ground {
                map,
                extent,
                chosen: None,
                filled: 0,
            }),
            None => options
                .terrain
                .as_ref()
                .map(TerrainFile::ground)
                .transpose()?,
        };
        // The species' own density is kept, for a world carried onto other ground.
        let mut recipe = WorldBuilder::new(options.species)
            .with_seed(options.seed)
            .with_density(options.density)
            .with_constraints(options.constraints)
            .with_year(options.year)
            .with_masks(options.paint.clone())
            .with_seedlings(!options.specimen);
        recipe.budget = options.budget;
        // The budget follows the forest's canopy trees, as the `sylva` command's does.
        let trees = options.trees.map(|n| n as usize);
        let canopy_trees = recipe.canopy_trees_expected(ground.as_ref(), trees, options.side);
        let mut builder = recipe.forest(canopy_trees, &Lines)?;
        let own_patch = builder.density().patch;
        if let Some(d) = options.density {
            builder.density_mut().patch = density_patch(d);
        }
        let patch = builder.density().patch;
        let ground = match ground {
            Some(ground) => ground,
            None => {
                let side = match options.trees {
                    _ if options.specimen => crate::specimen::world_patches(patch) as f32 * patch,
                    Some(n) => builder.side_for_canopy_trees(n as usize),
                    None => options.side,
                };
                Ground::generated(options.seed, side)?
            }
        };
        if options.specimen {
            builder = builder.with_composition(Some(crate::specimen::specimen(patch)))?;
        }
        // The viewer's world is square: the ground's shorter side, so every sample of it is
        // the model's own land (the default region is square within a sample).
        let side = ground.extent[0].min(ground.extent[1]);
        let built = recipe.finish(builder, ground, &Lines)?;
        let (builder, heightmap, layer) = (built.forest, built.ground.map, built.layer);
        let years = built.succession.map(crate::years::Years::of);
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
                if !inst.has_geometry() {
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
                phenology: Some(s.phenology),
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
            let parts: FloorParts = crate::floor::floor_parts(&chain, variants.len())?;
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
        if !(MIN_SIDE..=MAX_SIDE).contains(&side) {
            return Err(ViewerError::Usage(format!(
                "a world of {side} m: expected {MIN_SIDE} to {MAX_SIDE} metres a side"
            )));
        }
        let mut builder = ForestBuilder::clone(&self.forest().0);
        builder.density_mut().patch = density.map_or(self.own_patch, density_patch);
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

impl World {
    /// The floor items of the cell over `rect`, as placements tagged with their groups:
    /// shaded by the canopy trees of the forest as it stands.
    pub(crate) fn floor_instances(
        &self,
        floor: &ForestFloor,
        rect: Rect,
    ) -> Result<Vec<(u32, InstanceRaw)>, ForestError> {
        let (forest, _) = self.forest();
        let trees = forest.trees(&self.heightmap, rect.expanded(floor.reach()));
        let items = floor.items(&self.heightmap, rect, &trees)?;
        Ok(items
            .iter()
            .filter_map(|item| {
                let k = GroundKind::ALL.iter().position(|&g| g == item.kind)?;
                Some((
                    self.first_floor_group? + k as u32,
                    crate::floor::instance(item),
                ))
            })
            .collect())
    }
}

/// The forest floor of `builder`'s forest, drawn from the world's `seed`.
fn floor_of(builder: &ForestBuilder, seed: u64) -> ForestFloor {
    ForestFloor::of(
        builder,
        FloorOptions::default().with_seed(seed ^ 0xf100_5eed),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A real elevation model's window is walked: the world is the largest square of its
    /// land, at its heights, and a treeline keeps trees below it.
    #[test]
    fn a_real_model_is_the_world() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../terrain/tests/data/dems/west_bijou_escarpment.asc"
        );
        let model =
            sylva::terrain::dem::ElevationModel::read(path, &ReadOptions::default()).unwrap();
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
        let whole = Rect::new(
            sylva::terrain::glam::Vec2::ZERO,
            sylva::terrain::glam::Vec2::splat(below.side),
        );
        let trees = below.forest().0.trees(&below.heightmap, whole);
        assert!(!trees.is_empty());
        assert!(trees.iter().all(|t| t.position[1] <= treeline));
    }

    /// A model of any size makes a world: an SRTM tile (80 x 111 km) gives its middle
    /// square of at most 1000 m, and a crop names another window.
    #[test]
    fn a_large_model_gives_its_middle_square() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../terrain/tests/data/dems/N44W072.hgt"
        );
        let file = |crop| TerrainFile {
            path: path.into(),
            spacing: None,
            crop,
        };
        let middle = file(None).ground().unwrap();
        let chosen = middle.chosen.expect("a window was chosen");
        assert!(chosen.note().contains("--crop"), "{}", chosen.note());
        assert!(middle.side() <= DEFAULT_REGION_SIDE && middle.side() > 900.0);
        assert!((middle.extent[0] - middle.extent[1]).abs() < 100.0);
        let window = Window {
            column: 0,
            row: 0,
            width: 100,
            height: 100,
        };
        let cropped = file(Some(window)).ground().unwrap();
        assert!(cropped.chosen.is_none() && cropped.side() > 6000.0);
    }
}
