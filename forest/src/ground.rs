//! What grows on the forest floor: grass, ferns, low shrubs, fallen branches and rocks; how
//! each looks and how its density follows the light. Their meshes are `floor::mesh`'s.

use crate::appearance::{BarkPattern, LeafShape};

/// A kind of ground cover.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum GroundKind {
    /// Tufts of grass blades: most in full light, few under a closed canopy.
    Grass,
    /// Ferns: most in half shade, some in the open and under closed canopy.
    Fern,
    /// Low leafy shrubs: in light gaps.
    Shrub,
    /// Fallen branches: under the trees they fell from.
    Branch,
    /// Rocks: wherever the ground has them, light or not.
    Rock,
}

impl GroundKind {
    /// Every kind, in order.
    pub const ALL: [GroundKind; 5] = [
        GroundKind::Grass,
        GroundKind::Fern,
        GroundKind::Shrub,
        GroundKind::Branch,
        GroundKind::Rock,
    ];

    /// The kind's name in species files: `grass`, `fern`, `shrub`, `branch` or `rock`.
    pub fn name(self) -> &'static str {
        match self {
            GroundKind::Grass => "grass",
            GroundKind::Fern => "fern",
            GroundKind::Shrub => "shrub",
            GroundKind::Branch => "branch",
            GroundKind::Rock => "rock",
        }
    }

    /// The kind named `name` (as [`GroundKind::name`] spells it), if any.
    ///
    /// ```
    /// use sylva_forest::GroundKind;
    /// assert_eq!(GroundKind::from_name("fern"), Some(GroundKind::Fern));
    /// assert_eq!(GroundKind::from_name("moss"), None);
    /// ```
    pub fn from_name(name: &str) -> Option<GroundKind> {
        GroundKind::ALL.into_iter().find(|k| k.name() == name)
    }

    /// The share of its full density the kind reaches under canopy `cover` (0: open sky, 1:
    /// closed canopy).
    ///
    /// ```
    /// use sylva_forest::GroundKind;
    /// // Grass thins out under the trees; fallen branches gather there.
    /// assert!(GroundKind::Grass.light_response(0.0) > 4.0 * GroundKind::Grass.light_response(0.9));
    /// assert!(GroundKind::Branch.light_response(0.9) > GroundKind::Branch.light_response(0.1));
    /// ```
    pub fn light_response(self, cover: f32) -> f32 {
        let c = cover.clamp(0.0, 1.0);
        match self {
            GroundKind::Grass => 0.04 + 0.96 * (1.0 - c) * (1.0 - c),
            GroundKind::Fern => 0.3 + 0.7 * (1.0 - (2.0 * c - 1.0).abs()),
            GroundKind::Shrub => 0.1 + 0.9 * (1.0 - c),
            GroundKind::Branch => 0.15 + 0.85 * c,
            GroundKind::Rock => 1.0,
        }
    }

    /// Items per square metre in full response when no species names its own cover.
    pub fn default_density(self) -> f32 {
        match self {
            GroundKind::Grass => 3.0,
            GroundKind::Fern => 0.35,
            GroundKind::Shrub => 0.015,
            GroundKind::Branch => 0.03,
            GroundKind::Rock => 0.012,
        }
    }

    /// How the kind looks: bark colour and pattern (stems, wood, stone), leaf colour and
    /// card shape, and whether its leaves are textured cards (grass blades are plain).
    pub fn look(self) -> GroundLook {
        let look = |bark: [f32; 3], pattern, leaf: [f32; 3], shape, cards| GroundLook {
            bark,
            bark_pattern: pattern,
            leaf,
            leaf_shape: shape,
            cards,
        };
        match self {
            GroundKind::Grass => look(
                [0.1, 0.16, 0.05],
                BarkPattern::Smooth,
                [0.17, 0.30, 0.07],
                LeafShape::Needles,
                false,
            ),
            GroundKind::Fern => look(
                [0.08, 0.14, 0.04],
                BarkPattern::Smooth,
                [0.10, 0.26, 0.05],
                LeafShape::Serrated,
                true,
            ),
            GroundKind::Shrub => look(
                [0.16, 0.13, 0.10],
                BarkPattern::Smooth,
                [0.13, 0.28, 0.06],
                LeafShape::Serrated,
                true,
            ),
            GroundKind::Branch => look(
                [0.17, 0.14, 0.11],
                BarkPattern::Furrowed,
                [0.2, 0.3, 0.1],
                LeafShape::Broadleaf,
                true,
            ),
            GroundKind::Rock => look(
                [0.33, 0.32, 0.30],
                BarkPattern::Scaly,
                [0.3, 0.3, 0.3],
                LeafShape::Broadleaf,
                true,
            ),
        }
    }

    /// About how tall (or, lying, how wide) an item is, in metres: how far away it is still
    /// worth drawing.
    pub fn size(self) -> f32 {
        match self {
            GroundKind::Grass => 0.4,
            GroundKind::Fern => 0.6,
            GroundKind::Shrub => 1.4,
            GroundKind::Branch => 0.5,
            GroundKind::Rock => 0.7,
        }
    }
}

/// How a kind of ground cover looks.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GroundLook {
    /// Colour of stems, wood or stone (linear RGB), over `bark_pattern`'s texture.
    pub bark: [f32; 3],
    /// The bark texture.
    pub bark_pattern: BarkPattern,
    /// Leaf colour (linear RGB).
    pub leaf: [f32; 3],
    /// The leaf cards' texture, when `cards`.
    pub leaf_shape: LeafShape,
    /// Whether the leaves are textured cards; plain triangles otherwise.
    pub cards: bool,
}

/// One kind of cover and how dense it grows, in items per square metre where its light
/// response is full.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GroundCover {
    /// The kind.
    pub kind: GroundKind,
    /// Items per square metre at full response.
    pub density: f32,
}
