//! Settings of the turtle and of the meshes it builds.

use glam::Vec3;

use std::sync::Arc;

use crate::model_shapes::ModelShapes;
use crate::symbols::{Command, SymbolTable};

/// How branch segments become surfaces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum BranchShape {
    /// One closed cylinder per `F`, radius from the current width (the thesis's primitive).
    Cylinder,
    /// Tapered frustums whose radii run on from segment to segment; consecutive segments of
    /// one axis share their joining ring, so a branch is one smooth tube.
    #[default]
    Frustum,
}

/// Tropism: after each step the heading turns towards `direction` by `susceptibility * |H x T|`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tropism {
    /// The direction branches bend towards (gravity is `(0, -1, 0)`); need not be unit.
    pub direction: Vec3,
    /// The susceptibility `e`.
    pub susceptibility: f32,
}

/// Where a tree's stems snap: every stem at least `min_radius` thick that rises above
/// `height` ends there, a little narrower where it tore, and nothing it would have carried
/// from there on is drawn; branches that left it below stay, and thinner stems (twigs that
/// bent in the storm) reach on past the break.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StemBreak {
    /// Height of the break, in the tree's units, along +Y from its base.
    pub height: f32,
    /// The thinnest stem that snaps (radius).
    pub min_radius: f32,
}

/// The default of [`TurtleOptions::max_pieces`]: a million pieces of geometry per word (a
/// tree of that many is about 16 M triangles of tubes; the trees of a forest are thousands).
pub const MAX_PIECES: u64 = 1_000_000;

/// Turtle and meshing settings. Angles are in degrees.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct TurtleOptions {
    /// Which symbol means what. Default: ABOP's, [`SymbolTable::abop`].
    pub symbols: SymbolTable,
    /// Step length for `F` and `f` without a parameter. Default: 1.
    pub step: f32,
    /// Turning angle in degrees for rotations without a parameter. Default: 22.5.
    pub angle: f32,
    /// Initial width (diameter) in world units. Default: 0.1.
    pub width: f32,
    /// Multiplies every length given as a parameter to `F(l)` and `f(l)`: scales grammars
    /// written in other units (the ternary tree's trunk is `F(200)`) to metres. Default: 1.
    pub length_unit: f32,
    /// Multiplies every width given as a parameter to `!(w)`: grammars written in pixels
    /// (ABOP's Honda tree uses widths near 10 with unit steps) set it below 1. Default: 1.
    pub width_unit: f32,
    /// Factor for `!` without a parameter. Default: 0.7.
    pub width_factor: f32,
    /// Factor for `"` without a parameter. Default: 0.9.
    pub length_factor: f32,
    /// Factor for `;` without a parameter. Default: 0.9.
    pub angle_factor: f32,
    /// Optional tropism applied after every move. Default: none.
    pub tropism: Option<Tropism>,
    /// Leaf quad length (along the heading) and width. Default: [0.3, 0.15].
    pub leaf_size: [f32; 2],
    /// How far each leaf card turns about its heading towards facing the sky (+Y), from 0
    /// (the card lies in the turtle's heading-left plane) to 1 (its blade faces up as far as
    /// the heading allows). Leaves turn their blades to the light; from above, cards that
    /// face up cover the ground where edge-on cards would not. Default: 0.
    pub leaf_facing: f32,
    /// Cylinders or frustums. Default: frustums, [`BranchShape::Frustum`].
    pub shape: BranchShape,
    /// Vertices around each ring (at least 3). Default: 8.
    pub radial_segments: u32,
    /// Close tube ends with discs. Default: false.
    pub caps: bool,
    /// Radii below this are raised to it, so thin twigs stay visible. Default: 0.
    pub min_radius: f32,
    /// How much wider than the trunk its base flares where roots buttress it: 0 none, 0.6
    /// a base 1.6 times the trunk's radius. The flare fades over about three base radii up
    /// the first segment of the tree's first axis ([`MeshBuilder`](crate::MeshBuilder)).
    /// Default: 0.
    pub root_flare: f32,
    /// How much a branch swells where it leaves its parent, blending into it: 0 none, 0.5 a
    /// base 1.5 times the branch's radius at the parent's surface (never wider than the
    /// parent), fading over a few radii. Drawn on branches long enough to hold it (two rings
    /// each, [`MeshBuilder`](crate::MeshBuilder)). Default: 0.
    pub branch_collar: f32,
    /// How many straight pieces a stem is drawn in so that the tropism bends it along its
    /// length rather than at its end (Bloomenthal's curved stems): 1 draws every `F` as one
    /// segment; from 2 (at most 8) stems at least 15% of the first segment's radius thick
    /// that the tropism turns by more than a degree are drawn curved. Thin twigs, and trunks
    /// along the tropism, stay one piece. Default: 1.
    pub curve_steps: u32,
    /// Deepest `[` / `{` nesting accepted. Default: 1,048,576 (2^20).
    pub max_depth: usize,
    /// Most pieces of geometry (segments, leaves and polygons together) one word may draw:
    /// interpretation stops with [`TurtleError::TooManyPieces`](crate::TurtleError::TooManyPieces)
    /// past it, so a grammar that doubles its stems every generation ends in an error, not
    /// in all of memory. Default: [`MAX_PIECES`] (about 16 M triangles of tubes and 1 GB of
    /// mesh at the most).
    pub max_pieces: u64,
    /// A stem broken by a storm or lightning ([`StemBreak`]); `None` draws the whole tree.
    /// A forest's damaged trees are drawn with it (`sylva-forest`'s forms). Default: none.
    pub stem_break: Option<StemBreak>,
    /// Share of leaf cards drawn, 0 to 1: 1 draws every leaf, 0 none (a dead tree), 0.3 a
    /// crown thinned by dieback. Which leaves go is a pure function of their order in the
    /// word, so a tree thins the same way every time. Default: 1.
    pub leaf_keep: f32,
    /// A cpfg model's surfaces and contours ([`TurtleOptions::with_model_files`]).
    /// Default: empty (no surfaces or contours).
    pub shapes: Arc<ModelShapes>,
}

