//! Error types for parsing grammars and deriving words.

use std::fmt;

/// Where in the source text something went wrong: 1-based line and column (in characters).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Location {
    /// 1-based line number.
    pub line: usize,
    /// 1-based column, counted in Unicode scalar values.
    pub column: usize,
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "line {}, column {}", self.line, self.column)
    }
}

/// ` (production at line L, column C)` when the place is known, else nothing.
struct At(Option<Location>);

impl fmt::Display for At {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            Some(at) => write!(f, " (the production at {at})"),
            None => Ok(()),
        }
    }
}

/// A grammar or word that could not be parsed.
///
/// Fix the text at [`ParseError::location`]; the message says what the parser expected there.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{location}: {message}")]
#[non_exhaustive]
pub struct ParseError {
    /// Where the problem is.
    pub location: Location,
    /// What was expected or what is wrong, in words.
    pub message: String,
}

impl ParseError {
    pub(crate) fn new(line: usize, column: usize, message: impl Into<String>) -> Self {
        Self {
            location: Location { line, column },
            message: message.into(),
        }
    }
}

/// A grammar that cannot be used as built (only from
/// [`LSystem::from_parts`](crate::LSystem::from_parts); text input
/// reports a [`ParseError`](crate::ParseError) instead).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum GrammarError {
    /// A production refers to a symbol not in the alphabet, a parameter slot it does not bind,
    /// nests choices deeper than the parser allows, or has an expression deeper than
    /// [`MAX_EXPR_DEPTH`](crate::MAX_EXPR_DEPTH). Fix the production named.
    #[error("production {index}: {message}")]
    InvalidProduction {
        /// Index of the production.
        index: usize,
        /// What is wrong.
        message: String,
    },
    /// An axiom module uses a symbol not in the alphabet, a parameter variable, or a value
    /// that is not finite. Fix the module named.
    #[error("axiom module {module}: {message}")]
    InvalidAxiom {
        /// Index of the module in the axiom.
        module: usize,
        /// What is wrong.
        message: String,
    },
    /// A `#define` constant is not a finite constant expression within the depth limit.
    #[error("constant '{name}': {message}")]
    InvalidConstant {
        /// The constant's name.
        name: String,
        /// What is wrong.
        message: String,
    },
    /// The ignore set names a symbol that is not in the alphabet.
    #[error("the ignore set names a symbol that is not in the alphabet")]
    InvalidIgnore,
    /// A block run around the derivation (cpfg's `Start:` and the like) uses a parameter,
    /// an unknown block variable or too deep an expression.
    #[error("block: {0}")]
    InvalidBlock(String),
}

/// A derivation that was stopped before it could finish.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum DeriveError {
    /// The [`Environment`](crate::Environment) could not answer.
    #[error("generation {generation}: the environment failed: {error}")]
    Environment {
        /// The generation it was asked about.
        generation: u32,
        /// Why it could not answer.
        #[source]
        error: crate::EnvironmentError,
    },
    /// A statement block ran more statements than
    /// [`MAX_BLOCK_STATEMENTS`](crate::MAX_BLOCK_STATEMENTS) in one run: a loop that does
    /// not end.
    #[error(
        "generation {generation}: a statement block ran more than {limit} statements (a loop that never ends?){}",
        At(*at)
    )]
    EndlessBlock {
        /// The generation being produced.
        generation: u32,
        /// The limit.
        limit: u64,
        /// Where the production whose block it was stands, when known.
        at: Option<Location>,
    },
    /// The derivation's blocks ran more statements in all than
    /// [`Limits::max_statements`](crate::Limits::max_statements).
    #[error(
        "generation {generation}: the grammar's blocks ran more than {limit} statements in all"
    )]
    TooManyStatements {
        /// The generation being produced.
        generation: u32,
        /// The limit in force.
        limit: u64,
    },
    /// A decomposition or homomorphism still rewrote modules after its maximum depth of
    /// passes: its productions recurse without end, or the depth is set too low.
    #[error(
        "the {section} still rewrites modules after its maximum depth of {depth} passes (generation {generation}){}: a production recurses without end, or raise 'maximum depth'",
        At(*at)
    )]
    TooDeep {
        /// `decomposition` or `homomorphism`.
        section: &'static str,
        /// The maximum depth in force.
        depth: u32,
        /// The generation being decomposed (0 for the axiom) or interpreted.
        generation: u32,
        /// Where the production that still fired stands in the grammar text, when the
        /// grammar was parsed.
        at: Option<Location>,
    },
    /// The word grew past [`Limits::max_modules`](crate::Limits::max_modules).
    /// Derive fewer generations or raise the limit if the memory is really there.
    #[error("generation {generation} would exceed the limit of {limit} modules")]
    TooManyModules {
        /// The generation (1-based) that hit the limit.
        generation: u32,
        /// The limit in force.
        limit: usize,
    },
    /// The word's parameters grew past [`Limits::max_params`](crate::Limits::max_params).
    /// Derive fewer generations or raise the limit.
    #[error("generation {generation} would exceed the limit of {limit} parameters")]
    TooManyParams {
        /// The generation (1-based) that hit the limit.
        generation: u32,
        /// The limit in force.
        limit: usize,
    },
    /// More generations were asked for than
    /// [`Limits::max_generations`](crate::Limits::max_generations) allows.
    #[error("{requested} generations requested, the limit is {limit}")]
    TooManyGenerations {
        /// Generations asked for.
        requested: u32,
        /// The limit in force.
        limit: u32,
    },
    /// An expression produced infinity or NaN (for example a division by zero).
    /// Guard the production with a condition or change the constants.
    #[error(
        "generation {generation}: parameter {index} of module '{symbol}' is not finite ({value})"
    )]
    NonFiniteParameter {
        /// The generation (1-based) in which it happened.
        generation: u32,
        /// The module's symbol.
        symbol: String,
        /// Which parameter (0-based).
        index: usize,
        /// The offending value.
        value: f64,
    },
}

/// A grammar file that could not be read or parsed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum GrammarFileError {
    /// The file could not be read, is not text or is larger than
    /// [`MAX_GRAMMAR_BYTES`](crate::MAX_GRAMMAR_BYTES).
    #[error(transparent)]
    File(#[from] sylva_base::text_file::TextFileError),
    /// A model folder without its model: no `.l` file, or several.
    #[error("{}: {message}", path.display())]
    Model {
        /// The folder.
        path: std::path::PathBuf,
        /// What is wrong.
        message: String,
    },
    /// The text has an error at the location given.
    #[error("{}:{}:{}: {}", path.display(), error.location.line, error.location.column, error.message)]
    Parse {
        /// The file.
        path: std::path::PathBuf,
        /// Where and what.
        error: ParseError,
    },
}
