//! The seasons in a glTF file: each leaf material names its species' year, so an engine's
//! shader can play one with the meshes as they are.
//!
//! A leaf material's `extras.sylva_phenology` holds the species' [`Phenology`] and the
//! lengths of its phases; the vertices' `_PHENOLOGY` hold each card's order and each
//! surface's snow catch ([`sylva_forest::vertex_phenology`]); each placement's
//! `_WIND_TREE` w is its tree's phase, which moves the tree's day by up to
//! [`TREE_DAYS`] ([`sylva_forest::tree_day`]). On a day `d`, a card of order `o` on a
//! tree of phase `p` is drawn when `o` is below the share `Phenology::leaves(tree_day(d,
//! p))` gives, in the colour it gives; snow lies on a surface by its catch times
//! [`sylva_forest::snow`]. `docs/engines.md` spells the shader out.
//!
//! [`Phenology`]: sylva_forest::Phenology

use serde_json::json;
use sylva_forest::{FALL_DAYS, FLUSH_DAYS, GREEN_DAYS, Species, TREE_DAYS, TURN_DAYS};

/// `extras` of a species' leaf material: `{"sylva_phenology": {...}}`. `summer` is the
/// species' leaf colour as drawn (the day's colour when the forest was drawn with a season).
pub(super) fn phenology_extras(species: &Species) -> serde_json::Value {
    let p = &species.phenology;
    json!({
        "sylva_phenology": {
            "evergreen": p.evergreen,
            "leaf_out": p.leaf_out,
            "leaf_fall": p.leaf_fall,
            "spring": p.spring,
            "summer": species.leaf,
            "autumn": p.autumn,
            "flush_days": FLUSH_DAYS,
            "fall_days": FALL_DAYS,
            "turn_days": TURN_DAYS,
            "green_days": GREEN_DAYS,
            "tree_days": TREE_DAYS,
        }
    })
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
        assert_eq!(p["flush_days"], f64::from(FLUSH_DAYS));
    }
}
