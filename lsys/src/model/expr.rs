//! Parameter expressions as a syntax tree: operators, functions and [`Expr`].
//!
//! Parsing lives in `syntax`, printing in `syntax::print`, compilation and evaluation in
//! `engine`. Every walk over a tree that user input shapes is either bounded by
//! [`MAX_EXPR_DEPTH`] (checked without recursion before any recursive walk) or iterative.

/// Deepest nesting of parentheses, unary operators, calls and choices the parser accepts.
pub(crate) const MAX_NESTING: usize = 64;

/// Deepest expression tree the crate accepts, counting every operator level: `a+b+c` is two
/// levels, since binary chains nest to the left. Grammars in the wild stay far below it; the
/// bound keeps every recursive walk (compiling, printing, comparing) a few hundred frames deep.
pub const MAX_EXPR_DEPTH: usize = 256;

/// A unary operator.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum UnaryOp {
    /// `-x`
    Neg,
    /// `!x`: 1 when x is 0, else 0.
    Not,
}

/// A binary operator. Comparisons and logic yield 1 for true and 0 for false.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum BinaryOp {
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `*`
    Mul,
    /// `/`
    Div,
    /// `%`: the remainder of a division (C's `fmod`).
    Rem,
    /// `^`, right-associative power.
    Pow,
    /// `<`
    Lt,
    /// `<=`
    Le,
    /// `>`
    Gt,
    /// `>=`
    Ge,
    /// `==`
    Eq,
    /// `!=`
    Ne,
    /// `&&`
    And,
    /// `||`
    Or,
}

/// A built-in function. Trigonometric functions work in radians.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Function {
    /// `sin(x)`
    Sin,
    /// `cos(x)`
    Cos,
    /// `tan(x)`
    Tan,
    /// `asin(x)`
    Asin,
    /// `acos(x)`
    Acos,
    /// `atan(x)`
    Atan,
    /// `atan2(y, x)`
    Atan2,
    /// `sqrt(x)`
    Sqrt,
    /// `exp(x)`
    Exp,
    /// `log(x)`, the natural logarithm.
    Log,
    /// `abs(x)`
    Abs,
    /// `floor(x)`
    Floor,
    /// `ceil(x)`
    Ceil,
    /// `min(a, b)`
    Min,
    /// `max(a, b)`
    Max,
    /// `uniform(a, b)`: a seeded uniform draw in `[a, b)`.
    Uniform,
    /// `ran(x)`: a seeded uniform draw in `[0, x)` (cpfg).
    Ran,
    /// `nran(mean, sd)`: a seeded normal draw (cpfg).
    Nran,
    /// `bran(a, b)`: a seeded draw from the beta distribution B(a, b) (cpfg).
    Bran,
    /// `biran(n, p)`: a seeded binomial draw, successes in `n` trials of probability `p`
    /// (cpfg).
    Biran,
    /// `select(c, a, b)`: `a` when `c` is non-zero, else `b` (C's and cpfg's `c ? a : b`;
    /// both are evaluated).
    Select,
    /// `func(id, x)`: the model's function file `id` (from 1) at `x` in [0, 1] (cpfg; the
    /// functions of a model folder, [`crate::spline`]).
    Func,
    /// `curveX(id, t)`: the x of the model's curve file `id` (from 1) a fraction `t` of its
    /// length along it (cpfg; [`crate::curve`]).
    CurveX,
    /// `curveY(id, t)`: the y, as [`Function::CurveX`].
    CurveY,
    /// `curveZ(id, t)`: the z, as [`Function::CurveX`].
    CurveZ,
    /// `curveGAL(id)`: the length of the model's curve file `id` (cpfg).
    CurveLength,
    /// `stop(n)`: `n`, and unless `n` is 1 the derivation ends after the step under way
    /// (cpfg; `stop(1)` only asks cpfg's window to draw the word, which means nothing here).
    Stop,
}