impl Default for TurtleOptions {
    fn default() -> Self {
        TurtleOptions {
            symbols: SymbolTable::abop(),
            step: 1.0,
            angle: 22.5,
            width: 0.1,
            length_unit: 1.0,
            width_unit: 1.0,
            width_factor: 0.7,
            length_factor: 0.9,
            angle_factor: 0.9,
            tropism: None,
            leaf_size: [0.3, 0.15],
            leaf_facing: 0.0,
            shape: BranchShape::Frustum,
            radial_segments: 8,
            caps: false,
            min_radius: 0.0,
            root_flare: 0.0,
            branch_collar: 0.0,
            curve_steps: 1,
            max_depth: 1 << 20,
            max_pieces: MAX_PIECES,
            stem_break: None,
            leaf_keep: 1.0,
            shapes: Arc::default(),
        }
    }
}

impl TurtleOptions {
    /// Sets [`TurtleOptions::root_flare`].
    #[must_use]
    pub fn with_root_flare(mut self, root_flare: f32) -> Self {
        self.root_flare = root_flare;
        self
    }

    /// Sets [`TurtleOptions::branch_collar`].
    #[must_use]
    pub fn with_branch_collar(mut self, branch_collar: f32) -> Self {
        self.branch_collar = branch_collar;
        self
    }

    /// Sets [`TurtleOptions::curve_steps`].
    #[must_use]
    pub fn with_curve_steps(mut self, curve_steps: u32) -> Self {
        self.curve_steps = curve_steps;
        self
    }

    /// Sets [`TurtleOptions::width_factor`].
    #[must_use]
    pub fn with_width_factor(mut self, width_factor: f32) -> Self {
        self.width_factor = width_factor;
        self
    }

    /// Sets [`TurtleOptions::length_factor`].
    #[must_use]
    pub fn with_length_factor(mut self, length_factor: f32) -> Self {
        self.length_factor = length_factor;
        self
    }

    /// Sets [`TurtleOptions::angle_factor`].
    #[must_use]
    pub fn with_angle_factor(mut self, angle_factor: f32) -> Self {
        self.angle_factor = angle_factor;
        self
    }

    /// Sets [`TurtleOptions::leaf_size`].
    #[must_use]
    pub fn with_leaf_size(mut self, leaf_size: [f32; 2]) -> Self {
        self.leaf_size = leaf_size;
        self
    }

    /// Sets [`TurtleOptions::leaf_facing`].
    #[must_use]
    pub fn with_leaf_facing(mut self, leaf_facing: f32) -> Self {
        self.leaf_facing = leaf_facing;
        self
    }

    /// Sets [`TurtleOptions::stem_break`].
    #[must_use]
    pub fn with_stem_break(mut self, stem_break: Option<StemBreak>) -> Self {
        self.stem_break = stem_break;
        self
    }

    /// Sets [`TurtleOptions::leaf_keep`].
    #[must_use]
    pub fn with_leaf_keep(mut self, share: f32) -> Self {
        self.leaf_keep = share;
        self
    }

    /// Sets [`TurtleOptions::max_pieces`].
    #[must_use]
    pub fn with_max_pieces(mut self, max_pieces: u64) -> Self {
        self.max_pieces = max_pieces;
        self
    }

    /// Sets [`TurtleOptions::max_depth`].
    #[must_use]
    pub fn with_max_depth(mut self, max_depth: usize) -> Self {
        self.max_depth = max_depth;
        self
    }
}

impl TurtleOptions {
    /// Sets [`TurtleOptions::angle`] (degrees).
    #[must_use]
    pub fn with_angle(mut self, degrees: f32) -> Self {
        self.angle = degrees;
        self
    }

    /// Sets [`TurtleOptions::step`].
    #[must_use]
    pub fn with_step(mut self, step: f32) -> Self {
        self.step = step;
        self
    }

    /// Sets [`TurtleOptions::width`].
    #[must_use]
    pub fn with_width(mut self, width: f32) -> Self {
        self.width = width;
        self
    }

