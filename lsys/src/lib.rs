//! L-system grammars in ABOP / cpfg notation, and a fast seeded rewriting engine.
//!
//! ```
//! use sylva_lsys::LSystem;
//!
//! let plant: LSystem = "
//!     #define r 0.5
//!     axiom: A(1)
//!     A(x) : x < 4 -> F(x)[+A(x*2)][-A(x+r)]
//! ".parse()?;
//! let word = plant.derive(2, 7)?;
//! assert_eq!(word.to_string(), "F(1)[+F(2)[+A(4)][-A(2.5)]][-F(1.5)[+A(3)][-A(2)]]");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Grammar language
//!
//! One statement per line. Whitespace between modules is ignored. Comments are `/* ... */`
//! (may span lines) and lines starting with `//`.
//!
//! - `#define NAME expression`: a named constant, usable in every later expression.
//! - `#ignore: + - F`: symbols skipped when matching contexts.
//! - `#module Apex Internode`: module names of several characters.
//! - `axiom: modules` (or `ω: modules`): the initial word; parameters are constant expressions.
//! - Productions: `label: lc < pred(params) > rc : condition -> successor : weight`. Only the
//!   predecessor, the arrow (`->` or `→`) and the successor are required. The label (two or
//!   more letters or digits, as ABOP prints `p1:`) is ignored. A condition of `*` means none.
//!
//! A module is one character (anything but whitespace and `( ) , < > : ? #`) followed by an
//! optional parameter list, or a name of several characters declared with `#module Apex
//! Internode` (L-Py's `module`): the text is read by the longest declared name it continues
//! with, and words of such grammars print with spaces between modules. In predecessors and
//! contexts the parameters are names; in successors they are expressions.
//!
//! **Choosing a production.** The productions of a predecessor are tried in order. Those whose
//! parameter count, contexts and condition match form the candidates. If the first candidate
//! has no weight it fires. Otherwise one of the weighted candidates is drawn with probability
//! proportional to its weight (weights need not sum to 1). A module with no candidate is copied.
//!
//! **Contexts** follow ABOP section 1.8. Walking left from the predecessor, whole branches
//! `[...]` are skipped and a `[` leads to the parent's module; walking right, branches are
//! skipped unless the pattern itself enters them with `[` (and `]` in a pattern skips to the end
//! of the current branch). Symbols in `#ignore` are skipped both ways.
//!
//! **Expressions** have `+ - * / ^` (power, right-associative), comparisons `< <= > >= == !=`,
//! `&& || !`, unary minus and parentheses; truth is 1 and falsehood 0. Functions: `sin cos tan
//! asin acos atan atan2 sqrt exp log abs floor ceil min max` (radians), and the seeded random
//! draws `uniform(a, b)`, `ran(x)` (uniform in `[0, x)`), `nran(mean, sd)` (normal), `bran(a,
//! b)` (beta) and `biran(n, p)` (binomial); `c ? a : b` (or `select(c, a, b)`) and `%`.
//! `#` is the age symbol: the generation being produced (1 in the first step, 0 in the axiom),
//! so `B(#)` records when a module was introduced.
//!
//! **Cut.** The symbol `%` removes itself and the rest of its branch at the end of the step
//! that produced it (ABOP section 3.3.1 / cpfg).
//!
//! **Decomposition and homomorphism** (cpfg): a line `#decomposition [depth N]` or
//! `#homomorphism [depth N]` starts a section; the productions after it belong to it. The
//! decomposition rewrites the axiom and every step's word until none of its productions fires
//! (splitting a module into its parts); the homomorphism is applied the same way by
//! [`LSystem::interpretation`] to the word the turtle draws, and never changes development.
//! Each pass rewrites all modules in parallel; more than `N` passes that still fire (default
//! 1, at most [`MAX_RULE_DEPTH`]) is a [`DeriveError::TooDeep`], or with
//! `#homomorphism depth N stop` the end of the rewriting, the modules still rewritable kept as
//! they are (cpfg's way, and the cpfg dialect's: its `maximum depth:` keeps them).
//!
//! **Statement blocks** (cpfg): `A(x) : { x = x + 1; n = n + 1; } x < 5 { y = x * 2; } -> B(y)`.
//! A block before the condition runs when the production is tried (it may change the
//! production's own parameters); a block after it runs when the production is applied.
//! Statements are assignments, `if (c) ... else ...`, `while (c) ...`, `do ... while (c);`,
//! `srand(seed);` and expressions. Every other name assigned in a block is a block variable,
//! one value for the whole derivation; `#start { ... }`, `#starteach`, `#endeach` and `#end`
//! run blocks around the derivation and each step. Runs are bounded
//! ([`MAX_BLOCK_STATEMENTS`] per block, [`Limits::max_statements`] per derivation).
//! `#array len[2][3] = {1, 2, 3, 4}` declares an [`Array`] of block variables (cpfg's
//! `define: { array len[2][3] = {...}; }`): values row-major, zeros after them, set before
//! `#start`; `len[i][j]` reads an element and `len[i][j] = v;` sets one, each index clamped
//! to its dimension as cpfg clamps it. cpfg's `stop(n)` (`n` other than 1) ends the
//! derivation after the step that called it.
//!
//! **Rings** (cpfg's `ring lsystem`, `#ring`, [`LSystem::with_ring`]): the word's ends join
//! for contexts, the first module's left neighbour being the last.
//!
//! **Choices** (a sylva extension): `?(p)<then><otherwise>` in a successor emits `then` with
//! probability `p` and `otherwise` else, drawn independently each time the production fires.
//!
//! # Dialects
//!
//! [`LSystem::parse`] reads sylva's notation above, or cpfg's `.l` files when the text has
//! an `Lsystem:` line; [`LSystem::parse_dialect`] names the [`Dialect`] (cpfg, or the
//! declarative subset of L-Py's `.lpy` files) and [`LSystem::from_file`] goes by extension.
//! cpfg files pass through a C preprocessor of their own (`#define` with and without
//! parameters, `#if`, `#ifdef`); their trigonometry is in degrees. A vlab model is a folder:
//! [`LSystem::from_model_dir`] reads its `.l` file with the files beside it that it includes
//! and that its view file names ([`ModelFiles`]: functions for `func`, curves for `curveX`,
//! `curveY`, `curveZ` and `curveGAL`, contours and surfaces for the turtle). What a dialect
//! has that the engine does not run (cpfg's file functions, Python code) is refused with an
//! `unsupported: ...` error at its line and column. Every grammar prints in
//! sylva's notation and reads back to the same system. [`LSystem::derive_in`] asks an
//! [`Environment`] to answer query and communication modules between steps.
//!
//! # Determinism and limits
//!
//! [`LSystem::derive`] is a pure function of the grammar, the step count and the seed: one
//! PCG stream (`rand_pcg::Pcg64Mcg`) is consumed in word order. Words grow exponentially, so
//! every derivation runs under [`Limits`] (modules, parameters, generations) and returns
//! [`DeriveError`] instead of exhausting memory:
//!
//! ```
//! let doubling: sylva_lsys::LSystem = "axiom: F\nF -> FF".parse().unwrap();
//! assert!(doubling.derive(64, 0).is_err());
//! ```
//!
//! # Representation
//!
//! A [`Word`] is structure-of-arrays: `u16` symbol ids, `u32` parameter offsets and one flat
//! `f64` parameter array. Expressions are compiled once into postfix programs with constant
//! subtrees folded; a step streams one word into the next and allocates nothing per module.
//!
//! # Feature flags
//!
//! - `serde`: `Serialize`/`Deserialize` for [`SymbolId`].
//! - `proptest`: the `strategies` module, proptest strategies (words over a grammar's
//!   alphabet, well-formed grammars, parameters) for property tests of your own grammars.
//!
//! # Conventions
//!
//! Angles in turtle parameters are degrees (the turtle crate reads them); math functions in
//! expressions take radians. Parameters are `f64`.