pub(crate) const FUNCTIONS: &[(&str, Function, usize)] = &[
    ("sin", Function::Sin, 1),
    ("cos", Function::Cos, 1),
    ("tan", Function::Tan, 1),
    ("asin", Function::Asin, 1),
    ("acos", Function::Acos, 1),
    ("atan", Function::Atan, 1),
    ("atan2", Function::Atan2, 2),
    ("sqrt", Function::Sqrt, 1),
    ("exp", Function::Exp, 1),
    ("log", Function::Log, 1),
    ("abs", Function::Abs, 1),
    ("floor", Function::Floor, 1),
    ("ceil", Function::Ceil, 1),
    ("min", Function::Min, 2),
    ("max", Function::Max, 2),
    ("uniform", Function::Uniform, 2),
    ("ran", Function::Ran, 1),
    ("nran", Function::Nran, 2),
    ("bran", Function::Bran, 2),
    ("biran", Function::Biran, 2),
    ("select", Function::Select, 3),
    ("func", Function::Func, 2),
    ("curveX", Function::CurveX, 2),
    ("curveY", Function::CurveY, 2),
    ("curveZ", Function::CurveZ, 2),
    ("curveGAL", Function::CurveLength, 1),
    ("stop", Function::Stop, 1),
    // cpfg's C spelling of abs.
    ("fabs", Function::Abs, 1),
];

impl Function {
    /// The name used in grammar text.
    pub fn name(self) -> &'static str {
        FUNCTIONS.iter().find(|f| f.1 == self).map_or("?", |f| f.0)
    }

    /// Number of arguments.
    pub fn arity(self) -> usize {
        FUNCTIONS.iter().find(|f| f.1 == self).map_or(0, |f| f.2)
    }

    /// Whether the function reads one of the model's files (`func`, the curves).
    pub fn reads_files(self) -> bool {
        matches!(
            self,
            Function::Func
                | Function::CurveX
                | Function::CurveY
                | Function::CurveZ
                | Function::CurveLength
        )
    }

    /// Whether a call's value depends on its arguments alone, known while compiling: not
    /// a random draw, not a model file's value, not `stop`.
    pub(crate) fn is_pure(self) -> bool {
        !self.is_random() && !self.reads_files() && self != Function::Stop
    }

    /// Whether the function draws from the derivation's random stream.
    pub fn is_random(self) -> bool {
        matches!(
            self,
            Function::Uniform | Function::Ran | Function::Nran | Function::Bran | Function::Biran
        )
    }
}

/// A parameter expression as written in the grammar.
///
/// Dropping a tree of any depth is safe (the drop is iterative); the parser and
/// [`LSystem::from_parts`](crate::LSystem::from_parts) accept trees at most
/// [`MAX_EXPR_DEPTH`] deep.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Expr {
    /// A literal number.
    Number(f64),
    /// A `#define`d constant, kept by name for printing.
    Constant {
        /// The constant's name.
        name: String,
        /// Its value.
        value: f64,
    },
    /// A formal parameter of the production, by name and binding slot.
    Var {
        /// The parameter's name.
        name: String,
        /// Its index among the production's bound parameters (left context, predecessor,
        /// right context, in order).
        slot: u16,
    },
    /// A variable of the grammar's statement blocks, by name and slot: one value for the
    /// whole derivation, set by assignments in blocks (cpfg's variables are global).
    Global {
        /// The variable's name.
        name: String,
        /// Its index among the grammar's variables.
        slot: u16,
    },
    /// An element of an array of block variables (cpfg's `len[o][i]`): the array's variables
    /// are the slots `slot..slot + dims.product()`, row-major. Each index is clamped to its
    /// dimension (as cpfg clamps, with a warning there), so a read never leaves the array.
    Element {
        /// The array's name.
        name: String,
        /// The slot of its first element among the grammar's variables.
        slot: u16,
        /// Its dimensions, outermost first.
        dims: Vec<u32>,
        /// One index per dimension.
        indices: Vec<Expr>,
    },
    /// `#`: the generation being produced (1 in the first derivation step; 0 in the axiom).
    Generation,
    /// A unary operation.
    Unary(UnaryOp, Box<Expr>),
    /// A binary operation.
    Binary(BinaryOp, Box<Expr>, Box<Expr>),
    /// A function call.
    Call(Function, Vec<Expr>),
}

