//! The rewriting engine: one derivation step streams the current word into the next.

use crate::engine::block::{self, MAX_BLOCK_STATEMENTS};
use crate::engine::compile::{CProduction, Compiled};
use crate::engine::eval::Span;
use crate::engine::lsystem::LSystem;
use crate::engine::random::Random;
use crate::error::DeriveError;
use crate::model::alphabet::{CUT, SymbolId};
use crate::model::word::Word;

mod choose;
mod context;
mod emit;
mod entry;
mod limits;
mod plain;

use emit::{apply_cuts, copy_run};
pub use limits::Limits;

/// Which of a grammar's production tables a rewrite uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Table {
    Main,
    Decomposition,
    Homomorphism,
}

/// Rewrites words generation by generation, reusing its buffers; [`LSystem::derive`] wraps it.
#[derive(Debug)]
pub struct Deriver<'g> {
    grammar: &'g LSystem,
    rng: Random,
    limits: Limits,
    vars: Vec<f64>,
    stack: Vec<f64>,
    matched: Vec<u32>,
    candidates: Vec<(u32, f64)>,
    /// For `]`: index of its `[`; for `[`: index of its `]`. `u32::MAX` when unmatched.
    partner: Vec<u32>,
    /// The module a one-module left context of module `.0` names (`.1`, `u32::MAX` for
    /// none), remembered while the productions of `.0` are tried; `.0` is `u32::MAX` when
    /// nothing is remembered.
    near_left: (u32, u32),
    /// The same for a one-module right context.
    near_right: (u32, u32),
    /// The values of the grammar's block variables (cpfg's global variables).
    globals: Vec<f64>,
    /// The productions rewrites use.
    table: Table,
    /// Productions applied by the last rewrite.
    fired: usize,
    /// The production whose block before the condition set the parameters now bound, when
    /// `select` chose it.
    bound_for: Option<u32>,
    /// Block statements run so far in this derivation.
    statements: u64,
    /// The production (in the table in use) applied last.
    last_fired: Option<u32>,
    /// The sub-L-system whose productions rewrite the module at hand (main: `None`).
    sub: Option<usize>,
}

/// The block variables as a derivation starts: zero, but for the arrays' values.
fn initial_globals(grammar: &LSystem) -> Vec<f64> {
    let mut globals = vec![0.0; grammar.globals.len()];
    for array in &grammar.blocks.arrays {
        let from = array.slot as usize;
        if let Some(slots) = globals.get_mut(from..from + array.values.len()) {
            slots.copy_from_slice(&array.values);
        }
    }
    globals
}

impl<'g> Deriver<'g> {
    /// A deriver whose random stream starts from `seed`.
    pub fn new(grammar: &'g LSystem, seed: u64, limits: Limits) -> Self {
        Deriver {
            grammar,
            rng: Random::new(seed),
            limits,
            vars: Vec::new(),
            stack: Vec::new(),
            matched: Vec::new(),
            candidates: Vec::new(),
            partner: Vec::new(),
            near_left: (u32::MAX, u32::MAX),
            near_right: (u32::MAX, u32::MAX),
            globals: initial_globals(grammar),
            table: Table::Main,
            fired: 0,
            bound_for: None,
            statements: 0,
            last_fired: None,
            sub: None,
        }
    }

    /// Production `p` of `table` counted across the grammar's sections.
    fn global_index(&self, table: Table, p: u32) -> usize {
        let g = self.grammar;
        p as usize
            + match table {
                Table::Main => 0,
                Table::Decomposition => g.productions.len(),
                Table::Homomorphism => g.productions.len() + g.decomposition.productions.len(),
            }
    }

