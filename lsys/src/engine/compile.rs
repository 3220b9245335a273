//! The compiled form of a grammar that the engine runs: flat programs and per-symbol tables.

use crate::engine::block::{self, Instruction};
use crate::engine::eval::{Op, Span};
use crate::model::alphabet::{Alphabet, CUT, POP, PUSH, SymbolId};
use crate::model::grammar::{Pattern, Production, SuccessorItem};
use crate::model::statement::Statement;

#[derive(Debug, Clone)]
pub(crate) enum CItem {
    Module {
        symbol: SymbolId,
        args: Span,
    },
    Choice {
        probability: Span,
        then: Span,
        otherwise: Span,
    },
}

#[derive(Debug, Clone)]
pub(crate) struct CPattern {
    pub(crate) symbol: SymbolId,
    pub(crate) arity: u8,
}

#[derive(Debug, Clone)]
pub(crate) struct CProduction {
    pub(crate) left: Vec<CPattern>,
    pub(crate) arity: u8,
    /// The modules after the first of a string predecessor.
    pub(crate) rest: Vec<CPattern>,
    pub(crate) right: Vec<CPattern>,
    pub(crate) condition: Option<Span>,
    /// The blocks before the condition and on application, as spans of `blocks`.
    pub(crate) pre: Span,
    pub(crate) post: Span,
    pub(crate) successor: Span,
    pub(crate) weight: Option<f64>,
    /// Upper bound on the modules one application emits, for the size limit check.
    pub(crate) max_modules: u32,
    pub(crate) max_params: u32,
    /// When every successor item is a module with constant arguments, the successor
    /// pre-evaluated: a span into `const_symbols`/`const_ends` and one into `const_params`.
    pub(crate) constant: Option<(Span, Span)>,
}

/// How a plain table ([`Compiled::plain`]) rewrites a symbol.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum PlainRule {
    /// No production rewrites it: it is copied.
    Copied,
    /// Production `.0` always fires; its successor is `const_symbols[.1 .. .2]`.
    Fixed(u32, u32, u32),
    /// A weighted draw among productions whose weights add up to `total`: each choice's
    /// production, weight and successor span, in the order they are tried.
    Drawn {
        /// The weights' sum ([`Compiled::draw_total`]).
        total: f64,
        /// `(production, weight, (start, end))` in `const_symbols`.
        choices: Vec<(u32, f64, (u32, u32))>,
    },
}

#[derive(Debug, Clone, Default)]
pub(crate) struct Compiled {
    pub(crate) ops: Vec<Op>,
    /// Statement blocks' instructions; their expressions are in `ops`.
    pub(crate) blocks: Vec<Instruction>,
    /// Per successor-module argument: its program in `ops`.
    pub(crate) args: Vec<Span>,
    pub(crate) items: Vec<CItem>,
    pub(crate) productions: Vec<CProduction>,
    /// For symbol `s`, its productions are `by_symbol[s.0 .. s.0+1]` into `order`.
    pub(crate) by_symbol: Vec<u32>,
    pub(crate) order: Vec<u32>,
    pub(crate) ignored: Vec<bool>,
    pub(crate) has_context: bool,
    /// For each symbol: its only production when that one always fires (no context, no
    /// condition, no weight), else `u32::MAX`. The engine skips matching for these.
    pub(crate) simple: Vec<u32>,
    /// Whether any production rewrites the symbol.
    pub(crate) rewritten: Vec<bool>,
    /// For each symbol whose productions are a weighted draw and nothing else (each
    /// weighted, no context, no condition, no block, one arity): their weights' sum, added
    /// in order as a draw among matches adds them. A module of it takes a draw without
    /// matching any of them.
    pub(crate) draw_total: Vec<Option<f64>>,
    /// For each symbol: whether a module of it whose left context is a module of the same
    /// symbol never fires (every production names a nearest left context of another
    /// symbol). Runs of such modules, with ignored modules and whole branches between them,
    /// are copied in bulk after the first (the signal walking down a long word of ABOP 1.8).
    pub(crate) stays_after_itself: Vec<bool>,
    /// For each symbol: whether a module of it whose nearest right context is a module of
    /// the same symbol never fires (every production names a right context whose first
    /// module is of another symbol, and no string predecessor). In a run of such modules
    /// with only ignored modules nothing rewrites between them, every one but the last
    /// stays, and is copied in bulk (a signal waiting at the far end of a long word).
    pub(crate) stays_before_itself: Vec<bool>,
    /// When every symbol the table rewrites has one production that always fires or a
    /// weighted draw among productions and nothing else, all of no parameters, with
    /// successors of parameterless modules known in advance and no cut (ABOP's D0L and
    /// stochastic 0L systems): how each symbol is rewritten. A word without parameters is
    /// then rewritten by a lookup (and a draw) per module ([`super::derive`]'s plain pass),
    /// and no production pays for matching, binding or evaluating what others need.
    pub(crate) plain: Option<Vec<PlainRule>>,
    pub(crate) const_symbols: Vec<SymbolId>,
    /// Parameter end offsets of the pre-evaluated modules, relative to their successor.
    pub(crate) const_ends: Vec<u32>,
    pub(crate) const_params: Vec<f64>,
}

