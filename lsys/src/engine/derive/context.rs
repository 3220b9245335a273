//! Context matching (ABOP 1.8): whether a production's left and right contexts stand
//! around a module, skipping branches and ignored symbols as the notation says.

use super::Deriver;
use crate::engine::compile::{CPattern, CProduction};
use crate::model::alphabet::{POP, PUSH};
use crate::model::word::Word;

impl Deriver<'_> {
    pub(super) fn matches(&mut self, cur: &Word, i: usize, prod: &CProduction) -> bool {
        let arity = (cur.offsets[i + 1] - cur.offsets[i]) as usize;
        if arity != prod.arity as usize {
            return false;
        }
        self.matched.clear();
        if !prod.left.is_empty() && !self.match_left(cur, i, &prod.left) {
            return false;
        }
        self.matched.push(i as u32);
        // A string predecessor's other modules follow the first, in order, nothing between;
        // the right context begins after the last of them.
        let mut last = i;
        for p in &prod.rest {
            last += 1;
            if last >= cur.len()
                || cur.symbols[last] != p.symbol
                || Self::arity_of(cur, last) != p.arity
            {
                return false;
            }
            self.matched.push(last as u32);
        }
        prod.right.is_empty() || self.match_right(cur, last, &prod.right)
    }

    /// Fills `vars` with the parameters of the modules `matches` found, in slot order.
    /// `matched` says whether the last `matches` call was for `prod`; if not, it is redone.
    pub(super) fn bind(&mut self, cur: &Word, i: usize, prod: &CProduction, matched: bool) {
        self.vars.clear();
        if prod.left.is_empty() && prod.rest.is_empty() && prod.right.is_empty() {
            self.vars.extend_from_slice(cur.params(i));
            return;
        }
        if !matched {
            self.matches(cur, i, prod);
        }
        for &m in &self.matched {
            self.vars.extend_from_slice(cur.params(m as usize));
        }
    }

    fn arity_of(cur: &Word, j: usize) -> u8 {
        (cur.offsets[j + 1] - cur.offsets[j]) as u8
    }

    /// ABOP 1.8: walking left, a whole branch `[...]` is skipped and a `[` leads to the parent.
    fn match_left(&mut self, cur: &Word, i: usize, pattern: &[CPattern]) -> bool {
        let ignored = &self.compiled().ignored;
        let mut j = i;
        let start = self.matched.len();
        for p in pattern.iter().rev() {
            loop {
                if j == 0 {
                    return false;
                }
                j -= 1;
                let s = cur.symbols[j];
                if s == POP {
                    match self.partner[j] {
                        u32::MAX => return false,
                        open => j = open as usize,
                    }
                    continue;
                }
                if s == PUSH || ignored[s.index()] {
                    continue;
                }
                if s == p.symbol && Self::arity_of(cur, j) == p.arity {
                    self.matched.push(j as u32);
                    break;
                }
                return false;
            }
        }
        self.matched[start..].reverse();
        true
    }

    /// ABOP 1.8: walking right, branches not named by the pattern are skipped; `[` in the
    /// pattern enters a branch and `]` skips to the end of the current one.
    fn match_right(&mut self, cur: &Word, i: usize, pattern: &[CPattern]) -> bool {
        let ignored = &self.compiled().ignored;
        let n = cur.len();
        let mut j = i + 1;
        for p in pattern {
            if p.symbol == PUSH {
                while j < n && ignored[cur.symbols[j].index()] {
                    j += 1;
                }
                if j < n && cur.symbols[j] == PUSH {
                    j += 1;
                    continue;
                }
                return false;
            }
            if p.symbol == POP {
                loop {
                    if j >= n {
                        return false;
                    }
                    match cur.symbols[j] {
                        PUSH => match self.partner[j] {
                            u32::MAX => return false,
                            close => j = close as usize + 1,
                        },
                        POP => {
                            j += 1;
                            break;
                        }
                        _ => j += 1,
                    }
                }
                continue;
            }
            loop {
                if j >= n {
                    return false;
                }
                let s = cur.symbols[j];
                if s == PUSH {
                    match self.partner[j] {
                        u32::MAX => return false,
                        close => j = close as usize + 1,
                    }
                    continue;
                }
                if s == POP {
                    return false;
                }
                if ignored[s.index()] {
                    j += 1;
                    continue;
                }
                if s == p.symbol && Self::arity_of(cur, j) == p.arity {
                    self.matched.push(j as u32);
                    j += 1;
                    break;
                }
                return false;
            }
        }
        true
    }

    pub(super) fn link_brackets(&mut self, cur: &Word) {
        self.partner.clear();
        self.partner.resize(cur.len(), u32::MAX);
        let mut open = Vec::new();
        for (j, &s) in cur.symbols.iter().enumerate() {
            if s == PUSH {
                open.push(j as u32);
            } else if s == POP
                && let Some(o) = open.pop()
            {
                self.partner[j] = o;
                self.partner[o as usize] = j as u32;
            }
        }
    }
}