// The modules form layers: `model` (data) <- `engine` (check, compile, derive) <- `syntax`
// (parse, print). No module reaches back up.
pub mod curve;
mod engine;
mod error;
mod file_lines;
mod model;
mod model_files;
mod presets;
pub mod spline;
#[cfg(feature = "proptest")]
pub mod strategies;
pub mod surface;
mod syntax;

pub use engine::block::MAX_BLOCK_STATEMENTS;
pub use engine::derive::{Deriver, Limits};
pub use engine::environment::{Environment, EnvironmentError};
pub use engine::lsystem::LSystem;
pub use error::{DeriveError, GrammarError, GrammarFileError, Location, ParseError};
pub use model::alphabet::{Alphabet, CUT, MAX_NAME_CHARS, POP, PUSH, RESERVED, SymbolId};
pub use model::dialect::Dialect;
pub use model::expr::{BinaryOp, Expr, Function, MAX_EXPR_DEPTH, UnaryOp};
pub use model::grammar::{ModuleTemplate, Pattern, Production, RuleSet, SuccessorItem};
pub use model::statement::{Array, Blocks, Statement};
pub use model::word::{Module, Word};
pub use model_files::ModelFiles;
pub use presets::{PRESETS, Preset, preset};
pub use syntax::parser::{MAX_GRAMMAR_BYTES, MAX_RULE_DEPTH};