impl Compiled {
    /// Compiles a block onto `blocks`: its span there.
    pub(crate) fn block(&mut self, statements: &[Statement]) -> Span {
        let start = self.blocks.len() as u32;
        block::compile(statements, &mut self.ops, &mut self.blocks);
        (start, self.blocks.len() as u32)
    }

    pub(crate) fn new(
        alphabet: &Alphabet,
        ignore: &[SymbolId],
        productions: &[Production],
    ) -> Compiled {
        let mut c = Compiled::default();
        for p in productions {
            let condition = p.condition.as_ref().map(|e| {
                let start = c.ops.len() as u32;
                e.compile(&mut c.ops);
                (start, c.ops.len() as u32)
            });
            let successor = c.items_of(&p.successor);
            let (max_modules, max_params) = bound(&p.successor);
            let pat = |v: &[Pattern]| {
                v.iter()
                    .map(|q| CPattern {
                        symbol: q.symbol,
                        arity: q.params.len() as u8,
                    })
                    .collect::<Vec<_>>()
            };
            c.has_context |= !p.left.is_empty() || !p.right.is_empty();
            // A production with statements must run them each time it fires.
            let constant = if p.pre.is_empty() && p.post.is_empty() {
                c.pre_evaluate(successor)
            } else {
                None
            };
            let pre = c.block(&p.pre);
            let post = c.block(&p.post);
            c.productions.push(CProduction {
                left: pat(&p.left),
                arity: p.predecessor.params.len() as u8,
                rest: pat(&p.predecessor_rest),
                right: pat(&p.right),
                condition,
                pre,
                post,
                successor,
                weight: p.weight,
                max_modules,
                max_params,
                constant,
            });
        }
        let n = alphabet.len();
        let mut counts = vec![0u32; n + 1];
        for p in productions {
            counts[p.predecessor.symbol.index() + 1] += 1;
        }
        for i in 0..n {
            counts[i + 1] += counts[i];
        }
        c.by_symbol = counts.clone();
        c.order = vec![0; productions.len()];
        let mut fill = counts;
        for (i, p) in productions.iter().enumerate() {
            let s = p.predecessor.symbol.index();
            c.order[fill[s] as usize] = i as u32;
            fill[s] += 1;
        }
        c.simple = (0..n)
            .map(|s| {
                let (lo, hi) = (c.by_symbol[s] as usize, c.by_symbol[s + 1] as usize);
                let first = c.order.get(lo).copied();
                match first {
                    Some(p) if hi - lo == 1 => {
                        let q = &c.productions[p as usize];
                        let simple = q.left.is_empty()
                            && q.rest.is_empty()
                            && q.right.is_empty()
                            && q.condition.is_none()
                            && q.weight.is_none()
                            && q.pre.0 == q.pre.1
                            && q.post.0 == q.post.1;
                        if simple { p } else { u32::MAX }
                    }
                    _ => u32::MAX,
                }
            })
            .collect();
        c.rewritten = (0..n)
            .map(|s| c.by_symbol[s] < c.by_symbol[s + 1])
            .collect();
        c.ignored = vec![false; n];
        for s in ignore {
            c.ignored[s.index()] = true;
        }
        c.draw_total = (0..n)
            .map(|s| {
                c.is_drawn(s).then(|| {
                    c.of_symbol(s)
                        .fold(0.0, |total, q| total + q.weight.unwrap_or(0.0))
                })
            })
            .collect();
        c.plain = c.plain_rules();
        c.stays_before_itself = (0..n)
            .map(|s| {
                c.rewritten[s]
                    && !c.ignored[s]
                    && c.of_symbol(s).all(|q| {
                        q.rest.is_empty()
                            && q.right.first().is_some_and(|r| {
                                r.symbol.index() != s && r.symbol != PUSH && r.symbol != POP
                            })
                    })
            })
            .collect();
        c.stays_after_itself = (0..n)
            .map(|s| {
                c.rewritten[s]
                    && !c.ignored[s]
                    && c.of_symbol(s).all(|q| {
                        q.left
                            .last()
                            .is_some_and(|l| l.symbol.index() != s && l.symbol != PUSH)
                    })
            })
            .collect();
        c
    }

    /// How a plain table (see [`Compiled::plain`]) rewrites each symbol, or `None` when a
    /// symbol's productions need more than a lookup or a draw.
    fn plain_rules(&self) -> Option<Vec<PlainRule>> {
        (0..self.rewritten.len())
            .map(|s| {
                if !self.rewritten[s] {
                    return Some(PlainRule::Copied);
                }
                if let Some(total) = self.draw_total[s] {
                    let lo = self.by_symbol[s] as usize;
                    let choices = self
                        .of_symbol(s)
                        .enumerate()
                        .map(|(k, q)| {
                            let p = self.order[lo + k];
                            Some((p, q.weight.unwrap_or(0.0), self.plain_successor(q)?))
                        })
                        .collect::<Option<Vec<_>>>()?;
                    return Some(PlainRule::Drawn { total, choices });
                }
                let p = self.simple[s];
                let (a, b) = self.plain_successor(self.productions.get(p as usize)?)?;
                Some(PlainRule::Fixed(p, a, b))
            })
            .collect()
    }

