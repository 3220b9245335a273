//! One forest variant's whole chain: its levels tuned to its tree, its cache at each level,
//! its impostor and the error each level makes, built once and shared by the viewer, the
//! asset pack and engine plugins.

use sylva_forest::{Species, Variant};
use sylva_instancing::InstancingError;
use sylva_turtle::Mesh;

use super::cache::CacheLods;
use super::chain::LodChain;
use super::compare::calibrate_leaves;
use super::impostor::Impostor;
use super::raster::TreeLook;
use super::simplify::LodLevel;
use super::tree::variant_tree;

/// A variant's levels of detail.
#[derive(Debug, Clone, PartialEq)]
pub struct VariantLods {
    /// The whole tree (seed 1) the levels were tuned on and the impostor drawn from.
    pub tree: Mesh,
    /// The chain's levels with their cards' growth tuned to this tree's coverage.
    pub levels: Vec<LodLevel>,
    /// The variant's instance cache at full detail and at each level.
    pub cache: CacheLods,
    /// Its impostor (canopy variants only: seedlings are not drawn that far).
    pub impostor: Option<Impostor>,
    /// The error of each level, in metres, at the tree's own scale: level 1, level 2, ...,
    /// then the impostor (infinite without one); each at least the one before, so the
    /// distance from which each is drawn is `error * pixels_per_radian / pixel_error`.
    pub errors: Vec<f32>,
}

impl VariantLods {
    /// The chain of `variant` (of `species`) under `chain`.
    ///
    /// ```
    /// use sylva_export::lod::{LodChain, VariantLods};
    /// use sylva_forest::{ForestBuilder, ForestConfig, Species};
    /// let config = ForestConfig::new(vec![Species::from_preset("sylva-hazel", 3)?])
    ///     .with_budget(1 << 20);
    /// let builder = ForestBuilder::new(config)?;
    /// let species = &builder.config().species[0];
    /// let lods = VariantLods::build(&builder.variants()[0], species, &LodChain::default())?;
    /// assert_eq!(lods.cache.levels.len(), 3);
    /// assert!(lods.errors.windows(2).all(|w| w[0] <= w[1]));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn build(
        variant: &Variant,
        species: &Species,
        chain: &LodChain,
    ) -> Result<VariantLods, InstancingError> {
        let look = TreeLook::of(species);
        let tree = variant_tree(variant, 1)?;
        let levels: Vec<LodLevel> = chain
            .levels
            .iter()
            .map(|l| calibrate_leaves(&tree, &look, l))
            .collect();
        let mut tuned = chain.clone();
        tuned.levels.clone_from(&levels);
        let card = species.turtle.leaf_size[0].max(species.turtle.leaf_size[1]);
        let mut errors = Vec::with_capacity(levels.len() + 1);
        let mut worst = 0.0f32;
        for k in 0..levels.len() {
            worst = worst.max(tuned.level_error(k, card));
            errors.push(worst);
        }
        let impostor = (!variant.seedling).then(|| Impostor::render(&tree, &look, &chain.impostor));
        errors.push(
            impostor
                .as_ref()
                .map_or(f32::INFINITY, |i| tuned.impostor_error(i).max(worst)),
        );
        Ok(VariantLods {
            cache: CacheLods::of(&variant.cache, &levels),
            tree,
            levels,
            impostor,
            errors,
        })
    }
}
