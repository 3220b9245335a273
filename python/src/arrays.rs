//! Rust vectors as NumPy arrays. A vector of rows (`Vec<[T; N]>`) becomes an `(n, N)` array
//! without a copy where its allocation can be reused as a flat vector, which is always the
//! case for the plain number types used here.

use bytemuck::Pod;
use numpy::{Element, IntoPyArray, PyArray1, PyArray2, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// `values` as a 1-D array, without a copy.
pub(crate) fn column<T: Element>(py: Python<'_>, values: Vec<T>) -> Bound<'_, PyArray1<T>> {
    values.into_pyarray(py)
}

/// `rows` as an `(n, N)` array, without a copy when the allocation allows it.
pub(crate) fn rows<T: Element + Pod, const N: usize>(
    py: Python<'_>,
    rows: Vec<[T; N]>,
) -> PyResult<Bound<'_, PyArray2<T>>> {
    let n = rows.len();
    let flat: Vec<T> = match bytemuck::allocation::try_cast_vec(rows) {
        Ok(flat) => flat,
        Err((_, rows)) => rows.iter().flatten().copied().collect(),
    };
    flat.into_pyarray(py).reshape([n, N])
}

/// Flat triangle indices as an `(n, 3)` array of `uint32`, without a copy.
pub(crate) fn triangles(py: Python<'_>, indices: Vec<u32>) -> PyResult<Bound<'_, PyArray2<u32>>> {
    let n = indices.len() / 3;
    let mut indices = indices;
    indices.truncate(3 * n);
    indices.into_pyarray(py).reshape([n, 3])
}

/// A dict from `(name, value)` pairs, in order.
pub(crate) fn dict<'py>(
    py: Python<'py>,
    items: impl IntoIterator<Item = (&'static str, Bound<'py, PyAny>)>,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (name, value) in items {
        d.set_item(name, value)?;
    }
    Ok(d)
}

/// A dict of whole-number figures.
pub(crate) fn figures<'py, const N: usize>(
    py: Python<'py>,
    items: [(&'static str, u64); N],
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (name, value) in items {
        d.set_item(name, value)?;
    }
    Ok(d)
}
