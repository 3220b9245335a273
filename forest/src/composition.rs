//! The composition seam: which species, if any, stands at a spot. The patch density model asks
//! it for every tree it proposes; painting (the `sylva-paint` crate) implements it with a
//! layer of species densities, a user's own rules (a biome map, a land register) can too.

use std::fmt;

use glam::Vec2;

use crate::density::{Candidate, DensityModel, Rect};
use crate::patch::PatchDensity;

/// Decides the species of each tree the patch density model proposes, or that no tree stands.
///
/// Implementations must be pure functions of their inputs: the same spot and draw give the
/// same answer on every thread and in every region, so forests stay seamless and
/// deterministic.
///
/// ```
/// use sylva_forest::{Composition, DensityModel, PatchDensity, PatchSpecies, Rect};
/// use sylva_terrain::glam::Vec2;
///
/// /// Trees only west of x = 50, their species drawn by weight.
/// #[derive(Debug)]
/// struct West;
///
/// impl Composition for West {
///     fn choose(&self, density: &PatchDensity, p: Vec2, draw: u64) -> Option<usize> {
///         (p.x < 50.0).then(|| density.pick_species(draw))
///     }
///     fn species(&self) -> Option<usize> {
///         None
///     }
/// }
///
/// let model = PatchDensity::new(vec![PatchSpecies { canopy_radius: 3.0, weight: 1.0 }]);
/// let mut trees = Vec::new();
/// model.composed(&West).candidates(Rect::new(Vec2::ZERO, Vec2::splat(100.0)), 7, &mut trees);
/// assert!(!trees.is_empty() && trees.iter().all(|t| t.position.x < 50.0));
/// ```
pub trait Composition: fmt::Debug + Send + Sync {
    /// The species of a tree proposed at `p` (x, z), drawn from the bits of `draw`, or `None`
    /// for no tree there.
    fn choose(&self, density: &PatchDensity, p: Vec2, draw: u64) -> Option<usize>;

    /// How many species this composition was made for, so a forest can refuse one made for
    /// another forest; `None` when it fits any.
    fn species(&self) -> Option<usize>;
}

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