    /// The compiled productions of the table in use.
    fn compiled(&self) -> &'g Compiled {
        let grammar: &'g LSystem = self.grammar;
        match self.table {
            Table::Main => match self.sub {
                Some(k) => &grammar.compiled_subsystems[k],
                None => &grammar.compiled,
            },
            Table::Decomposition => &grammar.compiled_decomposition,
            Table::Homomorphism => &grammar.compiled_homomorphism,
        }
    }

    /// `word` (of generation `generation`) decomposed: the grammar's decomposition applied
    /// until no production fires. The word itself when there is no decomposition.
    pub fn decompose(&mut self, word: Word, generation: u32) -> Result<Word, DeriveError> {
        self.apply_rule_set(word, Table::Decomposition, generation)
    }

    fn apply_rule_set(
        &mut self,
        word: Word,
        table: Table,
        generation: u32,
    ) -> Result<Word, DeriveError> {
        let grammar: &'g LSystem = self.grammar;
        let (set, section) = match table {
            Table::Decomposition => (&grammar.decomposition, "decomposition"),
            Table::Homomorphism => (&grammar.homomorphism, "homomorphism"),
            Table::Main => return Ok(word),
        };
        if set.is_empty() {
            return Ok(word);
        }
        let saved = self.table;
        self.table = table;
        let mut current = word;
        let mut next = Word::empty(current.alphabet.clone());
        let mut passes = 0u32;
        let result = loop {
            // A pass rewrites with `#` still the generation being decomposed.
            if let Err(e) = self.rewrite_pass(&current, &mut next, generation) {
                break Err(e);
            }
            if self.fired == 0 {
                break Ok(current);
            }
            if passes == set.max_depth && set.stops_at_depth {
                // The pass just made went beyond the depth: its word is not taken.
                break Ok(current);
            }
            if passes == set.max_depth {
                break Err(DeriveError::TooDeep {
                    section,
                    depth: set.max_depth,
                    generation,
                    at: self
                        .last_fired
                        .and_then(|p| grammar.production_location(self.global_index(table, p))),
                });
            }
            passes += 1;
            std::mem::swap(&mut current, &mut next);
        };
        self.table = saved;
        result
    }

    /// Derives `generations` more generations from `word`, which is taken to be generation
    /// `generation` (so `#` in the first rewrite is `generation + 1`).
    pub fn derive_from(
        &mut self,
        word: Word,
        generation: u32,
        generations: u32,
    ) -> Result<Word, DeriveError> {
        if generations == 0 {
            return Ok(word);
        }
        self.derive_from_ref(&word, generation, generations)
    }

    /// As [`Deriver::derive_from`], reading `word` where it is: the first step rewrites it
    /// into a new word, so it is copied only when no step is made.
    pub(crate) fn derive_from_ref(
        &mut self,
        word: &Word,
        generation: u32,
        generations: u32,
    ) -> Result<Word, DeriveError> {
        if generations > self.limits.max_generations {
            return Err(DeriveError::TooManyGenerations {
                requested: generations,
                limit: self.limits.max_generations,
            });
        }
        if generations == 0 || self.rng.stop {
            return Ok(word.clone());
        }
        let mut current = Word::empty(word.alphabet.clone());
        let mut next = Word::empty(word.alphabet.clone());
        let decomposed = !self.grammar.decomposition.is_empty();
        for k in 1..=generations {
            if self.rng.stop {
                // cpfg's stop(n): the step that called it was the last.
                break;
            }
            let produced = generation.saturating_add(k);
            self.run_derivation_block(1, produced)?;
            let from = if k == 1 { word } else { &current };
            self.rewrite(from, &mut next, produced)?;
            std::mem::swap(&mut current, &mut next);
            if decomposed {
                current = self.decompose(current, produced)?;
            }
            self.run_derivation_block(2, produced)?;
        }
        Ok(current)
    }

    /// One parallel rewrite of `cur` into `out` (cleared first), producing generation
    /// `generation` (the value of `#`).
    pub fn rewrite(
        &mut self,
        cur: &Word,
        out: &mut Word,
        generation: u32,
    ) -> Result<(), DeriveError> {
        let saved = self.table;
        self.table = Table::Main;
        let result = self.rewrite_pass(cur, out, generation);
        self.table = saved;
        result
    }

    /// One parallel rewrite with the table in use.
    fn rewrite_pass(
        &mut self,
        cur: &Word,
        out: &mut Word,
        generation: u32,
    ) -> Result<(), DeriveError> {
        self.fired = 0;
        out.clear();
        out.alphabet = cur.alphabet.clone();
        // Most grammars grow: reserving the current size saves the first reallocations.
        out.symbols.reserve(cur.len());
        out.offsets.reserve(cur.len());
        out.params.reserve(cur.params.len());
        let c = self.compiled();
        // With sub-L-systems each module is rewritten by the system it stands in.
        let markers = self
            .grammar
            .sub_markers
            .filter(|_| self.table == Table::Main);
        if let Some(rules) = &c.plain
            && markers.is_none()
            && cur.params.is_empty()
        {
            return self.plain_pass(cur, out, (c, rules), generation);
        }
        if c.has_context {
            self.link_brackets(cur);
        }
        let gen_f = f64::from(generation);
        let mut cut_seen = false;
        let n = cur.len();
        let mut i = 0;
        let mut enclosing: Vec<Option<usize>> = Vec::new();
        self.sub = None;
        while i < n {
            if let Some(markers) = markers
                && i > 0
            {
                // A marker belongs to the system around it: the switch comes after it.
                self.enter_or_leave(cur, i - 1, markers, &mut enclosing);
            }
            let c = if markers.is_some() {
                self.compiled()
            } else {
                c
            };
            let sym = cur.symbols[i];
            let s = sym.index();
            if !c.rewritten[s] {
                // A run of modules no production rewrites is copied in bulk.
                let mut j = i + 1;
                while markers.is_none() && j < n && !c.rewritten[cur.symbols[j].index()] {
                    j += 1;
                }
                cut_seen |= copy_run(cur, i, j, out);
                i = j;
                continue;
            }
            if c.stays_before_itself[s] && markers.is_none() {
                // Modules of this symbol followed, past ignored modules only, by another of
                // it have no right context any production names: copied up to the last.
                let last = self.run_before(cur, i, c);
                if last > i {
                    cut_seen |= copy_run(cur, i, last, out);
                    i = last;
                    continue;
                }
            }
            let lo = c.by_symbol[s] as usize;
            let hi = c.by_symbol[s + 1] as usize;
            let mut consumed = 1;
            let chosen = match c.simple[s] {
                p if p != u32::MAX
                    && c.productions[p as usize].arity as usize == cur.params(i).len() =>
                {
                    // A simple production has no context: nothing was matched, nothing needs to be.
                    Some((p, true))
                }
                _ if c.draw_total[s].is_some() => self.draw(cur, i, &c.order[lo..hi]),
                _ => self.select(cur, i, &c.order[lo..hi], gen_f)?,
            };
            match chosen {
                Some((p, matched)) => {
                    self.fired += 1;
                    self.last_fired = Some(p);
                    let prod = &c.productions[p as usize];
                    self.check_room(out, prod, generation)?;
                    // A string predecessor rewrites all its modules at once.
                    consumed += prod.rest.len();
                    if let Some(((s0, s1), (p0, p1))) = prod.constant {
                        let syms = &c.const_symbols[s0 as usize..s1 as usize];
                        out.symbols.extend_from_slice(syms);
                        let base = out.params.len() as u32;
                        out.params
                            .extend_from_slice(&c.const_params[p0 as usize..p1 as usize]);
                        out.offsets.extend(
                            c.const_ends[s0 as usize..s1 as usize]
                                .iter()
                                .map(|&e| base + e),
                        );
                        cut_seen |= syms.contains(&CUT);
                    } else {
                        // A block before the condition may have changed the parameters:
                        // they are bound already for the production it chose.
                        if self.bound_for != Some(p) {
                            self.bind(cur, i, prod, matched);
                        }
                        self.run_block(c, (prod.post, Some(p)), gen_f)?;
                        cut_seen |= self.emit(prod.successor, out, gen_f, generation)?;
                    }
                }
                None => {
                    out.push(sym, cur.params(i));
                    cut_seen |= sym == CUT;
                }
            }
            i += consumed;
            if consumed == 1 && c.stays_after_itself[s] && markers.is_none() {
                // The modules of this symbol that follow, each with one of them as its left
                // context, stay as they are: copied with what stands between them.
                let j = self.run_after(cur, i - 1, c);
                if j > i {
                    cut_seen |= copy_run(cur, i, j, out);
                    i = j;
                }
            }
        }
        self.sub = None;
        if out.len() > self.limits.max_modules {
            return Err(DeriveError::TooManyModules {
                generation,
                limit: self.limits.max_modules,
            });
        }
        if out.params.len() > self.limits.max_params {
            return Err(DeriveError::TooManyParams {
                generation,
                limit: self.limits.max_params,
            });
        }
        if cut_seen {
            apply_cuts(out);
        }
        Ok(())
    }

    fn check_room(
        &self,
        out: &Word,
        prod: &CProduction,
        generation: u32,
    ) -> Result<(), DeriveError> {
        if out.len() + prod.max_modules as usize > self.limits.max_modules {
            return Err(DeriveError::TooManyModules {
                generation,
                limit: self.limits.max_modules,
            });
        }
        if out.params.len() + prod.max_params as usize > self.limits.max_params {
            return Err(DeriveError::TooManyParams {
                generation,
                limit: self.limits.max_params,
            });
        }
        Ok(())
    }

    /// Runs a block of `compiled` (span into its instructions) on the bound parameters and
    /// the block variables.
    fn run_block(
        &mut self,
        compiled: &'g Compiled,
        (span, production): (Span, Option<u32>),
        generation: f64,
    ) -> Result<(), DeriveError> {
        if span.0 == span.1 {
            return Ok(());
        }
        let left = self.limits.max_statements.saturating_sub(self.statements);
        let run = block::run(
            &compiled.blocks[span.0 as usize..span.1 as usize],
            &compiled.ops,
            (&mut self.vars, &mut self.globals, &self.grammar.files),
            generation,
            &mut self.rng,
            &mut self.stack,
            left.min(MAX_BLOCK_STATEMENTS),
        );
        match run {
            Ok(executed) => {
                self.statements += executed;
                Ok(())
            }
            Err(_) if left < MAX_BLOCK_STATEMENTS => Err(DeriveError::TooManyStatements {
                generation: generation as u32,
                limit: self.limits.max_statements,
            }),
            Err(_) => Err(DeriveError::EndlessBlock {
                generation: generation as u32,
                limit: MAX_BLOCK_STATEMENTS,
                at: production.and_then(|p| {
                    self.grammar
                        .production_location(self.global_index(self.table, p))
                }),
            }),
        }
    }

    /// After module `k`: `?(id, ...)` hands what follows to sub-L-system `id`, `$` gives it
    /// back to the system around.
    fn enter_or_leave(
        &mut self,
        cur: &Word,
        k: usize,
        (start, end): (SymbolId, SymbolId),
        enclosing: &mut Vec<Option<usize>>,
    ) {
        let symbol = cur.symbols[k];
        if symbol == start
            && let Some(&id) = cur.params(k).first()
        {
            enclosing.push(self.sub);
            self.sub = self
                .grammar
                .subsystems
                .iter()
                .position(|(s, _)| f64::from(*s) == id);
        } else if symbol == end {
            self.sub = enclosing.pop().flatten();
        }
    }

    /// Runs one of the grammar's derivation blocks: 0 start, 1 start each, 2 end each, 3 end.
    fn run_derivation_block(&mut self, which: usize, generation: u32) -> Result<(), DeriveError> {
        let grammar: &'g LSystem = self.grammar;
        self.vars.clear();
        self.run_block(
            &grammar.compiled,
            (grammar.block_spans[which], None),
            f64::from(generation),
        )
    }
}
