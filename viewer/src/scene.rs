//! The CPU side of the viewer: the world (forest recipe, terrain and the geometry placements
//! refer to), the cells streamed in around the camera, and the camera.

use bytemuck::{Pod, Zeroable};
use std::sync::{Arc, PoisonError, RwLock};

use sylva::forest::{
    BarkPattern, Composition, Extent, ForestBuilder, ForestConfig, LeafShape, Species, tree_proxy,
};
use sylva::instancing::Span;
use sylva::paint::PaintLayer;

use crate::cells::{Cells, Streamed, VIEW_DISTANCE};
use crate::cull::bounding_sphere;
use sylva::terrain::glam::{Mat4, Vec3};
use sylva::terrain::{HeightField, Heightmap, TerrainVertex};
use sylva::turtle::Vertex;

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

/// The world and the cells of it streamed in around the camera.
pub(crate) struct Scene {
    pub(crate) world: Arc<World>,
    pub(crate) terrain_vertices: Vec<TerrainVertex>,
    pub(crate) terrain_indices: Vec<u32>,
    pub(crate) cells: Cells,
}

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
}

#[cfg(test)]
impl SceneOptions {
    /// A small world for tests: the first two bundled species (oak and birch) on `side`
    /// metres, with a 4 MB instance cache.
    pub(crate) fn small(seed: u64, side: f32) -> SceneOptions {
        SceneOptions {
            seed,
            side,
            trees: None,
            species: default_species().expect("bundled species")[..2].to_vec(),
            budget: 4 << 20,
            paint: None,
        }
    }
}

/// The bundled species ([`sylva::presets::species`]).
pub(crate) fn default_species() -> Result<Vec<Species>, String> {
    sylva::presets::species().map_err(|e| e.to_string())
}

impl World {
    /// The forest's caches and the terrain ([`sylva::presets::terrain`], as the forest
    /// example's); no trees are placed until cells are streamed.
    pub(crate) fn build(options: SceneOptions) -> Result<World, String> {
        let mut config = ForestConfig::new(options.species);
        config.seed = options.seed;
        config.budget = options.budget;
        let mut builder = ForestBuilder::new(config).map_err(|e| e.to_string())?;
        let side = match options.trees {
            Some(n) => (n as f32).sqrt() * builder.density().patch,
            None => options.side,
        };
        if !(side > 10.0 && side <= 20_000.0) {
            return Err(format!(
                "a world of {side} m: expected 10 to 20000 metres a side"
            ));
        }
        let heightmap = sylva::presets::terrain(options.seed, side).map_err(|e| e.to_string())?;
        let mut layer = None;
        if let Some(dir) = &options.paint {
            let loaded = Arc::new(
                sylva::paint::load_masks_for(&builder, dir, &heightmap)
                    .map_err(|e| e.to_string())?,
            );
            let composition: Arc<dyn Composition> = loaded.clone();
            builder = builder
                .with_composition(Some(composition))
                .map_err(|e| e.to_string())?;
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
    pub(crate) fn repaint(&self, layer: Arc<PaintLayer>) -> Result<u64, String> {
        let (builder, _) = self.forest();
        let composition: Arc<dyn Composition> = layer.clone();
        let painted = builder
            .with_composition(Some(composition))
            .map_err(|e| e.to_string())?;
        let mut recipe = self.forest.write().unwrap_or_else(PoisonError::into_inner);
        recipe.version += 1;
        recipe.builder = Arc::new(painted);
        recipe.layer = Some(layer);
        Ok(recipe.version)
    }
}

impl Scene {
    /// The world with no cells streamed in yet.
    pub(crate) fn build(options: SceneOptions) -> Result<Scene, String> {
        let world = World::build(options)?;
        let terrain = world.heightmap.mesh(1).map_err(|e| e.to_string())?;
        Ok(Scene {
            world: Arc::new(world),
            terrain_vertices: terrain.vertices,
            terrain_indices: terrain.indices,
            cells: Cells::default(),
        })
    }

    /// The world's side in metres.
    pub(crate) fn side(&self) -> f32 {
        self.world.side
    }

    /// Brings the cells around `eye` in (see [`Cells::update`]).
    pub(crate) fn stream(
        &mut self,
        eye: Vec3,
        fine_everywhere: bool,
        wait: bool,
    ) -> Result<Streamed, String> {
        self.cells.update(&self.world, eye, fine_everywhere, wait)
    }

    /// Ground height under (x, z).
    pub(crate) fn ground(&self, x: f32, z: f32) -> f32 {
        self.world.heightmap.height(x, z)
    }
}

/// The camera's vertical field of view.
pub(crate) const FIELD_OF_VIEW_DEGREES: f32 = 60.0;

/// A camera held `height` metres above the terrain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Camera {
    pub(crate) x: f32,
    pub(crate) z: f32,
    pub(crate) yaw: f32,
    pub(crate) pitch: f32,
    pub(crate) height: f32,
}

impl Camera {
    /// Parses `x,z,yaw_degrees,pitch_degrees[,height]`.
    pub(crate) fn parse(text: &str) -> Result<Camera, String> {
        let v: Vec<f32> = text
            .split(',')
            .map(|s| s.trim().parse::<f32>())
            .collect::<Result<_, _>>()
            .map_err(|e| format!("--camera '{text}': {e}"))?;
        if v.iter().any(|x| !x.is_finite()) {
            return Err(format!("--camera '{text}': numbers must be finite"));
        }
        match v.as_slice() {
            [x, z, yaw, pitch] => Ok(Camera {
                x: *x,
                z: *z,
                yaw: yaw.to_radians(),
                pitch: pitch.to_radians(),
                height: 1.7,
            }),
            [x, z, yaw, pitch, h] => Ok(Camera {
                x: *x,
                z: *z,
                yaw: yaw.to_radians(),
                pitch: pitch.to_radians(),
                height: *h,
            }),
            _ => Err(format!(
                "--camera '{text}': expected x,z,yaw,pitch[,height]"
            )),
        }
    }

