//! `sylva.Forest`: a world built once (species, terrain, seed, region) as the `sylva`
//! command builds it, then written as glTF, USD or 3D Tiles, or read as NumPy arrays of
//! trees and placements, and each branch instance's mesh.

use std::path::PathBuf;

use numpy::{PyArray2, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use sylva::export::{
    GltfOptions, TileScheme, TilesetOptions, UsdOptions, check_tileset_folder, write_glb,
    write_tile, write_tileset, write_usda,
};
use sylva::forest::{PlacementBlock, Rect};
use sylva::terrain::dem::Window;
use sylva::terrain::glam::Vec2;
use sylva::turtle::Vertex;
use sylva::world::limits::{
    DEFAULT_GROUP, DEFAULT_SIDE, DEFAULT_TILE_SIZE, MAX_TREES, check_budget_mb,
};
use sylva::world::{Ground, World, WorldBuilder};

use crate::arrays::{column, dict, figures, rows, triangles};
use crate::columns::{PlacementColumns, TreeColumns};
use crate::errors::{Raise, Raised, invalid};
use crate::ground::{ground_mesh, ground_of};
use crate::progress::Callback;
use crate::tree::{day_of, file_size, species_material};

/// Most placements `Forest.placements` reads at once: 25 million (1.1 GB of arrays, a
/// million canopy trees' worth); a larger forest is read a region at a time.
const MAX_READ_PLACEMENTS: usize = 25_000_000;

/// A forest: species on ground, built once as the `sylva` command builds it.
///
/// Forest(*, area=800, species=None, seed=1, terrain=None, spacing=None, crop=None,
/// density=None, budget_mb=None, season=None, year=None, progress=None). Without `species`
/// the five bundled species (oak, birch, spruce, pine, hazel) grow; give bundled names
/// (sylva.species_names()) or species files. `terrain` is an elevation model's file
/// (GeoTIFF, SRTM .hgt, ESRI ASCII grid, 16-bit PNG) or a 2-D array of heights in metres,
/// row 0 the north edge, `spacing` metres apart (needed for an array, or a file that does
/// not say); a model larger than 1000 m gives its middle 1000 m (Forest.notes says which
/// window), or the window `crop` names: (column, row, width, height) in samples, from its
/// north-west corner. Without it, `area` metres of generated terrain. `density` is canopy
/// trees per hectare, `budget_mb` the instance cache's size (default: sized to the forest),
/// `season` a day of the year or a season's name, `year` draws the forest as it stands in
/// that year of a forest over time. `progress(stage, done, total)` hears how the build goes.
/// The GIL is released while it builds.
#[pyclass(module = "sylva", name = "Forest", frozen)]
#[derive(Debug)]
pub(crate) struct Forest {
    world: World,
    notes: Vec<String>,
}

#[pymethods]
impl Forest {
    #[new]
    #[pyo3(signature = (
        *, area = None, species = None, seed = 1, terrain = None, spacing = None,
        crop = None, density = None, budget_mb = None, season = None, year = None,
        progress = None
    ))]
    #[allow(
        clippy::too_many_arguments,
        reason = "Python's keyword arguments, each a setting of the world"
    )]
    fn new(
        py: Python<'_>,
        area: Option<f32>,
        species: Option<Vec<String>>,
        seed: u64,
        terrain: Option<Bound<'_, PyAny>>,
        spacing: Option<f32>,
        crop: Option<(usize, usize, usize, usize)>,
        density: Option<f32>,
        budget_mb: Option<u32>,
        season: Option<Bound<'_, PyAny>>,
        year: Option<u32>,
        progress: Option<Py<PyAny>>,
    ) -> PyResult<Forest> {
        let season = season.as_ref().map(day_of).transpose()?;
        // The limit every front end checks (world::limits), the server's and the CLI's.
        if let Some(Err(e)) = budget_mb.map(|mb| check_budget_mb(mb.into())) {
            return Err(invalid(format!("budget_mb {e}")));
        }
        let crop = crop.map(|(column, row, width, height)| Window {
            column,
            row,
            width,
            height,
        });
        let ground = ground_of(terrain.as_ref(), spacing, crop)?;
        let callback = Callback::new(progress);
        let built = py.detach(|| {
            let species = match &species {
                None => sylva::presets::species()?,
                Some(names) => names
                    .iter()
                    .map(sylva::presets::named_or_file)
                    .collect::<Result<Vec<_>, _>>()?,
            };
            let mut recipe = WorldBuilder::new(species)
                .with_seed(seed)
                .with_density(density)
                .with_season(season)
                .with_year(year);
            recipe.budget = budget_mb.map(|mb| mb as usize * (1 << 20));
            let (ground, notes) = match ground {
                Some(ground) => {
                    let notes = ground.notes("terrain");
                    (ground, notes)
                }
                None => (
                    Ground::generated(seed, area.unwrap_or(DEFAULT_SIDE))?,
                    Vec::new(),
                ),
            };
            // As the `sylva` command builds a world: the budget sized to the ground's canopy
            // trees, the same bytes for the same settings.
            let world = recipe.build(ground, &callback)?;
            Ok::<_, Raised>(Forest { world, notes })
        });
        callback.finish(built.raise())
    }

    /// Metres along the world's longer side.
    #[getter]
    fn side(&self) -> f32 {
        self.world.side()
    }

    /// The region the trees stand in: ((x0, z0), (x1, z1)), metres.
    #[getter]
    fn region(&self) -> ((f32, f32), (f32, f32)) {
        let r = self.world.region();
        ((r.min.x, r.min.y), (r.max.x, r.max.y))
    }

    /// The world seed.
    #[getter]
    fn seed(&self) -> u64 {
        self.world.seed
    }

    /// What was made of an elevation model: the window taken of a larger one, cells
    /// filled. Empty for generated terrain.
    #[getter]
    fn notes(&self) -> Vec<String> {
        self.notes.clone()
    }

    /// The terrain's heights, metres (float32, rows x columns, row 0 at z = 0), `spacing`
    /// apart.
    #[getter]
    fn heights<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f32>>> {
        let map = &self.world.ground.map;
        let size = map.size();
        column(py, map.heights().to_vec()).reshape([size, size])
    }

    /// Metres between the terrain's samples.
    #[getter]
    fn spacing(&self) -> f32 {
        self.world.ground.map.spacing()
    }

    /// The species' names, in order (a variant's `species` indexes it).
    #[getter]
    fn species(&self) -> Vec<String> {
        let config = self.world.forest.config();
        config.species.iter().map(|s| s.name.clone()).collect()
    }

    /// How each species is drawn, in Forest.species' order: a list of dicts as
    /// Tree.material gives them (colours, bark and leaf textures as PNG bytes, the alpha
    /// cutoff).
    fn materials<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
        let config = self.world.forest.config();
        config
            .species
            .iter()
            .map(|s| species_material(py, s))
            .collect()
    }

    /// The forest's variants (a species at one age or form, each with its instance cache):
    /// a list of dicts with `species` (an index into Forest.species), `seedling`,
    /// `generations`, `form` and `instances` (how many branch instances its cache holds).
    fn variants<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
        self.world
            .forest
            .variants()
            .iter()
            .map(|v| {
                dict(
                    py,
                    [
                        ("species", v.species.into_pyobject(py)?.into_any()),
                        (
                            "seedling",
                            v.seedling.into_pyobject(py)?.to_owned().into_any(),
                        ),
                        ("generations", v.generations.into_pyobject(py)?.into_any()),
                        (
                            "form",
                            format!("{:?}", v.form).into_pyobject(py)?.into_any(),
                        ),
                        (
                            "instances",
                            v.cache.instances.len().into_pyobject(py)?.into_any(),
                        ),
                    ],
                )
            })
            .collect()
    }

    /// The trees, in the order the forest streams them (block by block): `position`
    /// (float32, n x 3, the root on the ground), `yaw` (radians about +y), `scale`,
    /// `variant` (uint16, an index into Forest.variants()), `species` (uint16, an index into
    /// Forest.species) and `seed` (uint32, each tree's own).
    fn trees<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let (world, variants) = (&self.world, self.world.forest.variants());
        let mut t = TreeColumns::default();
        py.detach(|| {
            world.forest.stream_with(
                &world.ground.map,
                world.region(),
                &|_| false,
                &mut |block: &PlacementBlock| {
                    t.extend(block, variants);
                    if t.position.len() > MAX_TREES {
                        return Err(Raised::Other(format!("more than {MAX_TREES} trees")));
                    }
                    Ok(())
                },
            )
        })
        .raise()?;
        t.into_dict(py)
    }

    /// Every placement of a branch instance with geometry (the forest as a renderer draws
    /// it, and as the files hold it), in the forest's streaming order, within `region`
    /// ((x0, z0), (x1, z1)) when given: `position` (float32, n x 3), `rotation` (float32, n x 4, a unit quaternion x, y, z, w), `scale`
    /// (float32), `variant` and `instance` (uint32: the mesh, Forest.instance_mesh), and
    /// `tree` (uint32: for the whole forest the tree's index in Forest.trees(); for a region,
    /// among the region's trees in streaming order). At most 25 million placements at once.
    #[pyo3(signature = (region = None))]
    fn placements<'py>(
        &self,
        py: Python<'py>,
        region: Option<((f32, f32), (f32, f32))>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let world = &self.world;
        let region = match region {
            Some(((x0, z0), (x1, z1))) => Rect::new(Vec2::new(x0, z0), Vec2::new(x1, z1)),
            None => world.region(),
        };
        let mut p = PlacementColumns::drawing(world.forest.variants());
        py.detach(|| {
            world.forest.stream_with(
                &world.ground.map,
                region,
                &|_| true,
                &mut |block: &PlacementBlock| {
                    p.extend(block);
                    if p.position.len() > MAX_READ_PLACEMENTS {
                        return Err(Raised::Other(format!(
                            "more than {MAX_READ_PLACEMENTS} placements: read them a region \
                             at a time (placements(region=...))"
                        )));
                    }
                    Ok(())
                },
            )
        })
        .raise()?;
        p.into_dict(py)
    }

    /// The mesh of branch instance `instance` of variant `variant`, as placements place it:
    /// a dict of `positions`, `normals` (float32, n x 3), `uvs` (n x 2), `bark` and `leaves`
    /// (uint32 triangles indexing these vertices).
    fn instance_mesh<'py>(
        &self,
        py: Python<'py>,
        variant: usize,
        instance: usize,
    ) -> PyResult<Bound<'py, PyDict>> {
        let variants = self.world.forest.variants();
        let cache = &variants
            .get(variant)
            .ok_or_else(|| {
                invalid(format!(
                    "variant {variant}: the forest has {}",
                    variants.len()
                ))
            })?
            .cache;
        let inst = cache.instances.get(instance).ok_or_else(|| {
            invalid(format!(
                "instance {instance}: variant {variant} has {}",
                cache.instances.len()
            ))
        })?;
        let span = |s: sylva::instancing::Span, all: &[u32]| -> Vec<u32> {
            all.get(s.start as usize..s.end() as usize)
                .unwrap_or_default()
                .to_vec()
        };
        let (bark, leaves) = (
            span(inst.bark, &cache.bark),
            span(inst.leaves, &cache.leaves),
        );
        // The vertices the instance's triangles use, in the cache's order, renumbered from 0.
        let mut used: Vec<u32> = bark.iter().chain(&leaves).copied().collect();
        used.sort_unstable();
        used.dedup();
        let vertices: Vec<&Vertex> = used
            .iter()
            .filter_map(|&i| cache.vertices.get(i as usize))
            .collect();
        let renumber = |v: Vec<u32>| -> Vec<u32> {
            v.into_iter()
                .map(|i| used.binary_search(&i).unwrap_or_default() as u32)
                .collect()
        };
        dict(
            py,
            [
                (
                    "positions",
                    rows(py, vertices.iter().map(|v| v.position).collect())?.into_any(),
                ),
                (
                    "normals",
                    rows(py, vertices.iter().map(|v| v.normal).collect())?.into_any(),
                ),
                (
                    "uvs",
                    rows(py, vertices.iter().map(|v| v.uv).collect())?.into_any(),
                ),
                ("bark", triangles(py, renumber(bark))?.into_any()),
                ("leaves", triangles(py, renumber(leaves))?.into_any()),
            ],
        )
    }

    /// Writes the forest and its terrain as one binary glTF, as `sylva forest` does (the
    /// same bytes for the same world). With `instancing=False` every placement is a node of
    /// its own, for importers without EXT_mesh_gpu_instancing (at most 250,000). Returns
    /// a dict of figures: `trees`, `seedlings`, `placements`, `instance_nodes`, `bytes`.
    #[pyo3(signature = (path, *, instancing = true, progress = None))]
    fn write_glb<'py>(
        &self,
        py: Python<'py>,
        path: PathBuf,
        instancing: bool,
        progress: Option<Py<PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let world = &self.world;
        let callback = Callback::new(progress);
        let stats = py.detach(|| {
            callback.tell("writing glTF", 0, 1);
            let map = &world.ground.map;
            let mesh = ground_mesh(map)?;
            let mut options = GltfOptions::default();
            options.one_node_per_placement = !instancing;
            let stats = write_glb(
                &world.forest,
                map,
                world.region(),
                Some(&mesh),
                &options,
                &path,
            )?;
            callback.tell("writing glTF", 1, 1);
            Ok::<_, Raised>(stats)
        });
        let stats = callback.finish(stats.raise())?;
        figures(
            py,
            [
                ("trees", stats.trees as u64),
                ("seedlings", stats.seedlings as u64),
                ("placements", stats.placements as u64),
                ("instance_nodes", stats.instance_nodes as u64),
                ("bytes", stats.bytes as u64),
            ],
        )
    }

    /// Writes the forest and its terrain as USD text (.usda): one point instancer whose
    /// prototypes are the branch instances, with its textures in a folder beside it, as
    /// `sylva forest --usd` does. Returns a dict of figures: `trees`, `seedlings`,
    /// `placements`, `prototypes`, `images`, `bytes`.
    fn write_usd<'py>(&self, py: Python<'py>, path: PathBuf) -> PyResult<Bound<'py, PyDict>> {
        let world = &self.world;
        let stats = py
            .detach(|| {
                let map = &world.ground.map;
                let mesh = ground_mesh(map)?;
                let options = UsdOptions::default();
                Ok::<_, Raised>(write_usda(
                    &world.forest,
                    map,
                    world.region(),
                    Some(&mesh),
                    &options,
                    &path,
                )?)
            })
            .raise()?;
        figures(
            py,
            [
                ("trees", stats.trees as u64),
                ("seedlings", stats.seedlings as u64),
                ("placements", stats.placements as u64),
                ("prototypes", stats.prototypes as u64),
                ("images", stats.images as u64),
                ("bytes", stats.bytes),
            ],
        )
    }

    /// Writes the forest as a 3D Tiles tileset in the folder `path` (tileset.json, shared
    /// geometry and a GLB per tile), as `sylva tiles` does, tiles `tile_size` metres a side
    /// grouped `group` to a coarse tile. `progress("tiles", done, total)` hears each tile,
    /// and an exception it raises stops the writing. Returns a dict of figures: `tiles`,
    /// `trees`, `bytes`.
    #[pyo3(signature = (path, *, tile_size = DEFAULT_TILE_SIZE, group = DEFAULT_GROUP, progress = None))]
    fn write_tiles<'py>(
        &self,
        py: Python<'py>,
        path: PathBuf,
        tile_size: f32,
        group: u32,
        progress: Option<Py<PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let world = &self.world;
        let callback = Callback::new(progress);
        let written = py.detach(|| {
            check_tileset_folder(&path).raise()?;
            let (builder, map) = (&world.forest, &world.ground.map);
            let scheme = TileScheme::new(world.region(), tile_size, group).raise()?;
            let root =
                write_tileset(builder, map, &scheme, &path, &TilesetOptions::default()).raise()?;
            let ids = scheme.ids();
            let (mut trees, mut bytes) = (0u64, root as u64);
            for (k, id) in ids.iter().enumerate() {
                let s = write_tile(builder, map, &scheme, *id, &path).raise()?;
                trees += s.trees as u64;
                bytes += s.bytes as u64;
                callback.tell("tiles", k as u64 + 1, ids.len() as u64);
                callback.check()?;
            }
            Ok::<_, PyErr>((ids.len() as u64, trees, bytes))
        });
        let (tiles, trees, bytes) = callback.finish(written)?;
        figures(py, [("tiles", tiles), ("trees", trees), ("bytes", bytes)])
    }

    /// Writes the terrain as a 16-bit PNG heightmap, as `sylva forest` writes
    /// forest_height.png. Returns the bytes written.
    fn write_heightmap(&self, py: Python<'_>, path: PathBuf) -> PyResult<u64> {
        let map = &self.world.ground.map;
        py.detach(|| {
            sylva::base::file::write(&path, |w| {
                map.write_png16(w).map(drop).map_err(std::io::Error::other)
            })
        })
        .raise()?;
        file_size(&path)
    }

    fn __repr__(&self) -> String {
        let names = self.species().join(", ");
        format!(
            "<sylva.Forest {:.0} m, seed {}, {names}>",
            self.world.side(),
            self.world.seed
        )
    }
}
