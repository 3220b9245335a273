//! The parts of a grammar: patterns, successor templates and productions.

use crate::model::alphabet::SymbolId;
use crate::model::expr::Expr;
use crate::model::statement::Statement;

/// A module in a predecessor or context: a symbol and the names of its formal parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct Pattern {
    /// The symbol to match.
    pub symbol: SymbolId,
    /// Formal parameter names; a module matches only with the same number of parameters.
    pub params: Vec<String>,
}

/// A module to produce: a symbol and one expression per parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct ModuleTemplate {
    /// The symbol to emit.
    pub symbol: SymbolId,
    /// Expressions for the parameters.
    pub args: Vec<Expr>,
}

/// One element of a successor.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum SuccessorItem {
    /// Emit one module.
    Module(ModuleTemplate),
    /// A stochastic alternative (a sylva extension, written `?(p)<then><otherwise>`): with
    /// probability `p` emit `then`, else `otherwise`. The draw is made independently each time
    /// the production fires. The instancing crate uses it to decide each branch on its own.
    Choice {
        /// Probability of `then`, evaluated when the production fires; clamped to [0, 1].
        probability: Expr,
        /// Emitted with probability `p`.
        then: Vec<SuccessorItem>,
        /// Emitted with probability `1 - p`.
        otherwise: Vec<SuccessorItem>,
    },
}

/// A production `lc < pred > rc : condition -> successor : weight`.
#[derive(Debug, Clone, PartialEq)]
pub struct Production {
    /// Left context, nearest module last. Empty when the production has none.
    pub left: Vec<Pattern>,
    /// The module this production rewrites.
    pub predecessor: Pattern,
    /// The modules after the first of a string predecessor (cpfg's `A B --> ...`): they must
    /// follow it in order, with nothing between, and are rewritten with it. Empty when the
    /// predecessor is one module.
    pub predecessor_rest: Vec<Pattern>,
    /// Right context, may contain `[` and `]` to enter or leave branches. Empty when none.
    pub right: Vec<Pattern>,
    /// Statements run before the condition is tested (cpfg's block before the condition).
    pub pre: Vec<Statement>,
    /// The condition; `None` is always true.
    pub condition: Option<Expr>,
    /// Statements run when the production is applied, before its successor is made.
    pub post: Vec<Statement>,
    /// What replaces the predecessor.
    pub successor: Vec<SuccessorItem>,
    /// Weight for stochastic choice; `None` makes the production deterministic.
    pub weight: Option<f64>,
}

impl Production {
    /// Number of parameters bound by the contexts and the predecessor together, in the order
    /// left context, predecessor, the rest of a string predecessor, right context.
    pub fn binding_count(&self) -> usize {
        self.left
            .iter()
            .chain(std::iter::once(&self.predecessor))
            .chain(&self.predecessor_rest)
            .chain(&self.right)
            .map(|p| p.params.len())
            .sum()
    }
}

/// Productions applied outside the derivation steps, recursively: a decomposition (after
/// every step and to the axiom, splitting modules into their parts) or a homomorphism (only
/// for interpretation: what the turtle draws for each module). Each pass rewrites every
/// module in parallel, as a step does; passes repeat until none fires. A pass beyond
/// `max_depth` that would still fire is an error, or with `stops_at_depth` the end of the
/// rewriting.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct RuleSet {
    /// The productions, tried in order as in a step.
    pub productions: Vec<Production>,
    /// Most passes that may fire (cpfg's `maximum depth`).
    pub max_depth: u32,
    /// Whether the modules still rewritable after `max_depth` passes are kept as they are
    /// (cpfg's way: a module at the maximum depth is drawn or kept unchanged) rather than
    /// the rewriting being an error ([`DeriveError::TooDeep`](crate::DeriveError)).
    pub stops_at_depth: bool,
}

impl RuleSet {
    /// Whether the set has no productions (then it changes nothing).
    pub fn is_empty(&self) -> bool {
        self.productions.is_empty()
    }
}
