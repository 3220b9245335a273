//! What a species' textures show: the names species files use, drawn by `sylva-export`.

/// What a species' leaf cards show.
// Exhaustive on purpose: every renderer (the exporter, the viewer) must draw every shape, so a
// new one should fail to compile there rather than fall back to another's texture.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum LeafShape {
    /// A cluster of broad leaves: ovate blades with a pointed tip, a midrib and side veins.
    #[default]
    Broadleaf,
    /// A spray of needles along a twig, for conifers.
    Needles,
}

impl LeafShape {
    /// The name used in species files.
    pub fn name(self) -> &'static str {
        match self {
            LeafShape::Broadleaf => "broadleaf",
            LeafShape::Needles => "needles",
        }
    }

    /// The shape called `name` in species files.
    pub fn from_name(name: &str) -> Option<LeafShape> {
        [LeafShape::Broadleaf, LeafShape::Needles]
            .into_iter()
            .find(|s| s.name() == name)
    }
}

/// What a species' bark texture shows.
// Exhaustive for the same reason as `LeafShape`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum BarkPattern {
    /// Long ridges and furrows, as on oaks, pines and spruces.
    #[default]
    Furrowed,
    /// Smooth, with dark horizontal lenticels, as on birches.
    Smooth,
}

impl BarkPattern {
    /// The name used in species files.
    pub fn name(self) -> &'static str {
        match self {
            BarkPattern::Furrowed => "furrowed",
            BarkPattern::Smooth => "smooth",
        }
    }

    /// The pattern called `name` in species files.
    pub fn from_name(name: &str) -> Option<BarkPattern> {
        [BarkPattern::Furrowed, BarkPattern::Smooth]
            .into_iter()
            .find(|p| p.name() == name)
    }
}
