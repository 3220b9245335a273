//! `sylva.tree`: one tree of a species or a grammar as NumPy arrays (vertices, normals, uvs,
//! wind data, bark and leaf triangles) with its skeleton, and written as glTF or OBJ.

use std::path::PathBuf;

use numpy::PyArray2;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyTuple};
use sylva::export::Texture;
use sylva::export::limits::CUTOFF_MIP_LEVEL;
use sylva::forest::{Species, parse_day};
use sylva::turtle::{Mesh, MeshBuilder, Skeleton, Vertex, interpret, write_obj};

use crate::arrays::{column, dict, rows, triangles};
use crate::errors::{Raise, Raised, invalid};
use crate::grammar::Grammar;

/// One tree: its mesh as arrays, its skeleton, and the species it is drawn as.
///
/// sylva.tree() makes one. Each array property builds a new NumPy array: `positions`,
/// `normals` (float32, n x 3), `uvs` (n x 2), `wind` (n x 4: the branch's pivot and its depth
/// plus a phase), `bark` and `leaves` (uint32 triangles, m x 3, indexing the vertices) and
/// `skeleton` (a dict of arrays).
#[pyclass(module = "sylva", name = "Tree", frozen)]
#[derive(Debug)]
pub(crate) struct Tree {
    pub(crate) species: Species,
    pub(crate) mesh: Mesh,
    pub(crate) skeleton: Skeleton,
    pub(crate) seed: u64,
}

/// One attribute of every vertex.
fn each<const N: usize>(vertices: &[Vertex], of: impl Fn(&Vertex) -> [f32; N]) -> Vec<[f32; N]> {
    vertices.iter().map(of).collect()
}

#[pymethods]
impl Tree {
    /// The species' name ("tree" for a grammar's tree).
    #[getter]
    fn name(&self) -> &str {
        &self.species.name
    }

    /// The seed it was derived from.
    #[getter]
    fn seed(&self) -> u64 {
        self.seed
    }

    /// Vertex positions, metres, y up, the root at the origin (float32, n x 3).
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f32>>> {
        rows(py, each(&self.mesh.vertices, |v| v.position))
    }

    /// Unit vertex normals (float32, n x 3).
    #[getter]
    fn normals<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f32>>> {
        rows(py, each(&self.mesh.vertices, |v| v.normal))
    }

    /// Texture coordinates (float32, n x 2): on bark u runs once round a branch and v along
    /// it (tiling past 1); on leaf cards both run 0 to 1.
    #[getter]
    fn uvs<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f32>>> {
        rows(py, each(&self.mesh.vertices, |v| v.uv))
    }

    /// Wind data (float32, n x 4): the pivot where the vertex's branch leaves its parent,
    /// then the branch's depth plus a phase in [0, 1).
    #[getter]
    fn wind<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f32>>> {
        rows(py, each(&self.mesh.vertices, |v| v.wind))
    }

    /// Bark triangles (uint32, m x 3), counter-clockwise seen from outside.
    #[getter]
    fn bark<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<u32>>> {
        triangles(py, self.mesh.bark.clone())
    }

    /// Leaf-card triangles (uint32, m x 3); cards are seen from both sides.
    #[getter]
    fn leaves<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<u32>>> {
        triangles(py, self.mesh.leaves.clone())
    }

    /// The drawn segments as bones: `starts` and `ends` (float32, k x 3), `radii` (k x 2:
    /// at the start and the end) and `parents` (int64, -1 for the root).
    #[getter]
    fn skeleton<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        skeleton_arrays(py, &self.skeleton)
    }

    /// How its species is drawn, for building materials: `bark_colour` and `leaf_colour`
    /// (linear RGB), `bark_texture` and `leaf_texture` (PNG bytes: a tiling bark pattern, and
    /// the leaf card's cluster with its alpha) and `alpha_cutoff` (where to cut the card's
    /// alpha, as the glTF files do).
    #[getter]
    fn material<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        species_material(py, &self.species)
    }

    /// Number of vertices.
    #[getter]
    fn vertex_count(&self) -> usize {
        self.mesh.vertices.len()
    }

    /// Number of triangles, bark and leaves.
    #[getter]
    fn triangle_count(&self) -> usize {
        self.mesh.triangle_count()
    }

    /// Writes the tree as binary glTF with its species' materials and textures (any glTF
    /// importer reads it: no extension is required). Returns the bytes written.
    fn write_glb(&self, py: Python<'_>, path: PathBuf) -> PyResult<u64> {
        py.detach(|| sylva::export::write_tree_glb(&self.species, &self.mesh, &path))
            .raise()?;
        file_size(&path)
    }

    /// Writes the tree as a Wavefront OBJ file. Returns the bytes written.
    fn write_obj(&self, py: Python<'_>, path: PathBuf) -> PyResult<u64> {
        py.detach(|| sylva::base::file::write(&path, |w| write_obj(&self.mesh, w)))
            .raise()?;
        file_size(&path)
    }

    fn __repr__(&self) -> String {
        format!(
            "<sylva.Tree '{}' seed {}: {} vertices, {} triangles, {} bones>",
            self.species.name,
            self.seed,
            self.mesh.vertices.len(),
            self.mesh.triangle_count(),
            self.skeleton.bones.len()
        )
    }
}