    /// An overview from one corner of the map towards its centre, `height` above the ground.
    pub(crate) fn overview(side: f32, height: f32) -> Camera {
        let (x, z) = (side * 0.08, side * 0.08);
        let yaw = (side * 0.5 - z).atan2(side * 0.5 - x);
        Camera {
            x,
            z,
            yaw,
            pitch: -0.18,
            height,
        }
    }

    /// Walks `metres` along the heading, staying inside a world of side `side`.
    pub(crate) fn step(&mut self, metres: f32, side: f32) {
        let (s, c) = self.yaw.sin_cos();
        self.x = (self.x + c * metres).clamp(0.0, side);
        self.z = (self.z + s * metres).clamp(0.0, side);
    }

    pub(crate) fn forward(&self) -> Vec3 {
        Vec3::new(
            self.yaw.cos() * self.pitch.cos(),
            self.pitch.sin(),
            self.yaw.sin() * self.pitch.cos(),
        )
    }

    pub(crate) fn eye(&self, scene: &Scene) -> Vec3 {
        Vec3::new(self.x, scene.ground(self.x, self.z) + self.height, self.z)
    }

    pub(crate) fn view_proj(&self, scene: &Scene, aspect: f32) -> (Mat4, Vec3) {
        let eye = self.eye(scene);
        let view =
            sylva::terrain::glam::camera::rh::view::look_to_mat4(eye, self.forward(), Vec3::Y);
        // wgpu's clip space is Direct3D's: y up, depth from 0 to 1.
        let proj = sylva::terrain::glam::camera::rh::proj::directx::perspective(
            FIELD_OF_VIEW_DEGREES.to_radians(),
            aspect.max(1e-3),
            0.2,
            VIEW_DISTANCE * 1.2,
        );
        (proj * view, eye)
    }
}
