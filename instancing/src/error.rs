//! Errors of instancing.

use sylva_lsys::{DeriveError, GrammarError};
use sylva_turtle::TurtleError;

/// Why a cache or a tree could not be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum InstancingError {
    /// The grammar already uses one of the marker symbols; choose other [`Markers`](crate::Markers).
    #[error("the grammar already uses the marker symbol '{0}'")]
    MarkerInUse(char),
    /// Rewriting produced an invalid grammar (a bug if it ever happens with a parsed grammar).
    #[error("rewritten grammar is invalid: {0}")]
    Grammar(#[from] GrammarError),
    /// Deriving a hero or naive tree failed (usually a size limit).
    #[error("derivation: {0}")]
    Derive(#[from] DeriveError),
    /// Interpreting a hero or naive tree failed.
    #[error("turtle: {0}")]
    Turtle(#[from] TurtleError),
    /// The budget cannot hold even one hero tree of this species. Raise the budget or use fewer
    /// generations.
    #[error("a cache budget of {budget} bytes cannot hold one hero tree ({needed} bytes)")]
    BudgetTooSmall {
        /// The budget.
        budget: usize,
        /// Bytes the smallest hero needed.
        needed: usize,
    },
    /// The explicit 2^B form was asked of a production with more branches than it expands.
    #[error(
        "explicit form not available: production {production} has {branches} branches, more than {limit}"
    )]
    ExplicitTooManyBranches {
        /// The production, counted from 0.
        production: usize,
        /// Its branches.
        branches: usize,
        /// The most the explicit form expands.
        limit: usize,
    },
    /// The explicit form was asked of a deterministic production whose predecessor has other
    /// productions: its variants would join their weighted draw.
    #[error(
        "explicit form not available: production {production} is deterministic and shares its predecessor"
    )]
    ExplicitSharedPredecessor {
        /// The production, counted from 0.
        production: usize,
    },
    /// A tree referred to a species with no cache.
    #[error("no cache for species {0}")]
    UnknownSpecies(u16),
    /// Assembling a tree went deeper, or placed more instances, than the limits allow.
    #[error("tree assembly exceeded its limit of {0}")]
    AssemblyLimit(&'static str),
    /// A setting is NaN, infinite or out of its range.
    #[error(transparent)]
    OutOfRange(#[from] sylva_base::range::OutOfRange),
}