    /// The span in `const_symbols` of `q`'s successor when a plain table can emit it: no
    /// parameters in or out, a module of one symbol, no block, no cut.
    fn plain_successor(&self, q: &CProduction) -> Option<(u32, u32)> {
        match q.constant {
            Some(((s0, s1), (p0, p1)))
                if q.arity == 0
                    && q.rest.is_empty()
                    && q.post.0 == q.post.1
                    && p0 == p1
                    && !self.const_symbols[s0 as usize..s1 as usize].contains(&CUT) =>
            {
                Some((s0, s1))
            }
            _ => None,
        }
    }

    /// The productions of symbol `s`, in the order they are tried.
    pub(crate) fn of_symbol(&self, s: usize) -> impl Iterator<Item = &CProduction> {
        let (lo, hi) = (self.by_symbol[s] as usize, self.by_symbol[s + 1] as usize);
        self.order[lo..hi]
            .iter()
            .map(|&p| &self.productions[p as usize])
    }

    /// Whether symbol `s` is rewritten by a weighted draw alone (see
    /// [`Compiled::draw_total`]).
    fn is_drawn(&self, s: usize) -> bool {
        let mut all = self.of_symbol(s).peekable();
        let Some(arity) = all.peek().map(|q| q.arity) else {
            return false;
        };
        all.all(|q| {
            q.weight.is_some()
                && q.arity == arity
                && q.left.is_empty()
                && q.rest.is_empty()
                && q.right.is_empty()
                && q.condition.is_none()
                && q.pre.0 == q.pre.1
        })
    }

    /// Evaluates a successor once if nothing in it varies, so emitting it is a copy.
    fn pre_evaluate(&mut self, span: Span) -> Option<(Span, Span)> {
        let items = &self.items[span.0 as usize..span.1 as usize];
        let mut values = Vec::new();
        let mut symbols = Vec::new();
        let mut ends = Vec::new();
        for item in items {
            let CItem::Module { symbol, args } = item else {
                return None;
            };
            for a in args.0..args.1 {
                let (lo, hi) = self.args[a as usize];
                match self.ops[lo as usize..hi as usize] {
                    [Op::Num(v)] => values.push(v),
                    _ => return None,
                }
            }
            symbols.push(*symbol);
            ends.push(values.len() as u32);
        }
        let s0 = self.const_symbols.len() as u32;
        let p0 = self.const_params.len() as u32;
        self.const_symbols.extend(symbols);
        self.const_ends.extend(ends);
        self.const_params.extend(values);
        Some((
            (s0, self.const_symbols.len() as u32),
            (p0, self.const_params.len() as u32),
        ))
    }

    /// Lays out `items` contiguously (children after their parent list) and returns their span.
    fn items_of(&mut self, items: &[SuccessorItem]) -> Span {
        let start = self.items.len();
        // Reserve the slots first so the list is contiguous; nested lists go after it.
        for _ in items {
            self.items.push(CItem::Module {
                symbol: SymbolId(0),
                args: (0, 0),
            });
        }
        for (k, item) in items.iter().enumerate() {
            let compiled = match item {
                SuccessorItem::Module(m) => {
                    let a0 = self.args.len() as u32;
                    for e in &m.args {
                        let s = self.ops.len() as u32;
                        e.compile(&mut self.ops);
                        self.args.push((s, self.ops.len() as u32));
                    }
                    CItem::Module {
                        symbol: m.symbol,
                        args: (a0, self.args.len() as u32),
                    }
                }
                SuccessorItem::Choice {
                    probability,
                    then,
                    otherwise,
                } => {
                    let s = self.ops.len() as u32;
                    probability.compile(&mut self.ops);
                    let probability = (s, self.ops.len() as u32);
                    let then = self.items_of(then);
                    let otherwise = self.items_of(otherwise);
                    CItem::Choice {
                        probability,
                        then,
                        otherwise,
                    }
                }
            };
            self.items[start + k] = compiled;
        }
        (start as u32, (start + items.len()) as u32)
    }
}

/// Most modules and parameters one application of `items` can emit.
fn bound(items: &[SuccessorItem]) -> (u32, u32) {
    items.iter().fold((0u32, 0u32), |(m, p), item| match item {
        SuccessorItem::Module(t) => (m.saturating_add(1), p.saturating_add(t.args.len() as u32)),
        SuccessorItem::Choice {
            then, otherwise, ..
        } => {
            let (a, b) = (bound(then), bound(otherwise));
            (
                m.saturating_add(a.0.max(b.0)),
                p.saturating_add(a.1.max(b.1)),
            )
        }
    })
}
