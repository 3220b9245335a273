//! Grammar rewriting into instancing form (Kenwood section 4): branch detection, then each
//! branch either recorded between start/stop markers or replaced by a get-instance exit.

use std::collections::{BTreeSet, HashMap};

use sylva_lsys::{
    Alphabet, BinaryOp, Expr, LSystem, ModuleTemplate, POP, PUSH, Production, SuccessorItem,
    SymbolId,
};

use crate::error::InstancingError;

/// The three marker symbols the rewritten grammar uses. Each carries (branch id, age).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub struct Markers {
    /// Start of a recorded instance (Kenwood's startInstance). Default: `⟦`.
    pub start: char,
    /// End of a recorded instance (stopInstance). Default: `⟧`.
    pub stop: char,
    /// An exit to be filled with a cached instance (getInstance). Default: `◆`.
    pub get: char,
}

impl Default for Markers {
    fn default() -> Self {
        Markers {
            start: '⟦',
            stop: '⟧',
            get: '◆',
        }
    }
}

/// A branch found in a successor: a top-level `[ ... ]` holding at least one non-terminal.
#[derive(Debug, Clone, PartialEq)]
pub struct Branch {
    /// Its global id (1 and up; 0 is the whole tree). Identical branches share an id.
    pub id: u32,
    /// Index of the production it was found in.
    pub production: usize,
    /// Its text, as printed in the grammar.
    pub text: String,
}

/// A grammar prepared for instancing: the branches of every production and what is needed to
/// emit the instancing form for any instancing probability.
#[derive(Debug, Clone)]
pub struct InstancingGrammar {
    base: LSystem,
    markers: Markers,
    alphabet: Alphabet,
    ids: [SymbolId; 3],
    branches: Vec<Branch>,
    /// Per production: (first item, last item inclusive, branch id) of each branch.
    spans: Vec<Vec<(usize, usize, u32)>>,
    branch_count: u32,
}

fn item_text(item: &SuccessorItem, alphabet: &Alphabet) -> String {
    match item {
        SuccessorItem::Module(m) => {
            let args: Vec<String> = m.args.iter().map(ToString::to_string).collect();
            if args.is_empty() {
                alphabet.char(m.symbol).to_string()
            } else {
                format!("{}({})", alphabet.char(m.symbol), args.join(","))
            }
        }
        other => format!("{other:?}"),
    }
}

fn holds_nonterminal(items: &[SuccessorItem], nonterminals: &BTreeSet<SymbolId>) -> bool {
    items.iter().any(|item| match item {
        SuccessorItem::Module(m) => nonterminals.contains(&m.symbol),
        SuccessorItem::Choice {
            then, otherwise, ..
        } => holds_nonterminal(then, nonterminals) || holds_nonterminal(otherwise, nonterminals),
        _ => false,
    })
}

/// Top-level bracket pairs of a successor, as (open, close) item indices.
fn top_level_brackets(items: &[SuccessorItem]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut depth = 0usize;
    let mut open = 0;
    for (i, item) in items.iter().enumerate() {
        let SuccessorItem::Module(m) = item else {
            continue;
        };
        if m.symbol == PUSH {
            if depth == 0 {
                open = i;
            }
            depth += 1;
        } else if m.symbol == POP && depth > 0 {
            depth -= 1;
            if depth == 0 {
                out.push((open, i));
            }
        }
    }
    out
}

