//! A forest file's levels of detail: for every variant the chain the viewer draws (full
//! detail, the coarser levels of its instance cache, then for canopy variants the impostor's
//! cards), the distance from which each is drawn, and how far seedlings are drawn at all.

use rayon::prelude::*;
use sylva_forest::{ForestBuilder, ForestError};
use sylva_turtle::Mesh;

use crate::error::ExportError;
use crate::lod::{CARD_ALPHA_CUTOFF, LodChain, VariantLods, impostor_cards};

/// Pixels a seedling's height spans, on the chain's screen, below which it is not drawn: a
/// seedling smaller is a speck under the canopy, and drawing every one out to the horizon
/// would cost more triangles than all the canopy's impostors (about 80,000 seedlings in the
/// default forest).
pub const SEEDLING_MIN_PIXELS: f32 = 8.0;

/// One variant's levels in a file.
#[derive(Debug, Clone)]
pub(crate) struct VariantLevels {
    /// The chain, its cache at every level and its impostor.
    pub(crate) lods: VariantLods,
    /// The distance (metres, at the chain's screen) from which each coarser level is drawn,
    /// then the impostor's when it has one; each at least the one before.
    pub(crate) from: Vec<f32>,
    /// The distance beyond which the variant is not drawn at all (seedlings, which have no
    /// impostor); `None`: drawn at every distance.
    pub(crate) reach: Option<f32>,
    /// The impostor as cards and their texture (PNG), for canopy variants.
    pub(crate) cards: Option<(Mesh, Vec<u8>)>,
}

impl VariantLevels {
    /// Mesh levels, the full one included.
    pub(crate) fn mesh_levels(&self) -> usize {
        self.lods.cache.levels.len()
    }
}

/// Every variant's levels, built on every core.
#[derive(Debug, Clone)]
pub(crate) struct ForestLevels {
    pub(crate) chain: LodChain,
    pub(crate) variants: Vec<VariantLevels>,
}

impl ForestLevels {
    /// The levels of every variant of `builder` under `chain`.
    pub(crate) fn build(builder: &ForestBuilder, chain: &LodChain) -> Result<Self, ExportError> {
        let species = &builder.config().species;
        let variants = builder
            .variants()
            .par_iter()
            .map(|v| {
                let lods = VariantLods::build(v, &species[v.species], chain)?;
                let mut from: Vec<f32> = lods
                    .errors
                    .iter()
                    .filter(|e| e.is_finite())
                    .map(|&e| chain.distance_for(e))
                    .collect();
                // Each level is drawn from no nearer than the one before.
                for k in 1..from.len() {
                    from[k] = from[k].max(from[k - 1]);
                }
                let reach = lods.impostor.is_none().then(|| {
                    let (lo, hi) = bounds_y(&lods.tree);
                    let height = (hi - lo).max(0.01);
                    let reach = height * chain.pixels_per_radian / SEEDLING_MIN_PIXELS;
                    reach.max(from.last().copied().unwrap_or(0.0))
                });
                let cards = lods
                    .impostor
                    .as_ref()
                    .map(|i| (impostor_cards(i), i.cards_texture().png()));
                Ok(VariantLevels {
                    lods,
                    from,
                    reach,
                    cards,
                })
            })
            .collect::<Result<Vec<_>, sylva_instancing::InstancingError>>()
            .map_err(ForestError::from)?;
        Ok(ForestLevels {
            chain: chain.clone(),
            variants,
        })
    }

    /// Whether each variant has an impostor.
    pub(crate) fn impostors(&self) -> Vec<bool> {
        self.variants.iter().map(|v| v.cards.is_some()).collect()
    }
}

/// The alpha cutoff of the impostor cards' material.
pub(crate) const CARDS_CUTOFF: f32 = CARD_ALPHA_CUTOFF;

/// The lowest and highest y of a mesh's vertices.
fn bounds_y(mesh: &Mesh) -> (f32, f32) {
    mesh.vertices
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v.position[1]), hi.max(v.position[1]))
        })
}
