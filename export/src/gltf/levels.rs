//! A forest file's levels of detail: for every variant the chain the viewer draws (full
//! detail, the coarser levels of its instance cache, then the impostor's cards), the
//! distance from which each is drawn, and how far seedling forms are drawn at all.
//!
//! Unlike the viewer's chain, seedling forms (the young trees of the understory, 5 to 7 m
//! tall in the default forest) get an impostor too: a file's client has no fog to hide them
//! in, and 80,000 of them at their coarsest mesh level cost more triangles than a frame has.

use rayon::prelude::*;
use sylva_forest::{ForestBuilder, ForestError, Species};
use sylva_turtle::Mesh;

use super::position_bounds;
use crate::error::ExportError;
use crate::lod::{Impostor, LodChain, TreeLook, VariantLods, impostor_cards};

/// Pixels a seedling form's height spans, on the chain's screen, below which it is not
/// drawn: smaller, a young tree is a speck under the canopy, and the default forest's 80,000
/// of them as impostors out to the horizon would cost more triangles than the canopy's.
pub const SEEDLING_MIN_PIXELS: f32 = 16.0;

/// One variant's levels in a file.
#[derive(Debug, Clone)]
pub(crate) struct VariantLevels {
    /// The chain and its cache at every level (its impostor and whole tree taken out: the
    /// file keeps only the cards).
    pub(crate) lods: VariantLods,
    /// The distance (metres, at the chain's screen) from which each coarser level is drawn,
    /// then the impostor's when it has one; each at least the one before.
    pub(crate) from: Vec<f32>,
    /// The distance beyond which the variant is not drawn at all (seedling forms); `None`:
    /// drawn at every distance.
    pub(crate) reach: Option<f32>,
    /// The impostor as cards and their texture (PNG).
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
                let mut lods = VariantLods::build(v, &species[v.species], chain)?;
                if lods.impostor.is_none() {
                    // A seedling form: its impostor, drawn as the canopy's are.
                    let look = TreeLook::of(&species[v.species]);
                    let impostor = Impostor::render(&lods.tree, &look, &chain.impostor);
                    let worst = lods
                        .errors
                        .iter()
                        .copied()
                        .filter(|e| e.is_finite())
                        .fold(0.0, f32::max);
                    if let Some(last) = lods.errors.last_mut() {
                        *last = chain.impostor_error(&impostor).max(worst);
                    }
                    lods.impostor = Some(impostor);
                }
                let from = switch_distances(&lods, chain, &species[v.species]);
                let reach = v.seedling.then(|| {
                    let (lo, hi, _) =
                        position_bounds(lods.tree.vertices.iter().map(|v| v.position));
                    let height = (hi[1] - lo[1]).max(0.01);
                    let reach = height * chain.pixels_per_radian / SEEDLING_MIN_PIXELS;
                    reach.max(from.last().copied().unwrap_or(0.0))
                });
                let cards = lods
                    .impostor
                    .take()
                    .map(|i| (impostor_cards(&i), i.cards_texture().png()));
                // The file needs the cards and the cache's levels: the impostor's atlases
                // (colour, normals, depth: 12 MB a variant) and the whole tree go now, not
                // when every variant is built.
                lods.tree = Mesh::default();
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

/// The distance from which each coarser level and then the impostor is drawn: the nearest
/// distance where its own error spans the chain's pixel error, or where a coarser level's
/// does if that is nearer (a level with more error than a cheaper one after it is never
/// drawn: a young pine's thinned needles err more than its impostor does). Each at least
/// the one before.
fn switch_distances(lods: &VariantLods, chain: &LodChain, species: &Species) -> Vec<f32> {
    let mut tuned = chain.clone();
    tuned.levels.clone_from(&lods.levels);
    let card = species.turtle.leaf_size[0].max(species.turtle.leaf_size[1]);
    let mut errors: Vec<f32> = (0..lods.levels.len())
        .map(|k| tuned.level_error(k, card))
        .collect();
    errors.extend(lods.impostor.as_ref().map(|i| chain.impostor_error(i)));
    let mut from: Vec<f32> = errors.iter().map(|&e| chain.distance_for(e)).collect();
    for k in (0..from.len().saturating_sub(1)).rev() {
        from[k] = from[k].min(from[k + 1]);
    }
    from
}

/// The alpha cutoff of the impostor cards' material in a forest file: its cards are seen
/// only from afar, through a client's coarser mipmaps, where the tiles' cutoff
/// ([`CARD_ALPHA_CUTOFF`](crate::lod::CARD_ALPHA_CUTOFF), 0.3, which keeps a crown's fringe up close) lets more of each card
/// through than the tree covers. Measured in three.js r187 on the 200 m forest from 250 m up,
/// flat by role: foliage over the ground 80.6% at full detail; impostors cut at 0.3 gave
/// 83.8%, at 0.5 73.5%, at 0.37 80.4%.
pub(crate) const CARDS_CUTOFF: f32 = 0.37;