impl InstancingGrammar {
    /// Detects the branches of `grammar` (Kenwood's algorithm 1, Carey's "valid branch"):
    /// a top-level bracketed part of a successor that holds a non-terminal (a symbol some
    /// production rewrites). Branches with identical text share one id across productions.
    ///
    /// ```
    /// let g = sylva_lsys::preset("kenwood-leafy").unwrap().lsystem().unwrap();
    /// let ig = sylva_instancing::internal::InstancingGrammar::new(&g, Default::default()).unwrap();
    /// // [&FL!A] appears twice and [^FL!A] once; the leaf's brackets hold no non-terminal.
    /// assert_eq!(ig.branch_count(), 2);
    /// assert_eq!(ig.branches().len(), 3);
    /// ```
    pub fn new(grammar: &LSystem, markers: Markers) -> Result<Self, InstancingError> {
        let mut alphabet = (**grammar.alphabet()).clone();
        let mut ids = [SymbolId(0); 3];
        for (slot, c) in ids
            .iter_mut()
            .zip([markers.start, markers.stop, markers.get])
        {
            if alphabet.id(c).is_some() {
                return Err(InstancingError::MarkerInUse(c));
            }
            *slot = alphabet.intern(c).ok_or(InstancingError::MarkerInUse(c))?;
        }
        // Every symbol a production rewrites, a string predecessor's later modules too.
        let nonterminals: BTreeSet<SymbolId> = grammar
            .productions()
            .iter()
            .flat_map(|p| {
                std::iter::once(p.predecessor.symbol)
                    .chain(p.predecessor_rest.iter().map(|q| q.symbol))
            })
            .collect();
        let mut by_text: HashMap<String, u32> = HashMap::new();
        let mut branches = Vec::new();
        let mut spans = Vec::new();
        for (pi, p) in grammar.productions().iter().enumerate() {
            let mut found = Vec::new();
            for (open, close) in top_level_brackets(&p.successor) {
                if !holds_nonterminal(&p.successor[open + 1..close], &nonterminals) {
                    continue;
                }
                let text: String = p.successor[open..=close]
                    .iter()
                    .map(|i| item_text(i, &alphabet))
                    .collect();
                let next = by_text.len() as u32 + 1;
                let id = *by_text.entry(text.clone()).or_insert(next);
                branches.push(Branch {
                    id,
                    production: pi,
                    text,
                });
                found.push((open, close, id));
            }
            spans.push(found);
        }
        Ok(InstancingGrammar {
            base: grammar.clone(),
            markers,
            alphabet,
            ids,
            branches,
            spans,
            branch_count: by_text.len() as u32,
        })
    }

    /// Every branch occurrence, in production order.
    pub fn branches(&self) -> &[Branch] {
        &self.branches
    }

    /// Number of distinct branch ids (not counting 0, the whole tree).
    pub fn branch_count(&self) -> u32 {
        self.branch_count
    }

    /// The marker symbols.
    pub fn markers(&self) -> Markers {
        self.markers
    }

    /// The original grammar.
    pub fn base(&self) -> &LSystem {
        &self.base
    }

    fn marker(&self, which: usize, id: u32, age: Expr) -> SuccessorItem {
        SuccessorItem::Module(ModuleTemplate {
            symbol: self.ids[which],
            args: vec![Expr::Number(f64::from(id)), age],
        })
    }

    fn axiom(&self) -> Vec<ModuleTemplate> {
        let wrap = |which: usize| ModuleTemplate {
            symbol: self.ids[which],
            args: vec![Expr::Number(0.0), Expr::Number(0.0)],
        };
        let bracket = |symbol| ModuleTemplate {
            symbol,
            args: Vec::new(),
        };
        // The brackets end the trunk's axis before the stop marker, so that its closing cap
        // falls inside the whole-tree instance.
        let mut axiom = vec![wrap(0), bracket(PUSH)];
        axiom.extend(self.base.axiom().iter().cloned());
        axiom.extend([bracket(POP), wrap(1)]);
        axiom
    }

    fn recorded(&self, items: &[SuccessorItem], id: u32) -> Vec<SuccessorItem> {
        let mut v = vec![self.marker(0, id, Expr::Generation)];
        v.extend(items.iter().cloned());
        v.push(self.marker(1, id, Expr::Generation));
        v
    }

    /// The instancing grammar with `productions`, keeping the base grammar's decomposition
    /// and homomorphism (they rewrite the same modules).
    fn build(&self, productions: Vec<Production>) -> Result<LSystem, InstancingError> {
        Ok(LSystem::from_parts(
            self.alphabet.clone(),
            self.base.constants().to_vec(),
            self.base.ignore().to_vec(),
            self.axiom(),
            productions,
        )?
        .with_rule_sets(
            self.base.decomposition().clone(),
            self.base.homomorphism().clone(),
        )?)
    }