impl Expr {
    /// The depth of the tree: 1 for a leaf. Measured with an explicit stack, so any tree,
    /// however deep, can be asked.
    pub fn depth(&self) -> usize {
        let mut deepest = 0;
        let mut stack = vec![(self, 1usize)];
        while let Some((e, d)) = stack.pop() {
            deepest = deepest.max(d);
            for child in e.children() {
                stack.push((child, d + 1));
            }
        }
        deepest
    }

    /// The direct subexpressions, left to right.
    pub fn children(&self) -> impl Iterator<Item = &Expr> {
        let (pair, args): ([Option<&Expr>; 2], &[Expr]) = match self {
            Expr::Unary(_, e) => ([Some(e), None], &[]),
            Expr::Binary(_, a, b) => ([Some(a), Some(b)], &[]),
            Expr::Call(_, args) => ([None, None], args),
            Expr::Element { indices, .. } => ([None, None], indices),
            _ => ([None, None], &[]),
        };
        pair.into_iter().flatten().chain(args)
    }

    /// Whether the value is the same at every use: no parameters, no `#`, no random draws.
    /// Only called on trees within [`MAX_EXPR_DEPTH`].
    pub(crate) fn is_constant(&self) -> bool {
        match self {
            Expr::Number(_) | Expr::Constant { .. } => true,
            Expr::Var { .. } | Expr::Global { .. } | Expr::Element { .. } | Expr::Generation => {
                false
            }
            Expr::Call(f, _) if !f.is_pure() => false,
            _ => self.children().all(Expr::is_constant),
        }
    }

    /// Highest slot of a block variable ([`Expr::Global`]) used plus one.
    pub(crate) fn globals_used(&self) -> usize {
        match self {
            Expr::Global { slot, .. } => *slot as usize + 1,
            Expr::Element {
                slot,
                dims,
                indices,
                ..
            } => indices
                .iter()
                .map(Expr::globals_used)
                .fold(*slot as usize + elements(dims), usize::max),
            _ => self.children().map(Expr::globals_used).max().unwrap_or(0),
        }
    }

    /// Highest variable slot used plus one. Only called on trees within [`MAX_EXPR_DEPTH`].
    pub(crate) fn slots_used(&self) -> usize {
        match self {
            Expr::Var { slot, .. } => *slot as usize + 1,
            _ => self.children().map(Expr::slots_used).max().unwrap_or(0),
        }
    }
}

/// How many elements an array of dimensions `dims` has (saturating: the parser bounds it).
pub(crate) fn elements(dims: &[u32]) -> usize {
    dims.iter()
        .fold(1usize, |n, &d| n.saturating_mul(d as usize))
}

impl Drop for Expr {
    /// Takes the children apart onto a heap stack, so that dropping a chain millions of
    /// levels deep (which only code building trees by hand can make) cannot overflow the
    /// call stack.
    fn drop(&mut self) {
        fn detach(e: &mut Expr, out: &mut Vec<Expr>) {
            match e {
                Expr::Unary(_, a) => out.push(std::mem::replace(&mut **a, Expr::Generation)),
                Expr::Binary(_, a, b) => {
                    out.push(std::mem::replace(&mut **a, Expr::Generation));
                    out.push(std::mem::replace(&mut **b, Expr::Generation));
                }
                Expr::Call(_, args) | Expr::Element { indices: args, .. } => out.append(args),
                _ => {}
            }
        }
        if matches!(
            self,
            Expr::Number(_)
                | Expr::Generation
                | Expr::Var { .. }
                | Expr::Global { .. }
                | Expr::Constant { .. }
        ) {
            return;
        }
        let mut pending = Vec::new();
        detach(self, &mut pending);
        while let Some(mut e) = pending.pop() {
            detach(&mut e, &mut pending);
        }
    }
}
