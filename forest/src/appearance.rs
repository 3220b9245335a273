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
    /// A cluster of oak leaves: obovate blades with four or five rounded lobes a side.
    Lobed,
    /// A cluster of toothed leaves: ovate blades with serrated edges.
    Serrated,
    /// A tuft of long needles fanning out from a shoot's tip.
    NeedleTuft,
    /// A cluster of round-ovate, doubly toothed leaves, as on hazel, aspen and alder.
    Rounded,
    /// A cluster of small triangular-ovate, finely toothed leaves, as on birch.
    Deltoid,
    /// A cluster of five-lobed leaves as broad as long, as on sycamore and other maples.
    Palmate,
    /// A pine's shoot end: needles in pairs slanting forward along the shoot and brushing out
    /// from its tip, so many small cards read as tufted branch ends rather than fans.
    PineShoot,
}

impl LeafShape {
    /// The name used in species files.
    pub fn name(self) -> &'static str {
        match self {
            LeafShape::Broadleaf => "broadleaf",
            LeafShape::Needles => "needles",
            LeafShape::Lobed => "lobed",
            LeafShape::Serrated => "serrated",
            LeafShape::NeedleTuft => "needle-tuft",
            LeafShape::Rounded => "rounded",
            LeafShape::Deltoid => "deltoid",
            LeafShape::Palmate => "palmate",
            LeafShape::PineShoot => "pine-shoot",
        }
    }

    /// The share of its card the shape's texture fills (alpha at least a half, as renderers
    /// cut cards): what of the ground a card hides seen through it. Measured on the textures
    /// `sylva_export` draws, which a test there holds to these numbers.
    pub fn opacity(self) -> f32 {
        match self {
            LeafShape::Broadleaf => 0.465,
            LeafShape::Needles => 0.277,
            LeafShape::Lobed => 0.484,
            LeafShape::Serrated => 0.431,
            LeafShape::NeedleTuft => 0.236,
            LeafShape::Rounded => 0.605,
            LeafShape::Deltoid => 0.469,
            LeafShape::Palmate => 0.602,
            LeafShape::PineShoot => 0.259,
        }
    }

    /// Every shape, in the order renderers lay out their textures.
    pub const ALL: [LeafShape; 9] = [
        LeafShape::Broadleaf,
        LeafShape::Needles,
        LeafShape::Lobed,
        LeafShape::Serrated,
        LeafShape::NeedleTuft,
        LeafShape::Rounded,
        LeafShape::Deltoid,
        LeafShape::Palmate,
        LeafShape::PineShoot,
    ];

    /// The shape called `name` in species files.
    pub fn from_name(name: &str) -> Option<LeafShape> {
        LeafShape::ALL.into_iter().find(|s| s.name() == name)
    }
}

/// What a species' bark texture shows.
// Exhaustive for the same reason as `LeafShape`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum BarkPattern {
    /// Long ridges and furrows, as on oaks.
    #[default]
    Furrowed,
    /// Smooth, with dark horizontal lenticels, as on birches.
    Smooth,
    /// Plates parted by cracks, as on pines and spruces.
    Scaly,
}

impl BarkPattern {
    /// The name used in species files.
    pub fn name(self) -> &'static str {
        match self {
            BarkPattern::Furrowed => "furrowed",
            BarkPattern::Smooth => "smooth",
            BarkPattern::Scaly => "scaly",
        }
    }

    /// Every pattern, in the order renderers lay out their textures.
    pub const ALL: [BarkPattern; 3] = [
        BarkPattern::Furrowed,
        BarkPattern::Smooth,
        BarkPattern::Scaly,
    ];

    /// The pattern called `name` in species files.
    pub fn from_name(name: &str) -> Option<BarkPattern> {
        BarkPattern::ALL.into_iter().find(|p| p.name() == name)
    }
}
