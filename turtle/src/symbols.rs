//! Which symbol means what: the turtle's command table.

use std::collections::HashMap;

use sylva_lsys::{Alphabet, Dialect};

/// What the turtle does for one symbol.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Command {
    /// `F(l)`: move forward by `l` (default: current step) and draw a segment.
    Draw,
    /// `f(l)`: move forward without drawing.
    Move,
    /// `+(a)` / `-(a)`: turn left / right by `a` degrees about the up vector.
    Yaw(Sign),
    /// `&(a)` / `^(a)`: pitch down / up about the left vector.
    Pitch(Sign),
    /// `/(a)` / `\(a)`: roll right / left about the heading.
    Roll(Sign),
    /// `|`: turn around (yaw by 180 degrees).
    TurnAround,
    /// `$`: roll so that the left vector is horizontal.
    RollToHorizontal,
    /// `[`: push the turtle state.
    Push,
    /// `]`: pop the turtle state.
    Pop,
    /// `!(w)`: set the width; without a parameter, multiply it by the width factor.
    Width,
    /// `"(s)`: multiply the current step length by `s` (default: the length factor).
    ScaleLength,
    /// `;(s)`: multiply the current angle by `s` (default: the angle factor).
    ScaleAngle,
    /// `{`: start a polygon.
    PolygonStart,
    /// `.`: add the current position to the polygon.
    PolygonVertex,
    /// `}`: close and emit the polygon.
    PolygonEnd,
    /// A leaf: a quad in the turtle's frame; optional parameter scales it.
    Leaf,
    /// Passed to the sink with its parameters and the current frame, otherwise ignored.
    Marker,
    /// `@o(d)`: a sphere of diameter `d` (default: the current width) at the turtle.
    Sphere,
    /// `@c(d)`: a disc of diameter `d` (default: the current width) across the heading.
    Disc,
    /// `@Gs`: start a generalized cylinder at the turtle; draws inside it only move.
    CurveStart,
    /// `@Gc`: a control point of the generalized cylinder, at the turtle with its width.
    CurvePoint,
    /// `@Ge`: the last control point: the smooth tube through them all is drawn.
    CurveEnd,
    /// A query module (cpfg's `?P`, `?H`, `?L`, `?U`): the sink is told where the turtle is
    /// ([`GeometrySink::query`](crate::GeometrySink::query)), so that
    /// [`Queries`](crate::Queries) can write it into the module's parameters.
    Query,
    /// `@Tp(x, y, z)`: the tropism direction from here on in this branch (default gravity,
    /// `(0, -1, 0)`), keeping the susceptibility.
    TropismDirection,
    /// `@Ts(e)`: the tropism susceptibility from here on in this branch (0 turns tropism
    /// off), keeping the direction.
    TropismSusceptibility,
    /// `;(n)` / `,(n)`: set the colour index to `n`; without a parameter, the next or the
    /// previous index (cpfg, L-Py). Meshes record it per triangle.
    Colour(Sign),
    /// `?(id, s)`: cpfg's start of a sub-L-system: lengths and widths are scaled by `s` until
    /// the matching [`Command::SubEnd`].
    SubStart,
    /// `$` in cpfg: the end of a sub-L-system; the scale before it returns.
    SubEnd,
    /// `~l(s)`: the model's surface number `k` (cpfg's `~` and the surface's letter), `s`
    /// times its size ([`TurtleOptions::with_model_files`](crate::TurtleOptions::with_model_files)).
    Surface(u16),
    /// `@#(id)`: generalized cylinders from here on in this branch take the model's contour
    /// `id` as their cross-section (0, or an id the model lacks: a circle).
    Contour,
    /// Does nothing (cpfg's `@Gt`).
    Ignore,
}

/// What cpfg and L-Py both mean beyond ABOP: colour indices, spheres, discs and tropism.
const VLAB_COMMON: &[(&str, Command)] = &[
    (";", Command::Colour(Sign::Positive)),
    (",", Command::Colour(Sign::Negative)),
    ("@o", Command::Sphere),
    ("@O", Command::Sphere),
    ("@c", Command::Disc),
    ("@Tp", Command::TropismDirection),
    ("@Ts", Command::TropismSusceptibility),
];

/// Direction of a rotation command.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Sign {
    /// The command's positive sense (`+`, `&`, `/`).
    Positive,
    /// The opposite sense (`-`, `^`, `\`).
    Negative,
}

impl Sign {
    pub(crate) fn factor(self) -> f32 {
        match self {
            Sign::Positive => 1.0,
            Sign::Negative => -1.0,
        }
    }
}