    /// Sets [`TurtleOptions::length_unit`].
    #[must_use]
    pub fn with_length_unit(mut self, unit: f32) -> Self {
        self.length_unit = unit;
        self
    }

    /// Sets [`TurtleOptions::width_unit`].
    #[must_use]
    pub fn with_width_unit(mut self, unit: f32) -> Self {
        self.width_unit = unit;
        self
    }

    /// Sets [`TurtleOptions::tropism`].
    #[must_use]
    pub fn with_tropism(mut self, direction: Vec3, susceptibility: f32) -> Self {
        self.tropism = Some(Tropism {
            direction,
            susceptibility,
        });
        self
    }

    /// Sets [`TurtleOptions::shape`].
    #[must_use]
    pub fn with_shape(mut self, shape: BranchShape) -> Self {
        self.shape = shape;
        self
    }

    /// Sets [`TurtleOptions::radial_segments`].
    #[must_use]
    pub fn with_radial_segments(mut self, n: u32) -> Self {
        self.radial_segments = n;
        self
    }

    /// Sets [`TurtleOptions::caps`].
    #[must_use]
    pub fn with_caps(mut self, caps: bool) -> Self {
        self.caps = caps;
        self
    }

    /// Sets [`TurtleOptions::min_radius`].
    #[must_use]
    pub fn with_min_radius(mut self, r: f32) -> Self {
        self.min_radius = r;
        self
    }

    /// Sets [`TurtleOptions::symbols`].
    #[must_use]
    pub fn with_symbols(mut self, symbols: SymbolTable) -> Self {
        self.symbols = symbols;
        self
    }

    /// These options drawing a cpfg model's surfaces where its word has `~` and their letter,
    /// and sweeping its contours along generalized cylinders after `@#(id)` (set the
    /// symbols first: this adds the surfaces' names to them).
    ///
    /// ```
    /// use sylva_lsys::LSystem;
    /// use sylva_turtle::{SymbolTable, TurtleOptions};
    /// # let dir = std::env::temp_dir().join(format!("sylva-doc-shapes-{}", std::process::id()));
    /// # std::fs::create_dir_all(&dir)?;
    /// # std::fs::write(dir.join("plant.l"), "Lsystem: 1\nderivation length: 1\nAxiom: F~l(2)\nendlsystem\n")?;
    /// # std::fs::write(dir.join("plant.v"), "surface: l leaf.s 1 4 4\n")?;
    /// # std::fs::write(dir.join("leaf.s"), "0 1 0 1 0 0\nCONTACT POINT X: 0 Y: 0 Z: 0\nEND POINT X: 0 Y: 1 Z: 0\nHEADING X: 0 Y: 1 Z: 0\nUP X: 0 Y: 0 Z: 1\nSIZE: 1\np\n0 0 0 0 0.3 0 0 0.6 0 0 1 0\n0.3 0 0 0.3 0.3 0 0.3 0.6 0 0.3 1 0\n0.6 0 0 0.6 0.3 0 0.6 0.6 0 0.6 1 0\n1 0 0 1 0.3 0 1 0.6 0 1 1 0\n")?;
    /// let model = LSystem::from_model_dir(&dir)?;
    /// let options = TurtleOptions::default()
    ///     .with_symbols(SymbolTable::for_dialect(model.dialect()))
    ///     .with_model_files(model.files());
    /// assert_eq!(options, TurtleOptions::for_grammar(&model));
    /// let word = model.derive(1, 0)?;
    /// let stats = sylva_turtle::interpret(&word, &options, &mut sylva_turtle::NullSink)?;
    /// assert_eq!(stats.polygons, 16); // one patch cut 4 by 4
    /// # std::fs::remove_dir_all(&dir)?;
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    #[must_use]
    pub fn with_model_files(mut self, files: &sylva_lsys::ModelFiles) -> Self {
        let shapes = ModelShapes::new(files);
        for (k, (name, _)) in shapes.surfaces.iter().enumerate() {
            self.symbols.set(
                name.as_str(),
                Command::Surface(k.min(u16::MAX as usize) as u16),
            );
        }
        self.shapes = Arc::new(shapes);
        self
    }

    /// The turtle a grammar file draws with: its dialect's symbols ([`SymbolTable::for_dialect`])
    /// and its model's surfaces and contours ([`TurtleOptions::with_model_files`]).
    pub fn for_grammar(grammar: &sylva_lsys::LSystem) -> Self {
        TurtleOptions::default()
            .with_symbols(SymbolTable::for_dialect(grammar.dialect()))
            .with_model_files(grammar.files())
    }

    /// Options matching a bundled preset's published angle and tropism.
    pub fn for_preset(preset: &sylva_lsys::Preset) -> Self {
        let mut o = TurtleOptions::default().with_angle(preset.angle as f32);
        if let Some((d, e)) = preset.tropism {
            o = o.with_tropism(Vec3::new(d[0] as f32, d[1] as f32, d[2] as f32), e as f32);
        }
        o
    }
}
