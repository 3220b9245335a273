//! `sylva.succession`: a forest over time, grown from bare ground year by year, as its
//! yearly table (the columns of `sylva succession`'s succession.csv) of NumPy arrays.

use pyo3::prelude::*;
use pyo3::types::PyDict;
use sylva::forest::Rect;
use sylva::forest::succession::{Succession, SuccessionOptions, YearStats};
use sylva::terrain::glam::Vec2;
use sylva::world::limits::{MAX_SIDE, MAX_YEARS};

use crate::arrays::column;
use crate::errors::{Raise, Raised, invalid};
use crate::progress::Callback;

/// Grows a square of `area` metres from bare ground for `years` years with `species`
/// (bundled names or species files; default the five bundled species) and the world's
/// storms, lightning and disease, drawn from `seed`.
///
/// Returns the yearly table as a dict of NumPy arrays (float64, one entry per year from 0,
/// bare ground): the columns of `sylva succession`'s succession.csv (`year`, `stems_per_ha`,
/// `basal_area_m2_per_ha`, `mean_height_m`, deaths by cause, `canopy_cover`, and per species
/// `NAME_stems_per_ha` and the others), unrounded, and `events`, a list per year of what
/// happened ("storm", "lightning", "disease"). `progress("years", done, total)` hears each
/// year; an exception it raises stops the run. The GIL is released while it runs.
#[pyfunction]
#[pyo3(signature = (*, area = 200.0, years = 100, species = None, seed = 1, progress = None))]
pub(crate) fn succession<'py>(
    py: Python<'py>,
    area: f32,
    years: u32,
    species: Option<Vec<String>>,
    seed: u64,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    if !(area > 0.0 && area <= MAX_SIDE) {
        return Err(invalid(format!(
            "area {area}: expected 0 to {MAX_SIDE} metres"
        )));
    }
    if years == 0 || years > MAX_YEARS {
        return Err(invalid(format!("years {years}: expected 1 to {MAX_YEARS}")));
    }
    let callback = Callback::new(progress);
    let ran = py.detach(|| {
        let species = match &species {
            None => sylva::presets::species().raise()?,
            Some(names) => names
                .iter()
                .map(sylva::presets::named_or_file)
                .collect::<Result<Vec<_>, _>>()
                .raise()?,
        };
        let names: Vec<String> = species.iter().map(|s| s.name.clone()).collect();
        let region = Rect::new(Vec2::ZERO, Vec2::splat(area));
        let options = SuccessionOptions::default().with_seed(seed);
        let mut forest = Succession::new(species, region, options).raise()?;
        for done in 0..years {
            forest.step().map_err(Raised::from).raise()?;
            callback.tell("years", u64::from(done) + 1, u64::from(years));
            callback.check()?;
        }
        Ok::<_, PyErr>((names, forest.stats().to_vec()))
    });
    let (names, table) = callback.finish(ran)?;
    table_dict(py, &names, &table)
}

/// The yearly table as columns.
fn table_dict<'py>(
    py: Python<'py>,
    names: &[String],
    table: &[YearStats],
) -> PyResult<Bound<'py, PyDict>> {
    let header = YearStats::csv_header(names);
    let columns: Vec<&str> = header.split(',').collect();
    let rows: Vec<Vec<f64>> = table.iter().map(YearStats::values).collect();
    let d = PyDict::new(py);
    // Every column but the last, `events`, is a figure.
    for (k, name) in columns.iter().take(columns.len() - 1).enumerate() {
        let values: Vec<f64> = rows
            .iter()
            .map(|r| r.get(k).copied().unwrap_or(f64::NAN))
            .collect();
        d.set_item(*name, column(py, values).into_any())?;
    }
    let events: Vec<Vec<&str>> = table
        .iter()
        .map(|y| y.events.iter().map(|e| e.kind()).collect())
        .collect();
    d.set_item("events", events)?;
    Ok(d)
}
