//! What a forest or a stand stands on, read from Python: an elevation model's file or a
//! 2-D array of heights, as the `sylva` command reads a model; and its mesh as files hold it.

use std::path::PathBuf;

use numpy::{AllowTypeChange, PyArrayLike2};
use pyo3::prelude::*;
use pyo3::types::PyString;
use sylva::terrain::dem::{ElevationModel, ReadOptions, Window};
use sylva::terrain::{Heightmap, TerrainError, TerrainMesh};
use sylva::world::limits::{DEFAULT_REGION_SIDE, TERRAIN_MESH_SPACING};
use sylva::world::{Fit, Ground};

use crate::errors::{Raise, invalid};

/// What a forest or a stand stands on: nothing given, or ground read from a model's file or
/// an array of heights (its middle 1000 m, or the window `crop` names).
pub(crate) fn ground_of(
    terrain: Option<&Bound<'_, PyAny>>,
    spacing: Option<f32>,
    crop: Option<Window>,
) -> PyResult<Option<Ground>> {
    let Some(terrain) = terrain else {
        return Ok(None);
    };
    let options = ReadOptions {
        spacing,
        ..ReadOptions::default()
    };
    let fit = Fit::Middle {
        side: DEFAULT_REGION_SIDE,
    };
    if terrain.is_instance_of::<PyString>() || terrain.hasattr("__fspath__")? {
        let path: PathBuf = terrain.extract()?;
        let py = terrain.py();
        let ground = py.detach(|| Ground::read(&path, &options, crop, fit, "spacing="));
        return ground.raise().map(Some);
    }
    let heights: PyArrayLike2<'_, f32, AllowTypeChange> = terrain.extract().map_err(|_| {
        invalid("terrain: expected a file's path or a 2-D array of heights in metres")
    })?;
    let view = heights.as_array();
    let (rows_count, columns) = view.dim();
    let model = ElevationModel {
        width: columns,
        height: rows_count,
        // Row-major whatever the array's own order.
        heights: view.iter().copied().collect(),
        spacing: [spacing.unwrap_or(1.0); 2],
        nodata: 0,
        georeference: None,
        spacing_from_file: false,
    };
    Ground::of_model(model, "terrain array", &options, crop, fit, "spacing=")
        .raise()
        .map(Some)
}

/// A heightmap's mesh as `sylva forest` writes it: vertices at least
/// [`TERRAIN_MESH_SPACING`] apart.
pub(crate) fn ground_mesh(map: &Heightmap) -> Result<TerrainMesh, TerrainError> {
    map.mesh(map.stride_for_spacing(TERRAIN_MESH_SPACING))
}
