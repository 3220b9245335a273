//! [`LSystem`]: a grammar checked and compiled for the engine.

use std::sync::Arc;

use crate::engine::compile::Compiled;
use crate::engine::eval::Span;
use crate::error::{GrammarError, Location};
use crate::model::alphabet::{Alphabet, SymbolId};
use crate::model::dialect::Dialect;
use crate::model::expr::{Expr, MAX_EXPR_DEPTH, MAX_NESTING};
use crate::model::grammar::{ModuleTemplate, Production, RuleSet, SuccessorItem};
use crate::model::statement::{Blocks, Statement, expressions};
use crate::model::word::Word;
use crate::model_files::ModelFiles;

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
    /// Applied to the axiom and after every step.
    pub(crate) decomposition: RuleSet,
    pub(crate) compiled_decomposition: Compiled,
    /// Applied for interpretation only.
    pub(crate) homomorphism: RuleSet,
    pub(crate) compiled_homomorphism: Compiled,
    /// The axiom evaluated once, since its parameters are constants.
    pub(crate) axiom_word: Word,
    /// How many steps the model is meant to be derived (cpfg's `derivation length`).
    pub(crate) derivation_length: Option<u32>,
    /// The notation it was read from (which decides what its turtle symbols mean).
    pub(crate) dialect: Dialect,
    /// cpfg's sub-L-systems: each id with its productions, compiled. A module `?(id, ...)`
    /// hands the modules after it, to the matching `$`, to sub-L-system `id`.
    pub(crate) subsystems: Vec<(u32, Vec<Production>)>,
    pub(crate) compiled_subsystems: Vec<Compiled>,
    /// The symbols `?` and `$` when there are sub-L-systems.
    pub(crate) sub_markers: Option<(SymbolId, SymbolId)>,
    /// Where each production stands in the text it was parsed from: the main ones, then
    /// the decomposition's, then the homomorphism's (empty when built from parts).
    pub(crate) locations: Vec<Location>,
    /// The names of the block variables, by slot.
    pub(crate) globals: Vec<String>,
    /// The blocks run around the derivation, and their spans in `compiled.blocks`
    /// (start, start each, end each, end).
    pub(crate) blocks: Blocks,
    pub(crate) block_spans: [Span; 4],
    /// The data files the model reads (functions, curves, contours, surfaces).
    pub(crate) files: Arc<ModelFiles>,
    /// Whether the word is a ring for contexts (cpfg's `ring lsystem`): the first module's
    /// left neighbour is the last, the last's right neighbour the first.
    pub(crate) ring: bool,
}

impl PartialEq for LSystem {
    fn eq(&self, other: &Self) -> bool {
        self.alphabet.names().eq(other.alphabet.names())
            && self.constants == other.constants
            && self.ignore == other.ignore
            && self.axiom == other.axiom
            && self.productions == other.productions
            && self.decomposition == other.decomposition
            && self.homomorphism == other.homomorphism
            && self.derivation_length == other.derivation_length
            && self.globals == other.globals
            && self.subsystems == other.subsystems
            && self.blocks == other.blocks
            && self.files == other.files
            && self.ring == other.ring
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
        for (name, e) in &constants {
            // Depth first: every later check walks the tree recursively.
            if e.depth() > MAX_EXPR_DEPTH {
                return Err(GrammarError::InvalidConstant {
                    name: name.clone(),
                    message: format!("expression deeper than {MAX_EXPR_DEPTH} levels"),
                });
            }
            if !e.is_constant() || !e.eval_constant(0.0, 0).is_finite() {
                return Err(GrammarError::InvalidConstant {
                    name: name.clone(),
                    message: "value must be constant and finite".to_string(),
                });
            }
        }
        for (module, m) in axiom.iter().enumerate() {
            let bad = |message: &str| GrammarError::InvalidAxiom {
                module,
                message: message.to_string(),
            };
            if !known(m.symbol) {
                return Err(bad("unknown symbol"));
            }
            if m.args.iter().any(|a| a.depth() > MAX_EXPR_DEPTH) {
                return Err(bad("a parameter expression is too deep"));
            }
            if m.args.iter().any(|a| a.slots_used() > 0) {
                return Err(bad("uses a parameter variable"));
            }
        }
        if ignore.iter().any(|&s| !known(s)) {
            return Err(GrammarError::InvalidIgnore);
        }
        check_productions(&productions, 0, &known)?;
        let compiled = Compiled::new(&alphabet, &ignore, &productions);
        let alphabet = Arc::new(alphabet);
        let mut axiom_word = Word::empty(alphabet.clone());
        let mut params = Vec::new();
        for (module, m) in axiom.iter().enumerate() {
            params.clear();
            params.extend(m.args.iter().map(|a| a.eval_constant(0.0, 0)));
            if let Some(v) = params.iter().find(|v| !v.is_finite()) {
                return Err(GrammarError::InvalidAxiom {
                    module,
                    message: format!("parameter {v} is not finite"),
                });
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
            decomposition: RuleSet::default(),
            compiled_decomposition: Compiled::default(),
            homomorphism: RuleSet::default(),
            compiled_homomorphism: Compiled::default(),
            derivation_length: None,
            dialect: Dialect::Sylva,
            subsystems: Vec::new(),
            compiled_subsystems: Vec::new(),
            sub_markers: None,
            locations: Vec::new(),
            globals: Vec::new(),
            blocks: Blocks::default(),
            block_spans: [(0, 0); 4],
            files: Arc::default(),
            ring: false,
        })
    }

