//! The `sylva` Python package's native module, `sylva._sylva`: a thin layer over the sylva
//! crates with Python's names. Grammars derive words; a tree is NumPy arrays of vertices,
//! normals, uvs and triangles with its skeleton; a forest is built once (species, terrain as
//! an array or a file, seed, region) and then written as glTF, USD or 3D Tiles or read as
//! arrays of trees and placements; a stand is grown; a forest over time gives its yearly
//! table. Work that takes long releases the GIL and reports through a callback; mistakes are
//! Python exceptions with the Rust API's message, and a grammar's line and column.
//!
//! The package around it (`python/sylva/`) re-exports these names, with type stubs.

mod arrays;
mod columns;
mod errors;
mod forest;
mod grammar;
mod ground;
mod progress;
mod stand;
mod succession;
mod tree;

use pyo3::prelude::*;

/// The module `sylva._sylva`: every class, function and exception the package exports.
#[pymodule]
fn _sylva(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("SylvaError", py.get_type::<errors::SylvaError>())?;
    m.add("ParseError", py.get_type::<errors::ParseError>())?;
    m.add_class::<grammar::Grammar>()?;
    m.add_class::<tree::Tree>()?;
    m.add_class::<forest::Forest>()?;
    m.add_class::<stand::Stand>()?;
    m.add_function(wrap_pyfunction!(grammar::presets, m)?)?;
    m.add_function(wrap_pyfunction!(tree::species_names, m)?)?;
    m.add_function(wrap_pyfunction!(tree::tree, m)?)?;
    m.add_function(wrap_pyfunction!(stand::grow_stand, m)?)?;
    m.add_function(wrap_pyfunction!(succession::succession, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