/// How `species` is drawn, as a dict (see `Tree.material`).
pub(crate) fn species_material<'py>(
    py: Python<'py>,
    species: &Species,
) -> PyResult<Bound<'py, PyDict>> {
    let leaf = Texture::leaf(species.leaf_shape);
    let (bark_png, leaf_png) =
        py.detach(|| (Texture::bark(species.bark_pattern).png(), leaf.png()));
    dict(
        py,
        [
            ("bark_colour", PyTuple::new(py, species.bark)?.into_any()),
            ("leaf_colour", PyTuple::new(py, species.leaf)?.into_any()),
            ("bark_texture", PyBytes::new(py, &bark_png).into_any()),
            ("leaf_texture", PyBytes::new(py, &leaf_png).into_any()),
            (
                "alpha_cutoff",
                leaf.alpha_cutoff(CUTOFF_MIP_LEVEL)
                    .into_pyobject(py)?
                    .into_any(),
            ),
        ],
    )
}

/// A file's size, after writing it.
pub(crate) fn file_size(path: &std::path::Path) -> PyResult<u64> {
    std::fs::metadata(path)
        .map(|m| m.len())
        .map_err(|e| invalid(format!("{}: {e}", path.display())))
}

/// A skeleton's bones as a dict of arrays.
pub(crate) fn skeleton_arrays<'py>(
    py: Python<'py>,
    skeleton: &Skeleton,
) -> PyResult<Bound<'py, PyDict>> {
    let bones = &skeleton.bones;
    let starts: Vec<[f32; 3]> = bones.iter().map(|b| b.start.to_array()).collect();
    let ends: Vec<[f32; 3]> = bones.iter().map(|b| b.end.to_array()).collect();
    let radii: Vec<[f32; 2]> = bones
        .iter()
        .map(|b| [b.start_radius, b.end_radius])
        .collect();
    let parents: Vec<i64> = bones
        .iter()
        .map(|b| b.parent.map_or(-1, i64::from))
        .collect();
    dict(
        py,
        [
            ("starts", rows(py, starts)?.into_any()),
            ("ends", rows(py, ends)?.into_any()),
            ("radii", rows(py, radii)?.into_any()),
            ("parents", column(py, parents).into_any()),
        ],
    )
}

/// A day of the year from a number (1 to 365) or a season's name.
pub(crate) fn day_of(value: &Bound<'_, PyAny>) -> PyResult<f32> {
    let text = value.str()?.to_string();
    parse_day(&text).ok_or_else(|| {
        invalid(format!(
            "season '{text}': expected a day of the year (1 to 365) or spring, summer, autumn or winter"
        ))
    })
}

/// One tree of a bundled species or a species file (`species`, default "oak"), or of a
/// grammar (`grammar`, drawn with its own or its dialect's turtle settings).
///
/// `generations` defaults to the species' or grammar's own; `seed` draws the stochastic
/// productions; `season` (a day of the year 1 to 365, or "spring", "summer", "autumn",
/// "winter") draws a species' leaves as that day has them. The same arguments give the same
/// arrays as the Rust API, on any machine. The GIL is released while the tree is built.
#[pyfunction]
#[pyo3(signature = (species = None, *, grammar = None, seed = 0, generations = None, season = None))]
pub(crate) fn tree(
    py: Python<'_>,
    species: Option<String>,
    grammar: Option<Bound<'_, Grammar>>,
    seed: u64,
    generations: Option<u32>,
    season: Option<Bound<'_, PyAny>>,
) -> PyResult<Tree> {
    let day = season.as_ref().map(day_of).transpose()?;
    match (species, grammar) {
        (Some(_), Some(_)) => Err(invalid("give a species or a grammar, not both")),
        (_, Some(grammar)) => {
            if day.is_some() {
                return Err(invalid(
                    "season: a grammar's tree has no year; give a species",
                ));
            }
            let grammar = grammar.get();
            let options = grammar.turtle();
            let generations = generations.unwrap_or(grammar.generations);
            let lsystem = &grammar.lsystem;
            py.detach(|| {
                let word = lsystem
                    .derive(generations, seed)
                    .and_then(|w| lsystem.interpretation(&w, seed))?;
                let mut builder = MeshBuilder::new(&options);
                interpret(&word, &options, &mut builder)?;
                let mut skeleton = Skeleton::default();
                interpret(&word, &options, &mut skeleton)?;
                let mut species = Species::new("tree", lsystem.clone(), generations);
                species.turtle = options.clone();
                Ok::<_, Raised>(Tree {
                    species,
                    mesh: builder.finish(),
                    skeleton,
                    seed,
                })
            })
            .raise()
        }
        (species, None) => {
            let name = species.unwrap_or_else(|| "oak".into());
            py.detach(|| {
                let mut species = sylva::presets::named_or_file(&name)?;
                if let Some(day) = day {
                    species = species.in_season(day);
                }
                let generations = generations.unwrap_or(species.generations);
                let mesh = species.mesh(generations, seed)?;
                let skeleton = species.skeleton(generations, seed)?;
                Ok::<_, Raised>(Tree {
                    species,
                    mesh,
                    skeleton,
                    seed,
                })
            })
            .raise()
        }
    }
}

/// The bundled species' names, for sylva.tree and sylva.Forest.
#[pyfunction]
pub(crate) fn species_names() -> Vec<&'static str> {
    sylva::world::presets::bundled_names()
}
