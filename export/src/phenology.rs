//! A species' year as every export names it: one list of named values, which glTF spells as
//! a leaf material's `extras.sylva_phenology` and USD as its `customData`, so the two files
//! always carry the same entries in the same order; and the snow on a seasoned forest's
//! ground, which both formats paint on the terrain.

use sylva_forest::{
    FALL_DAYS, FLUSH_DAYS, ForestBuilder, GREEN_DAYS, Species, TREE_DAYS, TURN_DAYS,
};

/// One entry's value, typed as the formats type it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Value {
    Flag(bool),
    Number(f32),
    Colour([f32; 3]),
}

/// The entries of `species`' year: whether it is evergreen, the days its leaves come out and
/// half fall, its spring, summer (its leaf colour as drawn, the day's colour when the forest
/// was drawn with a season) and autumn colours, and the phases' lengths.
pub(crate) fn entries(species: &Species) -> [(&'static str, Value); 11] {
    let p = &species.phenology;
    [
        ("evergreen", Value::Flag(p.evergreen)),
        ("leaf_out", Value::Number(p.leaf_out)),
        ("leaf_fall", Value::Number(p.leaf_fall)),
        ("spring", Value::Colour(p.spring)),
        ("summer", Value::Colour(species.leaf)),
        ("autumn", Value::Colour(p.autumn)),
        ("flush_days", Value::Number(FLUSH_DAYS)),
        ("fall_days", Value::Number(FALL_DAYS)),
        ("turn_days", Value::Number(TURN_DAYS)),
        ("green_days", Value::Number(GREEN_DAYS)),
        ("tree_days", Value::Number(TREE_DAYS)),
    ]
}

/// The snow on the ground of a forest drawn on a day of the year
/// ([`sylva_forest::ForestConfig::season`]): [`sylva_forest::snow`] that day, none without a
/// season.
pub(crate) fn snow_lying(builder: &ForestBuilder) -> f32 {
    builder.config().season.map_or(0.0, sylva_forest::snow)
}
