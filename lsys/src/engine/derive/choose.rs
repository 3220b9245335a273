//! Choosing the production that rewrites a module: the first whose contexts and condition
//! hold, or a weighted draw among those that match.

use super::Deriver;
use crate::engine::eval::eval;
use crate::error::DeriveError;
use crate::model::word::Word;

impl Deriver<'_> {
    /// Picks the production to apply to module `i`, if any: the first match when it is
    /// deterministic, else a weighted draw among all matching weighted productions. The flag
    /// says whether `matched` still holds the chosen production's context match.
    pub(super) fn select(
        &mut self,
        cur: &Word,
        i: usize,
        order: &[u32],
        generation: f64,
    ) -> Result<Option<(u32, bool)>, DeriveError> {
        let c = self.compiled();
        self.candidates.clear();
        self.bound_for = None;
        let mut total = 0.0;
        for &p in order {
            let prod = &c.productions[p as usize];
            if !self.matches(cur, i, prod) {
                continue;
            }
            let pre = prod.pre.0 != prod.pre.1;
            if pre {
                self.bind(cur, i, prod, true);
                self.run_block(c, (prod.pre, Some(p)), generation)?;
            }
            if let Some((a, b)) = prod.condition {
                if !pre {
                    self.bind(cur, i, prod, true);
                }
                let v = eval(
                    &c.ops[a as usize..b as usize],
                    (&self.vars, &self.globals, &self.grammar.files),
                    generation,
                    &mut self.rng,
                    &mut self.stack,
                );
                if v == 0.0 || v.is_nan() {
                    continue;
                }
            }
            match prod.weight {
                None if self.candidates.is_empty() => {
                    if pre {
                        self.bound_for = Some(p);
                    }
                    return Ok(Some((p, true)));
                }
                None => {}
                Some(w) => {
                    total += w;
                    self.candidates.push((p, w));
                }
            }
        }
        if self.candidates.is_empty() || total <= 0.0 {
            return Ok(None);
        }
        // Later candidates were matched after the drawn one: its match must be redone.
        let u = self.rng.unit() * total;
        Ok(pick(u, self.candidates.iter().copied()).map(|p| (p, false)))
    }

    /// Picks the production of a symbol rewritten by a weighted draw alone, whose weights
    /// add up to `total` ([`Compiled::draw_total`]): the draw [`Deriver::select`] makes,
    /// without matching.
    pub(super) fn draw(&mut self, cur: &Word, i: usize, order: &[u32]) -> Option<(u32, bool)> {
        let c = self.compiled();
        self.bound_for = None;
        let total = c.draw_total[cur.symbols[i].index()]?;
        if total <= 0.0 || c.productions[order[0] as usize].arity as usize != cur.params(i).len() {
            return None;
        }
        let u = self.rng.unit() * total;
        let weighted = order
            .iter()
            .map(|&p| (p, c.productions[p as usize].weight.unwrap_or(0.0)));
        pick(u, weighted).map(|p| (p, false))
    }
}

/// The production a draw `u` in `[0, total)` lands on among weighted `choices`, in order;
/// past them all (rounding), the last with a weight.
pub(super) fn pick(mut u: f64, choices: impl Iterator<Item = (u32, f64)>) -> Option<u32> {
    let mut last = None;
    for (p, w) in choices {
        if u < w {
            return Some(p);
        }
        u -= w;
        if w > 0.0 {
            last = Some(p);
        }
    }
    last
}