impl LSystem {
    /// Parses grammar text. Errors name the line and column and say what was expected.
    ///
    /// ```
    /// let err = sylva_lsys::LSystem::parse("axiom: A\nA -> B(1,").unwrap_err();
    /// assert_eq!((err.location.line, err.location.column), (2, 10));
    /// ```
    ///
    /// The dialect is the one the text declares ([`Dialect::declared_in`]): cpfg when a line
    /// starts with `Lsystem:`, else sylva's notation.
    pub fn parse(text: &str) -> Result<LSystem, ParseError> {
        syntax::read::parse(text)
    }

    /// Parses grammar text written in `dialect`.
    ///
    /// ```
    /// use sylva_lsys::{Dialect, LSystem};
    /// let cpfg = "
    ///     #define STEPS 3
    ///     Lsystem: 1
    ///     derivation length: STEPS
    ///     Axiom: A(0)
    ///     A(n) : n < 2 --> F(sin(90)) [+A(n+1)] A(n+1)
    ///     A(n) : n >= 2 --> *
    ///     endlsystem";
    /// let plant = LSystem::parse_dialect(cpfg, Dialect::Cpfg)?;
    /// assert_eq!(plant.derivation_length(), Some(3));
    /// // Angles in cpfg's trigonometry are degrees: sin(90) = 1.
    /// assert_eq!(plant.derive(3, 0)?.to_string(), "F(1)[+F(1)[+]]F(1)[+]");
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn parse_dialect(text: &str, dialect: Dialect) -> Result<LSystem, ParseError> {
        syntax::read::parse_dialect(text, dialect)
    }

    /// Parses grammar text written in `dialect` whose expressions read `files` (`func(id, x)`
    /// its functions, id 1 the first; a function set's names are defined as their ids in
    /// cpfg text; `curveX(id, t)` and the others its curves): a model's files without its
    /// folder, or a model printed and read back.
    ///
    /// ```
    /// use sylva_lsys::spline::SplineFunction;
    /// use sylva_lsys::{Dialect, LSystem, ModelFiles};
    /// let up = SplineFunction::new(None, vec![[0.0, 0.0], [0.4, 0.4], [0.6, 0.6], [1.0, 1.0]], Some(11))?;
    /// let files = ModelFiles { functions: vec![up], ..ModelFiles::default() };
    /// let g = LSystem::parse_with_files("axiom: A\nA -> B(func(1, 0.5))", Dialect::Sylva, files)?;
    /// let b = g.derive(1, 0)?.params(0)[0];
    /// assert!((b - 0.5).abs() < 2e-3);
    /// // Printed, it reads back with the same functions.
    /// let again = LSystem::parse_with_files(&g.to_string(), Dialect::Sylva, g.files().clone())?;
    /// assert_eq!(again.derive(1, 0)?, g.derive(1, 0)?);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn parse_with_files(
        text: &str,
        dialect: Dialect,
        files: ModelFiles,
    ) -> Result<LSystem, ParseError> {
        syntax::read::parse_with(text, dialect, None, files).map_err(|e| e.error)
    }
}

