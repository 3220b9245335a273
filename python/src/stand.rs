//! `sylva.grow_stand`: trees grown together into their environment (the voxel growth
//! paper: light and collision), as meshes and a glTF file.

use std::path::PathBuf;

use numpy::{AllowTypeChange, PyArrayLike2};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use sylva::forest::{GrownStand, Planting, Species, StandOptions, grow_stand as grow};
use sylva::growth::Response;
use sylva::terrain::glam::Vec2;
use sylva::terrain::{FlatPlane, TerrainMesh};
use sylva::turtle::Skeleton;

use crate::arrays::figures;
use crate::errors::{Raise, Raised, invalid};
use crate::ground::{ground_mesh, ground_of};
use crate::progress::Callback;
use crate::tree::{Tree, file_size};

/// Most trees a stand grows, as `sylva grow` allows.
const MAX_STAND_TREES: usize = 400;

/// A grown stand: its trees and what growing them did.
///
/// sylva.grow_stand() makes one. `trees()` gives each tree as a sylva.Tree (its mesh and
/// skeleton as grown), `stats` the growth's figures, `write_glb` the stand as binary glTF.
#[pyclass(module = "sylva", name = "Stand", frozen)]
#[derive(Debug)]
pub(crate) struct Stand {
    stand: GrownStand,
    /// The ground's mesh, when the stand grew on terrain given.
    terrain: Option<TerrainMesh>,
    species: Vec<Species>,
    seeds: Vec<u64>,
}

#[pymethods]
impl Stand {
    /// Each planting's tree as grown, in the order given.
    fn trees(&self, py: Python<'_>) -> Vec<Tree> {
        py.detach(|| {
            let meshes = self.stand.meshes(&self.species);
            meshes
                .into_iter()
                .zip(&self.stand.trees)
                .zip(&self.seeds)
                .map(|(((s, mesh), (_, grown)), &seed)| {
                    let mut skeleton = Skeleton::default();
                    grown.emit(&mut skeleton);
                    Tree {
                        species: self.species[s].clone(),
                        mesh,
                        skeleton,
                        seed,
                    }
                })
                .collect()
        })
    }

    /// What growing cost and did: `segments` grown, `deflected` round obstacles and
    /// neighbours, `aborted`, `stopped` by shade, light `samples`, `ray_steps`,
    /// `iterations`.
    #[getter]
    fn stats<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let s = &self.stand.stats;
        figures(
            py,
            [
                ("segments", s.segments),
                ("deflected", s.deflected),
                ("aborted", s.aborted),
                ("stopped", s.stopped),
                ("samples", s.samples),
                ("ray_steps", s.ray_steps),
                ("iterations", u64::from(s.iterations)),
            ],
        )
    }

    /// Writes the stand as binary glTF with its species' materials, and its terrain when it
    /// grew on terrain given. Returns the bytes written.
    fn write_glb(&self, py: Python<'_>, path: PathBuf) -> PyResult<u64> {
        let terrain = self.terrain.as_ref();
        py.detach(|| sylva::export::write_stand_glb(&self.stand, &self.species, terrain, &path))
            .raise()?;
        file_size(&path)
    }

    fn __repr__(&self) -> String {
        format!(
            "<sylva.Stand {} trees, {} segments>",
            self.stand.trees.len(),
            self.stand.stats.segments
        )
    }
}