    /// This system with block variables (`globals`, by slot: the names `Expr::Global` and
    /// `Statement::Assign` refer to) and blocks run around the derivation. Checks that every
    /// expression anywhere in the grammar refers to a block variable that exists.
    pub fn with_blocks(
        mut self,
        globals: Vec<String>,
        blocks: Blocks,
    ) -> Result<LSystem, GrammarError> {
        let n = globals.len();
        let too_high = |e: &Expr| e.globals_used() > n;
        for (k, p) in self
            .productions
            .iter()
            .chain(&self.decomposition.productions)
            .chain(&self.homomorphism.productions)
            .enumerate()
        {
            let mut all = expressions(&p.pre);
            all.extend(expressions(&p.post));
            all.extend(p.condition.iter());
            all.extend(successor_expressions(&p.successor));
            if all.into_iter().any(too_high) {
                return Err(GrammarError::InvalidProduction {
                    index: k,
                    message: "uses a block variable the grammar does not have".to_string(),
                });
            }
        }
        if blocks
            .arrays
            .iter()
            .any(|a| a.slot as usize + a.len() > n || a.values.len() > a.len())
        {
            return Err(GrammarError::InvalidBlock(
                "an array reaches past the block variables or has more values than elements"
                    .to_string(),
            ));
        }
        for block in [
            &blocks.start,
            &blocks.start_each,
            &blocks.end_each,
            &blocks.end,
        ] {
            let bad = expressions(block)
                .into_iter()
                .any(|e| too_high(e) || e.slots_used() > 0 || e.depth() > MAX_EXPR_DEPTH)
                || assigned_slots(block).any(|s| s as usize >= n);
            if bad {
                return Err(GrammarError::InvalidBlock(
                    "a block uses a parameter, an unknown block variable or too deep an expression"
                        .to_string(),
                ));
            }
        }
        self.block_spans = [
            &blocks.start,
            &blocks.start_each,
            &blocks.end_each,
            &blocks.end,
        ]
        .map(|b| self.compiled.block(b));
        self.globals = globals;
        self.blocks = blocks;
        Ok(self)
    }

    /// The notation the grammar was read from: cpfg's turtle gives some symbols other
    /// meanings (`;` is a colour there), so a turtle should use that dialect's table.
    pub fn dialect(&self) -> Dialect {
        self.dialect
    }

    /// This system with sub-L-systems (cpfg): each id with its productions. In a derived
    /// word, the modules after a module `?(id, ...)` up to its matching `$` are rewritten by
    /// sub-L-system `id`'s productions (the `?` and `$` themselves by the enclosing system's);
    /// an id without productions of its own leaves them to the enclosing system. Errors when
    /// a production is invalid, or when the alphabet has no `?` and `$` to mark them.
    pub fn with_subsystems(
        mut self,
        subsystems: Vec<(u32, Vec<Production>)>,
    ) -> Result<LSystem, GrammarError> {
        if subsystems.is_empty() {
            return Ok(self);
        }
        let alphabet = self.alphabet.clone();
        let (Some(start), Some(end)) = (alphabet.id_of("?"), alphabet.id_of("$")) else {
            return Err(GrammarError::InvalidBlock(
                "sub-L-systems need the modules '?' and '$' in the grammar".to_string(),
            ));
        };
        let known = |s: SymbolId| s.index() < alphabet.len();
        let mut first = self.productions.len()
            + self.decomposition.productions.len()
            + self.homomorphism.productions.len();
        for (_, productions) in &subsystems {
            check_productions(productions, first, &known)?;
            first += productions.len();
        }
        self.compiled_subsystems = subsystems
            .iter()
            .map(|(_, p)| Compiled::new(&alphabet, &self.ignore, p))
            .collect();
        self.subsystems = subsystems;
        self.sub_markers = Some((start, end));
        Ok(self)
    }

    /// The sub-L-systems, by id, with their productions.
    pub fn subsystems(&self) -> &[(u32, Vec<Production>)] {
        &self.subsystems
    }