impl LSystem {
    /// Reads and parses a grammar file of at most [`MAX_GRAMMAR_BYTES`], in the dialect its
    /// extension names (`.l`: cpfg) or its text declares. Errors name the file, line and
    /// column.
    ///
    /// ```
    /// let path = std::env::temp_dir().join("sylva-lsys-doctest.lsys");
    /// std::fs::write(&path, "axiom: A\nA -> B(").unwrap();
    /// let err = sylva_lsys::LSystem::from_file(&path).unwrap_err();
    /// assert!(err.to_string().ends_with("sylva-lsys-doctest.lsys:2:8: expected a number, a name, '#' or '(' in an expression, found end of line"));
    /// # std::fs::remove_file(&path).ok();
    /// ```
    pub fn from_file(path: impl AsRef<std::path::Path>) -> Result<LSystem, GrammarFileError> {
        let path = path.as_ref();
        let text = sylva_base::text_file::read(path, MAX_GRAMMAR_BYTES as u64)?;
        let dialect = match Dialect::of_path(path) {
            Dialect::Sylva => Dialect::declared_in(&text),
            named => named,
        };
        LSystem::parse_dialect(&text, dialect).map_err(|error| GrammarFileError::Parse {
            path: path.to_path_buf(),
            error,
        })
    }
}

impl LSystem {
    /// Reads a vlab model: a folder holding one `.l` file, or a `.l` file inside its folder,
    /// with the files beside it that the model includes (`#include "name"`, read from the
    /// folder only, at most 16 deep). Errors name the file they are in, the model's or an
    /// included one, with its line and column.
    ///
    /// ```
    /// let dir = std::env::temp_dir().join(format!("sylva-model-doctest-{}", std::process::id()));
    /// std::fs::create_dir_all(&dir).unwrap();
    /// std::fs::write(dir.join("constants.h"), "#define STEPS 3\n#define ANGLE 30\n").unwrap();
    /// std::fs::write(
    ///     dir.join("plant.l"),
    ///     "#include \"constants.h\"\nLsystem: 1\nderivation length: STEPS\naxiom: A\n\
    ///      A --> F[+(ANGLE)A]A\nendlsystem\n",
    /// )
    /// .unwrap();
    /// let plant = sylva_lsys::LSystem::from_model_dir(&dir)?;
    /// assert_eq!(plant.derivation_length(), Some(3));
    /// assert_eq!(plant.derive(1, 0)?.to_string(), "F[+(30)A]A");
    /// // A mistake in the included file is reported there.
    /// std::fs::write(dir.join("constants.h"), "#define STEPS 3\n#if\n").unwrap();
    /// let err = sylva_lsys::LSystem::from_model_dir(&dir).unwrap_err().to_string();
    /// assert!(err.contains("constants.h"), "{err}");
    /// # std::fs::remove_dir_all(&dir).ok();
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn from_model_dir(path: impl AsRef<std::path::Path>) -> Result<LSystem, GrammarFileError> {
        syntax::model_folder::read_model(path.as_ref())
    }
}

impl std::str::FromStr for LSystem {
    type Err = ParseError;
    fn from_str(text: &str) -> Result<LSystem, ParseError> {
        syntax::read::parse(text)
    }
}
