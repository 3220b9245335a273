//! The patch density model composed with a [`Composition`]: the seam through which painting
//! (the `sylva-paint` crate) or a user's own rules (a biome map, a land register) decide which
//! species, if any, stands at each spot the model proposes.

use crate::density::{Candidate, DensityModel, Rect};
use crate::patch::{Composition, PatchDensity};

/// The patch density model with each tree's presence and species decided by a
/// [`Composition`]: spacing, moves and seedling thinning as without one.
#[derive(Debug, Clone, Copy)]
pub struct ComposedDensity<'a> {
    density: &'a PatchDensity,
    composition: &'a dyn Composition,
}

impl PatchDensity {
    /// This model, its species decided by `composition`.
    pub fn composed<'a>(&'a self, composition: &'a dyn Composition) -> ComposedDensity<'a> {
        ComposedDensity {
            density: self,
            composition,
        }
    }
}

impl DensityModel for ComposedDensity<'_> {
    fn candidates(&self, region: Rect, seed: u64, out: &mut Vec<Candidate>) {
        self.density
            .candidates_by(self.composition, region, seed, out);
    }
}