    /// Where production `index` stands in the grammar text (counted as in
    /// [`GrammarError::InvalidProduction`]: main productions, then the decomposition's,
    /// then the homomorphism's), when the system was parsed.
    pub fn production_location(&self, index: usize) -> Option<Location> {
        self.locations.get(index).copied()
    }

    /// This system with the places of its productions in its text.
    #[must_use]
    pub(crate) fn with_locations(mut self, locations: Vec<Location>) -> LSystem {
        self.locations = locations;
        self
    }

    /// This system with the data files its expressions read (`func`, `curveX`, ...) and
    /// its turtle draws (surfaces, contours); a model folder's are read by
    /// [`LSystem::from_model_dir`].
    #[must_use]
    pub fn with_files(mut self, files: ModelFiles) -> LSystem {
        self.files = Arc::new(files);
        self
    }

    /// The data files the model reads: its functions, curves, contours and surfaces.
    pub fn files(&self) -> &ModelFiles {
        &self.files
    }

    /// This system with its word a ring for contexts, or not (cpfg's `ring lsystem`): a
    /// left context walks on from the word's start to its end, a right context from its end
    /// to its start.
    ///
    /// ```
    /// use sylva_lsys::LSystem;
    /// // Information passed round a ring: the A moves one place right each step, and from
    /// // the last place to the first.
    /// let ring = LSystem::parse("axiom: BBA\nA < B -> A\nA -> B")?.with_ring(true);
    /// assert_eq!(ring.derive(1, 0)?.to_string(), "ABB");
    /// assert_eq!(ring.derive(3, 0)?.to_string(), "BBA");
    /// let line = ring.with_ring(false);
    /// assert_eq!(line.derive(1, 0)?.to_string(), "BBB");
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    #[must_use]
    pub fn with_ring(mut self, ring: bool) -> LSystem {
        self.ring = ring;
        self
    }

    /// Whether the word is a ring for contexts ([`LSystem::with_ring`]).
    pub fn is_ring(&self) -> bool {
        self.ring
    }

    /// This system marked as read from `dialect`.
    #[must_use]
    pub fn with_dialect(mut self, dialect: Dialect) -> LSystem {
        self.dialect = dialect;
        self
    }

    /// The block variables' names, by slot.
    pub fn globals(&self) -> &[String] {
        &self.globals
    }

    /// The blocks run around the derivation.
    pub fn blocks(&self) -> &Blocks {
        &self.blocks
    }

    /// This system stating how many steps it is meant to be derived.
    #[must_use]
    pub fn with_derivation_length(mut self, steps: Option<u32>) -> LSystem {
        self.derivation_length = steps;
        self
    }

    /// How many steps the model is meant to be derived, when it says (cpfg's `derivation
    /// length:`, sylva's `#derivation N`).
    pub fn derivation_length(&self) -> Option<u32> {
        self.derivation_length
    }

    /// This system with a decomposition (applied to the axiom and after every step) and a
    /// homomorphism (applied by [`LSystem::interpretation`]). Their productions are checked
    /// like the main ones; an invalid one is reported with its index counted after the main
    /// productions (decomposition first).
    ///
    /// ```
    /// use sylva_lsys::LSystem;
    /// // The apex A lays down a metamer B, which is decomposed into an internode and a leaf
    /// // after the step that made it.
    /// let plant: LSystem = "axiom: A\nA -> B A\n#decomposition\nB -> I[L]".parse()?;
    /// assert_eq!(plant.derive(2, 0)?.to_string(), "I[L]I[L]A");
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn with_rule_sets(
        mut self,
        decomposition: RuleSet,
        homomorphism: RuleSet,
    ) -> Result<LSystem, GrammarError> {
        let alphabet = self.alphabet.clone();
        let known = |s: SymbolId| s.index() < alphabet.len();
        check_productions(&decomposition.productions, self.productions.len(), &known)?;
        check_productions(
            &homomorphism.productions,
            self.productions.len() + decomposition.productions.len(),
            &known,
        )?;
        self.compiled_decomposition =
            Compiled::new(&alphabet, &self.ignore, &decomposition.productions);
        self.compiled_homomorphism =
            Compiled::new(&alphabet, &self.ignore, &homomorphism.productions);
        self.decomposition = decomposition;
        self.homomorphism = homomorphism;
        Ok(self)
    }

    /// The decomposition (empty when the grammar has none).
    pub fn decomposition(&self) -> &RuleSet {
        &self.decomposition
    }