/// Maps symbols (one character, or a module name of several) to [`Command`]s. Symbols not in
/// the table are skipped by the turtle.
///
/// ```
/// use sylva_turtle::{Command, SymbolTable};
/// let mut table = SymbolTable::abop();
/// table.set('G', Command::Move); // make G a move too
/// table.set('S', Command::Marker);
/// table.set("Internode", Command::Draw);
/// assert_eq!(table.get("F"), Some(Command::Draw));
/// assert_eq!(table.get("Internode"), Some(Command::Draw));
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SymbolTable {
    commands: HashMap<String, Command>,
}

impl Default for SymbolTable {
    fn default() -> Self {
        Self::abop()
    }
}

impl SymbolTable {
    /// An empty table: every symbol is skipped.
    pub fn empty() -> Self {
        SymbolTable {
            commands: HashMap::new(),
        }
    }

    /// The ABOP 3D turtle: `F f + - & ^ / \ | $ [ ] ! " ; { . }`, and `~` and `J` for leaves
    /// (ABOP's predefined surface, and the Carey report's leaf).
    pub fn abop() -> Self {
        use Command::*;
        let entries = [
            ('F', Draw),
            ('f', Move),
            ('+', Yaw(Sign::Positive)),
            ('-', Yaw(Sign::Negative)),
            ('&', Pitch(Sign::Positive)),
            ('^', Pitch(Sign::Negative)),
            ('/', Roll(Sign::Positive)),
            ('\\', Roll(Sign::Negative)),
            ('|', TurnAround),
            ('$', RollToHorizontal),
            ('[', Push),
            (']', Pop),
            ('!', Width),
            ('"', ScaleLength),
            (';', ScaleAngle),
            ('{', PolygonStart),
            ('.', PolygonVertex),
            ('}', PolygonEnd),
            ('~', Leaf),
            ('J', Leaf),
        ];
        SymbolTable {
            commands: entries
                .into_iter()
                .map(|(c, command)| (c.to_string(), command))
                .collect(),
        }
    }

    /// Sets what `symbol` (a character or a name) means.
    pub fn set(&mut self, symbol: impl Into<String>, command: Command) -> &mut Self {
        self.commands.insert(symbol.into(), command);
        self
    }

    /// Makes the turtle skip `symbol`.
    pub fn remove(&mut self, symbol: impl Into<String>) -> &mut Self {
        self.commands.remove(&symbol.into());
        self
    }

    /// What the symbol named `name` means, if anything.
    pub fn get(&self, name: &str) -> Option<Command> {
        self.commands.get(name).copied()
    }

    /// cpfg's turtle: ABOP's, where `;` and `,` change the colour index (recorded per
    /// triangle in the mesh), `#` sets the width like `!`, `@o`/`@O` spheres, `@c` discs
    /// and `@Gs`/`@Gc`/`@Ge` generalized cylinders draw, `@v` rolls to horizontal, and
    /// `?(id, s)` ... `$` scale a sub-L-system.
    pub fn cpfg() -> Self {
        Self::abop().with(VLAB_COMMON).with(&[
            ("#", Command::Width),
            ("@Gs", Command::CurveStart),
            ("@Gc", Command::CurvePoint),
            ("@Gt", Command::Ignore),
            ("@#", Command::Contour),
            ("@Ge", Command::CurveEnd),
            ("@v", Command::RollToHorizontal),
            ("?", Command::SubStart),
            ("$", Command::SubEnd),
            ("?P", Command::Query),
            ("?H", Command::Query),
            ("?L", Command::Query),
            ("?U", Command::Query),
        ])
    }

    /// L-Py's turtle: ABOP's, where `_` sets the width, `;` and `,` change the colour index,
    /// and `@O`/`@o` draw spheres.
    pub fn lpy() -> Self {
        Self::abop()
            .with(VLAB_COMMON)
            .with(&[("_", Command::Width)])
    }

    /// This table with `entries` set.
    fn with(mut self, entries: &[(&str, Command)]) -> Self {
        for &(name, command) in entries {
            self.set(name, command);
        }
        self
    }

    /// The table of the notation a grammar was read from ([`sylva_lsys::LSystem::dialect`]).
    pub fn for_dialect(dialect: Dialect) -> Self {
        match dialect {
            Dialect::Cpfg => Self::cpfg(),
            Dialect::LPy => Self::lpy(),
            _ => Self::abop(),
        }
    }

    /// The table as a dense array indexed by the alphabet's symbol ids.
    pub(crate) fn resolve(&self, alphabet: &Alphabet) -> Vec<Option<Command>> {
        alphabet.names().map(|n| self.get(n)).collect()
    }
}
