//! The seasons in a glTF file: each leaf material names its species' year, so an engine's
//! shader can play one with the meshes as they are.
//!
//! A leaf material's `extras.sylva_phenology` holds the species' [`Phenology`] and the
//! lengths of its phases; the vertices' `_WIND` and `NORMAL` give each card's order and each
//! surface's snow catch ([`sylva_forest::vertex_phenology`]); each placement's
//! `_WIND_TREE` w is its tree's phase, which moves the tree's day by up to
//! [`TREE_DAYS`] ([`sylva_forest::tree_day`]). On a day `d`, a card of order `o` on a
//! tree of phase `p` is drawn when `o` is below the share `Phenology::leaves(tree_day(d,
//! p))` gives, in the colour it gives; snow lies on a surface by its catch times
//! [`sylva_forest::snow`]. `docs/engines.md` spells the shader out.
//!
//! [`Phenology`]: sylva_forest::Phenology

use serde_json::{Map, Value, json};
use sylva_forest::Species;

use crate::phenology::{self, Value as Entry};

/// `extras` of a species' leaf material: `{"sylva_phenology": {...}}`, the entries of
/// [`phenology::entries`].
pub(super) fn phenology_extras(species: &Species) -> Value {
    let year: Map<String, Value> = phenology::entries(species)
        .into_iter()
        .map(|(name, entry)| {
            let value = match entry {
                Entry::Flag(flag) => json!(flag),
                Entry::Number(number) => json!(number),
                Entry::Colour(colour) => json!(colour),
            };
            (name.to_owned(), value)
        })
        .collect();
    json!({ "sylva_phenology": year })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_deciduous_species_names_its_days_and_colours() {
        let mut oak = Species::from_preset("sylva-oak", 3).unwrap();
        oak.phenology.evergreen = false;
        oak.phenology.leaf_out = 120.0;
        let extras = phenology_extras(&oak);
        let p = &extras["sylva_phenology"];
        assert_eq!(p["evergreen"], false);
        assert_eq!(p["leaf_out"], 120.0);
        assert_eq!(p["summer"].as_array().unwrap().len(), 3);
        assert_eq!(p["flush_days"], f64::from(sylva_forest::FLUSH_DAYS));
    }
}