    /// The compact instancing form: every branch becomes an independent choice
    /// `?(p)<get(id,#)><start(id,#)[...]stop(id,#)>` with `p = probability(id)` (an
    /// expression that may use `#`). One right-hand side per production, yet the same
    /// distribution as the paper's 2^B right-hand sides ([`InstancingGrammar::explicit`]).
    pub fn compact(&self, probability: impl Fn(u32) -> Expr) -> Result<LSystem, InstancingError> {
        let productions = self
            .base
            .productions()
            .iter()
            .zip(&self.spans)
            .map(|(p, spans)| {
                let mut q = p.clone();
                q.successor = self.replace_branches(p, spans, |_, branch, id, items| {
                    items.push(SuccessorItem::Choice {
                        probability: probability(id),
                        then: vec![self.marker(2, id, Expr::Generation)],
                        otherwise: self.recorded(branch, id),
                    });
                });
                q
            })
            .collect();
        self.build(productions)
    }

    /// The successor of `p` with each branch in `spans` replaced by what `replace` appends;
    /// `replace` gets the branch's index among the production's branches, its items and id.
    fn replace_branches(
        &self,
        p: &Production,
        spans: &[(usize, usize, u32)],
        mut replace: impl FnMut(usize, &[SuccessorItem], u32, &mut Vec<SuccessorItem>),
    ) -> Vec<SuccessorItem> {
        let mut items = Vec::with_capacity(p.successor.len() + 2 * spans.len());
        let mut next = 0;
        for (k, &(open, close, id)) in spans.iter().enumerate() {
            items.extend(p.successor[next..open].iter().cloned());
            replace(k, &p.successor[open..=close], id, &mut items);
            next = close + 1;
        }
        items.extend(p.successor[next..].iter().cloned());
        items
    }

    /// The paper's explicit form: a production with B branches becomes 2^B productions, one per
    /// subset of instanced branches, weighted `w * P^i * (1 - P)^(B - i)` where `w` is the
    /// original weight (1 for a deterministic production). Errors when B > 12, or when a
    /// predecessor has several productions and one of them is deterministic with branches (its
    /// variants would join the others' weighted draw).
    pub fn explicit(&self, p: f64) -> Result<LSystem, InstancingError> {
        sylva_base::range::check(
            "instancing probability",
            p,
            (0.0..=1.0).contains(&p),
            "in [0, 1]",
        )?;
        let prods = self.base.productions();
        let mut out = Vec::new();
        for (k, (prod, spans)) in prods.iter().zip(&self.spans).enumerate() {
            let b = spans.len();
            if b == 0 {
                out.push(prod.clone());
                continue;
            }
            if b > 12 {
                return Err(InstancingError::ExplicitTooManyBranches {
                    production: k,
                    branches: b,
                    limit: 12,
                });
            }
            let siblings = prods
                .iter()
                .filter(|q| q.predecessor.symbol == prod.predecessor.symbol)
                .count();
            if prod.weight.is_none() && siblings > 1 {
                return Err(InstancingError::ExplicitSharedPredecessor { production: k });
            }
            let w = prod.weight.unwrap_or(1.0);
            for mask in 0u32..(1 << b) {
                let i = mask.count_ones() as i32;
                let mut q = prod.clone();
                q.successor = self.replace_branches(prod, spans, |bit, branch, id, items| {
                    if mask & (1 << bit) != 0 {
                        items.push(self.marker(2, id, Expr::Generation));
                    } else {
                        items.extend(self.recorded(branch, id));
                    }
                });
                q.weight = Some(w * p.powi(i) * (1.0 - p).powi(b as i32 - i));
                out.push(q);
            }
        }
        self.build(out)
    }
}

/// `p * ((# == a1) || (# == a2) || ...)`: probability `p` at the listed ages, 0 elsewhere.
pub fn probability_at_ages(p: f64, ages: &[u32]) -> Expr {
    let Some((first, rest)) = ages.split_first() else {
        return Expr::Number(0.0);
    };
    let is_age = |a: u32| {
        Expr::Binary(
            BinaryOp::Eq,
            Box::new(Expr::Generation),
            Box::new(Expr::Number(f64::from(a))),
        )
    };
    let any = rest.iter().fold(is_age(*first), |acc, &a| {
        Expr::Binary(BinaryOp::Or, Box::new(acc), Box::new(is_age(a)))
    });
    Expr::Binary(BinaryOp::Mul, Box::new(Expr::Number(p)), Box::new(any))
}
