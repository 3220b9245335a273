//! The grammar model: productions, successors, the `LSystem` type and its printer.

use std::fmt;
use std::sync::Arc;

use crate::alphabet::{Alphabet, SymbolId};
use crate::compile::Compiled;
use crate::expr::{Expr, MAX_NESTING};

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
    /// Right context, may contain `[` and `]` to enter or leave branches. Empty when none.
    pub right: Vec<Pattern>,
    /// The condition; `None` is always true.
    pub condition: Option<Expr>,
    /// What replaces the predecessor.
    pub successor: Vec<SuccessorItem>,
    /// Weight for stochastic choice; `None` makes the production deterministic.
    pub weight: Option<f64>,
}

impl Production {
    /// Number of parameters bound by the contexts and the predecessor together.
    pub fn binding_count(&self) -> usize {
        self.left
            .iter()
            .chain(std::iter::once(&self.predecessor))
            .chain(&self.right)
            .map(|p| p.params.len())
            .sum()
    }
}

/// A grammar that cannot be used as built (only from [`LSystem::from_parts`]; text input
/// reports a [`ParseError`](crate::ParseError) instead).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum GrammarError {
    /// A production refers to a symbol not in the alphabet, a parameter slot it does not bind,
    /// or nests choices deeper than the parser allows. Fix the production named.
    #[error("production {index}: {message}")]
    InvalidProduction {
        /// Index of the production.
        index: usize,
        /// What is wrong.
        message: String,
    },
    /// The axiom uses a symbol not in the alphabet or a parameter variable.
    #[error("axiom: {0}")]
    InvalidAxiom(String),
}

/// A parsed, compiled L-system: axiom, productions, constants and the context ignore set.
///
/// Build one with [`LSystem::parse`] (or `str::parse`) and derive words with
/// [`LSystem::derive`]. `Display` prints grammar text that parses back to an equal system.
#[derive(Debug, Clone)]
pub struct LSystem {
    pub(crate) alphabet: Arc<Alphabet>,
    pub(crate) constants: Vec<(String, Expr)>,
    pub(crate) ignore: Vec<SymbolId>,
    pub(crate) axiom: Vec<ModuleTemplate>,
    pub(crate) productions: Vec<Production>,
    pub(crate) compiled: Compiled,
    /// The axiom evaluated once, since its parameters are constants.
    pub(crate) axiom_word: crate::word::Word,
}

impl PartialEq for LSystem {
    fn eq(&self, other: &Self) -> bool {
        self.alphabet.chars() == other.alphabet.chars()
            && self.constants == other.constants
            && self.ignore == other.ignore
            && self.axiom == other.axiom
            && self.productions == other.productions
    }
}

impl LSystem {
    /// Builds a system from its parts, checking that every symbol is in `alphabet` and every
    /// variable is bound.
    pub fn from_parts(
        alphabet: Alphabet,
        constants: Vec<(String, Expr)>,
        ignore: Vec<SymbolId>,
        axiom: Vec<ModuleTemplate>,
        productions: Vec<Production>,
    ) -> Result<LSystem, GrammarError> {
        let known = |s: SymbolId| s.index() < alphabet.len();
        for (i, m) in axiom.iter().enumerate() {
            if !known(m.symbol) {
                return Err(GrammarError::InvalidAxiom(format!(
                    "module {i} has an unknown symbol"
                )));
            }
            if m.args.iter().any(|a| a.slots_used() > 0) {
                return Err(GrammarError::InvalidAxiom(format!(
                    "module {i} uses a parameter variable"
                )));
            }
        }
        for (index, p) in productions.iter().enumerate() {
            let bad = |message: &str| GrammarError::InvalidProduction {
                index,
                message: message.to_string(),
            };
            let patterns = p.left.iter().chain([&p.predecessor]).chain(&p.right);
            if patterns.clone().any(|pat| !known(pat.symbol)) || ignore.iter().any(|&s| !known(s)) {
                return Err(bad("unknown symbol"));
            }
            if patterns
                .clone()
                .any(|pat| pat.params.len() > u8::MAX as usize)
            {
                return Err(bad("more than 255 parameters on one module"));
            }
            let slots = p.binding_count();
            if p.condition.as_ref().is_some_and(|c| c.slots_used() > slots) {
                return Err(bad("condition uses an unbound parameter"));
            }
            if !items_valid(&p.successor, slots, &known, 0) {
                return Err(bad(
                    "successor uses an unknown symbol or unbound parameter, or nests too deep",
                ));
            }
            if p.weight.is_some_and(|w| !(w.is_finite() && w >= 0.0)) {
                return Err(bad("weight must be finite and not negative"));
            }
        }
        let compiled = Compiled::new(&alphabet, &ignore, &productions);
        let alphabet = Arc::new(alphabet);
        let mut axiom_word = crate::word::Word::empty(alphabet.clone());
        let mut params = Vec::new();
        for m in &axiom {
            params.clear();
            params.extend(m.args.iter().map(|a| a.eval_constant(0.0, 0)));
            if let Some(v) = params.iter().find(|v| !v.is_finite()) {
                return Err(GrammarError::InvalidAxiom(format!(
                    "parameter {v} is not finite"
                )));
            }
            axiom_word.push(m.symbol, &params);
        }
        Ok(LSystem {
            axiom_word,
            alphabet,
            constants,
            ignore,
            axiom,
            productions,
            compiled,
        })
    }