/// Grows trees together, each competing for light and room (the voxel growth paper), on
/// flat ground at height 0, or on `terrain`: an elevation model's file or a 2-D array of
/// heights, `spacing` metres apart, as sylva.Forest takes it (x and z from its north-west
/// corner).
///
/// `positions` is an n x 2 array of (x, z) metres, one tree each (at most 400); `species`
/// a bundled species' name or a species file for all of them, or a list with one for each;
/// `seed` the stand's seed (each tree draws its own from it); `generations` overrides the
/// species'; `voxel` the side of the space's voxels in metres (0.05 to 1). The GIL is
/// released while it grows; `progress("growing", done, total)` hears the start and end.
#[pyfunction]
#[pyo3(signature = (
    positions, *, species = None, seed = 1, generations = None, voxel = 0.1, terrain = None,
    spacing = None, progress = None
))]
#[allow(
    clippy::too_many_arguments,
    reason = "Python's keyword arguments, each a setting of the stand"
)]
pub(crate) fn grow_stand(
    py: Python<'_>,
    positions: PyArrayLike2<'_, f32, AllowTypeChange>,
    species: Option<Bound<'_, PyAny>>,
    seed: u64,
    generations: Option<u32>,
    voxel: f32,
    terrain: Option<Bound<'_, PyAny>>,
    spacing: Option<f32>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Stand> {
    let ground = ground_of(terrain.as_ref(), spacing, None)?;
    let view = positions.as_array();
    let (n, columns) = view.dim();
    if columns != 2 {
        return Err(invalid(format!(
            "positions: expected n x 2 (x, z), got {n} x {columns}"
        )));
    }
    if !(1..=MAX_STAND_TREES).contains(&n) {
        return Err(invalid(format!(
            "positions: {n} trees; a stand grows 1 to {MAX_STAND_TREES}"
        )));
    }
    if !(0.05..=1.0).contains(&voxel) {
        return Err(invalid(format!("voxel {voxel}: expected 0.05 to 1 metres")));
    }
    let at: Vec<Vec2> = view
        .rows()
        .into_iter()
        .map(|r| Vec2::new(r[0], r[1]))
        .collect();
    if at.iter().any(|p| !p.is_finite()) {
        return Err(invalid("positions: expected finite numbers"));
    }
    let names: Vec<String> = match &species {
        None => vec!["oak".into()],
        Some(s) => match s.extract::<String>() {
            Ok(one) => vec![one],
            Err(_) => s.extract::<Vec<String>>()?,
        },
    };
    if names.len() != 1 && names.len() != n {
        return Err(invalid(format!(
            "species: give one, or one for each of the {n} positions (got {})",
            names.len()
        )));
    }
    let callback = Callback::new(progress);
    let grown = py.detach(|| {
        // Each name once, in order of first use; each planting's species an index into them.
        let mut distinct: Vec<&String> = Vec::new();
        let mut kinds: Vec<usize> = Vec::with_capacity(names.len());
        for name in &names {
            let k = distinct.iter().position(|d| *d == name).unwrap_or_else(|| {
                distinct.push(name);
                distinct.len() - 1
            });
            kinds.push(k);
        }
        let mut species = distinct
            .iter()
            .map(|name| sylva::presets::named_or_file(name.as_str()))
            .collect::<Result<Vec<Species>, _>>()?;
        if let Some(g) = generations {
            for s in &mut species {
                s.generations = g;
            }
        }
        let seeds: Vec<u64> = (0..n as u64)
            .map(|k| seed.wrapping_mul(1000).wrapping_add(k))
            .collect();
        let plantings: Vec<Planting> = at
            .iter()
            .zip(&seeds)
            .enumerate()
            .map(|(k, (&position, &seed))| Planting {
                // One name for all, or one each.
                species: kinds[k.min(kinds.len() - 1)],
                position,
                seed,
                start: 0,
                response: Response::default(),
            })
            .collect();
        let (lo, hi) = at.iter().fold(
            (Vec2::splat(f32::INFINITY), Vec2::splat(f32::NEG_INFINITY)),
            |(lo, hi), &p| (lo.min(p), hi.max(p)),
        );
        let margin = Vec2::splat(30.0);
        let flat = FlatPlane {
            height: 0.0,
            min: lo - margin,
            max: hi + margin,
        };
        let mut options = StandOptions::default();
        options.voxel = voxel;
        callback.tell("growing", 0, 1);
        let (stand, terrain) = match &ground {
            Some(g) => (
                grow(&species, &plantings, &g.map, &options)?,
                Some(ground_mesh(&g.map)?),
            ),
            None => (grow(&species, &plantings, &flat, &options)?, None),
        };
        callback.tell("growing", 1, 1);
        Ok::<_, Raised>(Stand {
            stand,
            terrain,
            species,
            seeds,
        })
    });
    callback.finish(grown.raise())
}
