//! Plots when this `sylva` is built without the `plots` feature: nothing is drawn, and the
//! user is told once per plot how to get them (the tables beside them are written either
//! way). Plotting's font and rasteriser stay out of the quick start's build.

use std::path::Path;

use sylva::forest::succession::YearStats;
use sylva::terrain::analysis::FractalAnalysis;

use crate::Failure;

/// Whether plots are drawn by this build.
pub(crate) const DRAWN: bool = false;

/// Says that `path` was not drawn and how to build a `sylva` that draws it.
fn absent(path: &Path) -> Result<(), Failure> {
    eprintln!(
        "note: {} not drawn: this sylva was built without plots (cargo install --path cli --features plots)",
        path.display()
    );
    Ok(())
}

/// Each species' share of the stand's basal area by year: not drawn in this build.
pub(crate) fn species_shares(path: &Path, _: &[YearStats], _: &[String]) -> Result<(), Failure> {
    absent(path)
}

/// Stem density against mean diameter: not drawn in this build.
pub(crate) fn self_thinning(
    path: &Path,
    _: &[YearStats],
    _: &[YearStats],
    _: Option<f32>,
) -> Result<(), Failure> {
    absent(path)
}

/// A terrain's variogram: not drawn in this build.
pub(crate) fn variogram(path: &Path, _: &FractalAnalysis, _: &str) -> Result<(), Failure> {
    absent(path)
}
