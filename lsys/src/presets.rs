//! Grammars shipped with the crate: ABOP figures, the Garden of Eden trees, Kenwood's leafy tree.

use crate::engine::lsystem::LSystem;
use crate::error::ParseError;

/// A bundled grammar with the viewing settings it was published with.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct Preset {
    /// Short name, used by the examples' `--preset`.
    pub name: &'static str,
    /// Where it comes from, in a line.
    pub description: &'static str,
    /// The grammar text.
    pub source: &'static str,
    /// Generations of the published figure.
    pub generations: u32,
    /// Default turning angle in degrees, for symbols without a parameter.
    pub angle: f64,
    /// Tropism direction and susceptibility `e` of the published figure, if any.
    pub tropism: Option<([f64; 3], f64)>,
}

impl Preset {
    /// Parses the bundled grammar. Bundled grammars always parse (a test checks every one).
    pub fn lsystem(&self) -> Result<LSystem, ParseError> {
        LSystem::parse(self.source)
    }
}

macro_rules! preset {
    ($name:literal, $desc:literal, $generations:expr, $angle:expr, $tropism:expr) => {
        Preset {
            name: $name,
            description: $desc,
            source: include_str!(concat!("../presets/", $name, ".lsys")),
            generations: $generations,
            angle: $angle,
            tropism: $tropism,
        }
    };
}

/// Every bundled grammar.
pub const PRESETS: &[Preset] = &[
    preset!(
        "abop-1.24a",
        "ABOP figure 1.24a, bracketed edge-rewriting plant",
        5,
        25.7,
        None
    ),
    preset!(
        "abop-1.24b",
        "ABOP figure 1.24b, bracketed edge-rewriting plant",
        5,
        20.0,
        None
    ),
    preset!(
        "abop-1.24c",
        "ABOP figure 1.24c, bracketed edge-rewriting bush",
        4,
        22.5,
        None
    ),
    preset!(
        "abop-1.24d",
        "ABOP figure 1.24d, node-rewriting plant",
        7,
        20.0,
        None
    ),
    preset!(
        "abop-1.24e",
        "ABOP figure 1.24e, node-rewriting plant",
        7,
        25.7,
        None
    ),
    preset!(
        "abop-1.24f",
        "ABOP figure 1.24f, node-rewriting plant",
        5,
        22.5,
        None
    ),
    preset!(
        "abop-honda",
        "ABOP figure 2.6a, Honda's monopodial tree",
        10,
        45.0,
        None
    ),
    preset!(
        "abop-ternary",
        "ABOP figure 2.8a, ternary branching tree",
        6,
        18.95,
        Some(([0.0, -1.0, 0.0], 0.22))
    ),
    preset!("goe-honda", "Garden of Eden HondaTree", 10, 45.0, None),
    preset!(
        "goe-ternary",
        "Garden of Eden TernaryTree",
        6,
        18.95,
        Some(([0.0, -1.0, 0.0], 0.27))
    ),
    preset!(
        "goe-random",
        "Garden of Eden RandomTree, stochastic junctions and parameter variation",
        6,
        18.95,
        Some(([0.0, -1.0, 0.0], 0.22))
    ),
    preset!(
        "kenwood-leafy",
        "Kenwood, Gain and Marais 2014 table 3, leafy tree",
        7,
        22.5,
        None
    ),
    preset!(
        "sylva-oak",
        "A broad oak: spreading sympodial limbs, a wide rounded crown (metres)",
        7,
        30.0,
        Some(([0.0, -1.0, 0.0], 0.05))
    ),
    preset!(
        "sylva-birch",
        "A silver birch: slender pale trunk, narrow crown, hanging twigs (metres)",
        9,
        35.0,
        Some(([0.0, -1.0, 0.0], 0.35))
    ),
    preset!(
        "sylva-spruce",
        "A Norway spruce: straight leader, whorls of drooping needled branches, a narrow cone (metres)",
        16,
        40.0,
        Some(([0.0, -1.0, 0.0], 0.05))
    ),
    preset!(
        "sylva-pine",
        "A Scots pine: tall clear orange bole, a flattened crown of needle tufts (metres)",
        13,
        40.0,
        None
    ),
    preset!(
        "sylva-hazel",
        "A hazel shrub: many stems from the ground fanning out like a vase (metres)",
        6,
        35.0,
        None
    ),
];

/// The bundled grammar called `name`.
///
/// ```
/// let p = sylva_lsys::preset("abop-1.24a").unwrap();
/// let word = p.lsystem().unwrap().derive(1, 0).unwrap();
/// assert_eq!(word.to_string(), "F[+F]F[-F]F");
/// ```
pub fn preset(name: &str) -> Option<&'static Preset> {
    PRESETS.iter().find(|p| p.name == name)
}
