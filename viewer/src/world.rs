//! What never changes while the camera moves: the forest's recipe, the terrain, and the
//! geometry every placement refers to, shared by the streaming, the culling and the drawing.

use bytemuck::{Pod, Zeroable};
use std::sync::{Arc, PoisonError, RwLock};

use sylva::forest::{
    BarkPattern, Composition, Extent, ForestBuilder, ForestConfig, ForestError, LeafShape, Species,
    tree_proxy,
};
use sylva::instancing::Span;
use sylva::paint::PaintLayer;
use sylva::terrain::Heightmap;
use sylva::terrain::glam::{Quat, Vec3};
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

/// One species variant's shared buffers.
pub(crate) struct VariantGeometry {
    pub(crate) vertices: Vec<Vertex>,
    pub(crate) bark: Vec<u32>,
    pub(crate) leaves: Vec<u32>,
    pub(crate) bark_colour: [f32; 3],
    pub(crate) leaf_colour: [f32; 3],
    pub(crate) leaf_shape: LeafShape,
    pub(crate) bark_pattern: BarkPattern,
}

/// One cached instance drawn with its placements: one instanced draw per non-empty index
/// range. Its placements live in the streamed cells.
pub(crate) struct Group {
    pub(crate) variant: usize,
    pub(crate) bark: Span,
    pub(crate) leaves: Span,
    /// A sphere around the instance's triangles in its own space (centre, radius), with room
    /// for the wind's sway.
    pub(crate) sphere: (Vec3, f32),
}

/// A variant's whole-tree proxy (`sylva_forest::tree_proxy`), drawn for trees far from the
/// camera: trunk in `bark`, crown in `leaves`.
pub(crate) struct Proxy {
    pub(crate) vertices: Vec<Vertex>,
    pub(crate) bark: Vec<u32>,
    pub(crate) leaves: Vec<u32>,
    /// A sphere around it in the tree's own space (centre, radius).
    pub(crate) sphere: (Vec3, f32),
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
    /// Per variant: whether it is a seedling form (left out of coarse cells, as coarse tiles
    /// leave it out).
    pub(crate) seedling: Vec<bool>,
}

/// How to build a [`World`].
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
        let mut builder = ForestBuilder::new(config)?;
        let patch = builder.density().patch;
        let side = match options.trees {
            _ if options.specimen => crate::turntable::world_patches(patch) as f32 * patch,
            Some(n) => builder.side_for_canopy_trees(n as usize),
            None => options.side,
        };
        if options.specimen {
            builder = builder.with_composition(Some(crate::turntable::specimen(patch)))?;
        }
        if !(side > 10.0 && side <= 20_000.0) {
            return Err(ViewerError::WorldSize { side });
        }
        let heightmap = sylva::presets::terrain(options.seed, side)?;
        let mut layer = None;
        if let Some(dir) = &options.paint {
            let loaded = Arc::new(sylva::paint::load_masks_for(&builder, dir, &heightmap)?);
            let composition: Arc<dyn Composition> = loaded.clone();
            builder = builder.with_composition(Some(composition))?;
            layer = Some(loaded);
        }
        let species = &builder.config().species;
        let mut groups = Vec::new();
        let mut group_of = Vec::new();
        for (variant, v) in builder.variants().iter().enumerate() {
            let cache = &v.cache;
            let mut of = Vec::with_capacity(cache.instances.len());
            for inst in &cache.instances {
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
                of.push(Some(groups.len() as u32));
                groups.push(Group {
                    variant,
                    bark: inst.bark,
                    leaves: inst.leaves,
                    sphere: (centre, radius * 1.1 + 0.5),
                });
            }
            group_of.push(of);
        }
        let proxies = builder
            .variants()
            .iter()
            .map(|v| {
                let mesh = tree_proxy(Extent::of(v));
                let (centre, radius) =
                    bounding_sphere(mesh.vertices.iter().map(|v| Vec3::from(v.position)));
                Proxy {
                    vertices: mesh.vertices,
                    bark: mesh.bark,
                    leaves: mesh.leaves,
                    sphere: (centre, radius * 1.1 + 0.5),
                }
            })
            .collect();
        let variants = builder
            .variants()
            .iter()
            .map(|v| {
                let s = &species[v.species];
                VariantGeometry {
                    vertices: v.cache.vertices.clone(),
                    bark: v.cache.bark.clone(),
                    leaves: v.cache.leaves.clone(),
                    bark_colour: s.bark,
                    leaf_colour: s.leaf,
                    leaf_shape: s.leaf_shape,
                    bark_pattern: s.bark_pattern,
                }
            })
            .collect();
        let seedling = builder.variants().iter().map(|v| v.seedling).collect();
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
            seedling,
        })
    }
}

impl World {
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
}