    /// The homomorphism (empty when the grammar has none).
    pub fn homomorphism(&self) -> &RuleSet {
        &self.homomorphism
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

/// Checks each production's symbols, parameters, expressions and weight; `first` is the index
/// the first one is reported as.
fn check_productions(
    productions: &[Production],
    first: usize,
    known: &dyn Fn(SymbolId) -> bool,
) -> Result<(), GrammarError> {
    for (k, p) in productions.iter().enumerate() {
        let bad = |message: &str| GrammarError::InvalidProduction {
            index: first + k,
            message: message.to_string(),
        };
        if !expressions_within_depth(p) {
            return Err(bad(&format!(
                "an expression is deeper than {MAX_EXPR_DEPTH} levels or choices nest deeper than {MAX_NESTING}"
            )));
        }
        let patterns = p
            .left
            .iter()
            .chain([&p.predecessor])
            .chain(&p.predecessor_rest)
            .chain(&p.right);
        if patterns.clone().any(|pat| !known(pat.symbol)) {
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
        let blocks = [&p.pre, &p.post];
        if blocks.iter().any(|b| {
            expressions(b)
                .into_iter()
                .any(|e| e.depth() > MAX_EXPR_DEPTH || e.slots_used() > slots)
                || parameter_slots(b).any(|s| s as usize >= slots)
        }) {
            return Err(bad(
                "a block uses an unbound parameter or an expression that is too deep",
            ));
        }
        if !items_valid(&p.successor, slots, known, 0) {
            return Err(bad(
                "successor uses an unknown symbol or unbound parameter, or nests too deep",
            ));
        }
        if p.weight.is_some_and(|w| !(w.is_finite() && w >= 0.0)) {
            return Err(bad("weight must be finite and not negative"));
        }
    }
    Ok(())
}

/// The block variables `statements` assign, nested ones included.
fn assigned_slots(statements: &[Statement]) -> impl Iterator<Item = u16> + '_ {
    flatten(statements).filter_map(|s| match s {
        Statement::Assign { slot, .. } => Some(*slot),
        // An element's slot is its array's first and at most its last.
        Statement::AssignElement { slot, dims, .. } => {
            let last = crate::model::expr::elements(dims).saturating_sub(1);
            Some(slot.saturating_add(u16::try_from(last).unwrap_or(u16::MAX)))
        }
        _ => None,
    })
}

/// The parameters `statements` assign, nested ones included.
fn parameter_slots(statements: &[Statement]) -> impl Iterator<Item = u16> + '_ {
    flatten(statements).filter_map(|s| match s {
        Statement::SetParameter { slot, .. } => Some(*slot),
        _ => None,
    })
}

/// Every statement, nested ones included.
fn flatten(statements: &[Statement]) -> impl Iterator<Item = &Statement> + '_ {
    let mut pending: Vec<&Statement> = statements.iter().rev().collect();
    std::iter::from_fn(move || {
        let s = pending.pop()?;
        match s {
            Statement::If {
                then, otherwise, ..
            } => pending.extend(then.iter().chain(otherwise).rev()),
            Statement::While { body, .. } | Statement::DoWhile { body, .. } => {
                pending.extend(body.iter().rev())
            }
            _ => {}
        }
        Some(s)
    })
}

/// Every expression of a successor, in choices too.
fn successor_expressions(items: &[SuccessorItem]) -> Vec<&Expr> {
    let mut out = Vec::new();
    let mut pending: Vec<&SuccessorItem> = items.iter().collect();
    while let Some(item) = pending.pop() {
        match item {
            SuccessorItem::Module(m) => out.extend(&m.args),
            SuccessorItem::Choice {
                probability,
                then,
                otherwise,
            } => {
                out.push(probability);
                pending.extend(then.iter().chain(otherwise));
            }
        }
    }
    out
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

/// Whether every expression of the production is at most [`MAX_EXPR_DEPTH`] deep and its
/// choices nest at most [`MAX_NESTING`] deep. Walks items with an explicit stack.
fn expressions_within_depth(p: &Production) -> bool {
    if p.condition
        .as_ref()
        .is_some_and(|c| c.depth() > MAX_EXPR_DEPTH)
    {
        return false;
    }
    let mut pending = vec![(&p.successor[..], 0usize)];
    while let Some((items, nesting)) = pending.pop() {
        if nesting > MAX_NESTING {
            return false;
        }
        for item in items {
            match item {
                SuccessorItem::Module(m) => {
                    if m.args.iter().any(|a| a.depth() > MAX_EXPR_DEPTH) {
                        return false;
                    }
                }
                SuccessorItem::Choice {
                    probability,
                    then,
                    otherwise,
                } => {
                    if probability.depth() > MAX_EXPR_DEPTH {
                        return false;
                    }
                    pending.push((then, nesting + 1));
                    pending.push((otherwise, nesting + 1));
                }
            }
        }
    }
    true
}