    /// The symbols of this system.
    pub fn alphabet(&self) -> &Arc<Alphabet> {
        &self.alphabet
    }

    /// The `#define` constants in order, by name and defining expression.
    pub fn constants(&self) -> &[(String, Expr)] {
        &self.constants
    }

    /// The value of a `#define` constant.
    pub fn constant(&self, name: &str) -> Option<f64> {
        self.constants
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, e)| e.eval_constant(0.0, 0))
    }

    /// Symbols skipped when matching contexts (`#ignore`).
    pub fn ignore(&self) -> &[SymbolId] {
        &self.ignore
    }

    /// The axiom's modules.
    pub fn axiom(&self) -> &[ModuleTemplate] {
        &self.axiom
    }

    /// The productions in the order they are tried.
    pub fn productions(&self) -> &[Production] {
        &self.productions
    }
}

fn items_valid(
    items: &[SuccessorItem],
    slots: usize,
    known: &dyn Fn(SymbolId) -> bool,
    depth: usize,
) -> bool {
    if depth > MAX_NESTING {
        return false;
    }
    items.iter().all(|item| match item {
        SuccessorItem::Module(m) => {
            known(m.symbol) && m.args.iter().all(|a| a.slots_used() <= slots)
        }
        SuccessorItem::Choice {
            probability,
            then,
            otherwise,
        } => {
            probability.slots_used() <= slots
                && items_valid(then, slots, known, depth + 1)
                && items_valid(otherwise, slots, known, depth + 1)
        }
    })
}

pub(crate) struct PatternsDisplay<'a>(pub(crate) &'a [Pattern], pub(crate) &'a Alphabet);

impl fmt::Display for PatternsDisplay<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, p) in self.0.iter().enumerate() {
            // Spaces keep "/*" and a leading "//" from reading back as comments.
            if i > 0 {
                f.write_str(" ")?;
            }
            write!(f, "{}", self.1.char(p.symbol))?;
            if !p.params.is_empty() {
                write!(f, "({})", p.params.join(","))?;
            }
        }
        Ok(())
    }
}

pub(crate) struct ItemsDisplay<'a>(pub(crate) &'a [SuccessorItem], pub(crate) &'a Alphabet);

impl fmt::Display for ItemsDisplay<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut previous: Option<&ModuleTemplate> = None;
        for item in self.0 {
            match item {
                SuccessorItem::Module(m) => {
                    separate(f, previous, m, self.1)?;
                    write_template(f, m, self.1)?;
                    previous = Some(m);
                    continue;
                }
                SuccessorItem::Choice {
                    probability,
                    then,
                    otherwise,
                } => write!(
                    f,
                    "?({probability})<{}><{}>",
                    ItemsDisplay(then, self.1),
                    ItemsDisplay(otherwise, self.1)
                )?,
            }
            previous = None;
        }
        Ok(())
    }
}

/// Writes a space where two modules would otherwise print as the comment opener `/*`.
fn separate(
    f: &mut fmt::Formatter<'_>,
    previous: Option<&ModuleTemplate>,
    next: &ModuleTemplate,
    alphabet: &Alphabet,
) -> fmt::Result {
    match previous {
        Some(p)
            if p.args.is_empty()
                && alphabet.char(p.symbol) == '/'
                && alphabet.char(next.symbol) == '*' =>
        {
            f.write_str(" ")
        }
        _ => Ok(()),
    }
}

fn write_template(
    f: &mut fmt::Formatter<'_>,
    m: &ModuleTemplate,
    alphabet: &Alphabet,
) -> fmt::Result {
    write!(f, "{}", alphabet.char(m.symbol))?;
    if !m.args.is_empty() {
        f.write_str("(")?;
        for (i, a) in m.args.iter().enumerate() {
            if i > 0 {
                f.write_str(",")?;
            }
            write!(f, "{a}")?;
        }
        f.write_str(")")?;
    }
    Ok(())
}

impl fmt::Display for LSystem {
    /// Writes the grammar in the notation [`LSystem::parse`] reads.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let a = &*self.alphabet;
        for (name, e) in &self.constants {
            writeln!(f, "#define {name} {e}")?;
        }
        if !self.ignore.is_empty() {
            let s: Vec<String> = self.ignore.iter().map(|&s| a.char(s).to_string()).collect();
            writeln!(f, "#ignore: {}", s.join(" "))?;
        }
        f.write_str("axiom: ")?;
        let mut previous = None;
        for m in &self.axiom {
            separate(f, previous, m, a)?;
            write_template(f, m, a)?;
            previous = Some(m);
        }
        writeln!(f)?;
        for p in &self.productions {
            if !p.left.is_empty() {
                write!(f, "{} < ", PatternsDisplay(&p.left, a))?;
            }
            write!(
                f,
                "{}",
                PatternsDisplay(std::slice::from_ref(&p.predecessor), a)
            )?;
            if !p.right.is_empty() {
                write!(f, " > {}", PatternsDisplay(&p.right, a))?;
            }
            if let Some(c) = &p.condition {
                write!(f, " : {c}")?;
            }
            write!(f, " -> {}", ItemsDisplay(&p.successor, a))?;
            if let Some(w) = p.weight {
                write!(f, " : {w}")?;
            }
            writeln!(f)?;
        }
        Ok(())
    }
}
