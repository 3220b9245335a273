//! Writing the next word: a production's successor evaluated, runs of unchanged modules
//! copied, and cut symbols applied.

use super::Deriver;
use crate::engine::compile::CItem;
use crate::engine::eval::Span;
use crate::engine::eval::eval;
use crate::error::DeriveError;
use crate::model::alphabet::{CUT, POP, PUSH};
use crate::model::word::{Word, extend_short};

impl Deriver<'_> {
    /// Emits the items of `span`; returns whether a cut symbol was produced.
    pub(super) fn emit(
        &mut self,
        span: Span,
        out: &mut Word,
        generation: f64,
        step: u32,
    ) -> Result<bool, DeriveError> {
        let c = self.compiled();
        let mut cut = false;
        for k in span.0..span.1 {
            match c.items[k as usize] {
                CItem::Module { symbol, args } => {
                    for a in args.0..args.1 {
                        let (lo, hi) = c.args[a as usize];
                        let v = eval(
                            &c.ops[lo as usize..hi as usize],
                            (&self.vars, &self.globals, &self.grammar.files),
                            generation,
                            &mut self.rng,
                            &mut self.stack,
                        );
                        if !v.is_finite() {
                            return Err(DeriveError::NonFiniteParameter {
                                generation: step,
                                symbol: self.grammar.alphabet.name(symbol).to_string(),
                                index: (a - args.0) as usize,
                                value: v,
                            });
                        }
                        out.params.push(v);
                    }
                    out.symbols.push(symbol);
                    out.offsets.push(out.params.len() as u32);
                    cut |= symbol == CUT;
                }
                CItem::Choice {
                    probability,
                    then,
                    otherwise,
                } => {
                    let (lo, hi) = probability;
                    let p = eval(
                        &c.ops[lo as usize..hi as usize],
                        (&self.vars, &self.globals, &self.grammar.files),
                        generation,
                        &mut self.rng,
                        &mut self.stack,
                    );
                    let branch = if self.rng.unit() < p { then } else { otherwise };
                    cut |= self.emit(branch, out, generation, step)?;
                }
            }
        }
        Ok(cut)
    }
}

/// Appends modules `i..j` of `cur` to `out`; returns whether a cut symbol was among them.
pub(super) fn copy_run(cur: &Word, i: usize, j: usize, out: &mut Word) -> bool {
    if j == i + 1 {
        out.push(cur.symbols[i], cur.params(i));
        return cur.symbols[i] == CUT;
    }
    let syms = &cur.symbols[i..j];
    extend_short(&mut out.symbols, syms);
    let (p0, p1) = (cur.offsets[i], cur.offsets[j]);
    let shift = out.params.len() as i64 - i64::from(p0);
    extend_short(&mut out.params, &cur.params[p0 as usize..p1 as usize]);
    out.offsets.extend(
        cur.offsets[i + 1..=j]
            .iter()
            .map(|&o| (i64::from(o) + shift) as u32),
    );
    syms.contains(&CUT)
}

/// Removes every cut symbol `%` and the rest of the branch it stands in (ABOP's cut).
pub(super) fn apply_cuts(w: &mut Word) {
    let mut read = Word::empty(w.alphabet.clone());
    std::mem::swap(&mut read, w);
    let mut i = 0;
    while i < read.len() {
        let s = read.symbols[i];
        if s == CUT {
            let mut depth = 0usize;
            i += 1;
            while i < read.len() {
                match read.symbols[i] {
                    PUSH => depth += 1,
                    POP if depth == 0 => break,
                    POP => depth -= 1,
                    _ => {}
                }
                i += 1;
            }
            continue;
        }
        w.push(s, read.params(i));
        i += 1;
    }
}
