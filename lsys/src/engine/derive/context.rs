//! Context matching (ABOP 1.8): whether a production's left and right contexts stand
//! around a module, skipping branches and ignored symbols as the notation says.

use super::Deriver;
use crate::engine::compile::{CPattern, CProduction, Compiled};
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
        if let [p] = pattern {
            // One module of context, as most productions have: the walk from module `i` is
            // the same for every production tried on it, so it is made once.
            if self.near_left.0 != i as u32 {
                self.near_left = (i as u32, self.walk_left(cur, i));
            }
            return self.names_module(cur, self.near_left.1, p);
        }
        let start = self.matched.len();
        let mut j = i;
        for p in pattern.iter().rev() {
            let near = self.walk_left(cur, j);
            if !self.names_module(cur, near, p) {
                return false;
            }
            j = near as usize;
        }
        self.matched[start..].reverse();
        true
    }

    /// Whether module `j` (`u32::MAX` for none) is the one pattern `p` names; it is noted as
    /// matched when it is.
    fn names_module(&mut self, cur: &Word, j: u32, p: &CPattern) -> bool {
        let found = j != u32::MAX
            && cur.symbols[j as usize] == p.symbol
            && Self::arity_of(cur, j as usize) == p.arity;
        if found {
            self.matched.push(j);
        }
        found
    }

    /// The nearest module left of `i` a left context can name (`u32::MAX` for none): ignored
    /// modules and `[` are stepped over, a branch `[...]` is skipped from its `]`. In a ring
    /// L-system the start of the word joins its end: the walk goes on from the last module,
    /// once round at most.
    fn walk_left(&self, cur: &Word, i: usize) -> u32 {
        let ignored = &self.compiled().ignored;
        let mut j = i;
        let mut wrapped = false;
        loop {
            if j == 0 {
                if !self.grammar.ring || wrapped {
                    return u32::MAX;
                }
                wrapped = true;
                j = cur.len();
                continue;
            }
            j -= 1;
            if wrapped && j < i {
                return u32::MAX;
            }
            let s = cur.symbols[j];
            if s == POP {
                match self.partner[j] {
                    u32::MAX => return u32::MAX,
                    open => j = open as usize,
                }
            } else if s != PUSH && !ignored[s.index()] {
                return j as u32;
            }
        }
    }

    /// The nearest module from `from` on that a right context can name (`u32::MAX` for
    /// none): ignored modules and whole branches are stepped over; the end of the current
    /// branch ends the walk. In a ring L-system the end of the word joins its start: the
    /// walk goes on from the first module, once round at most.
    fn walk_right(&self, cur: &Word, from: usize) -> u32 {
        let ignored = &self.compiled().ignored;
        let mut j = from;
        let mut wrapped = false;
        loop {
            if j >= cur.len() {
                if !self.grammar.ring || wrapped {
                    return u32::MAX;
                }
                wrapped = true;
                j = 0;
                continue;
            }
            if wrapped && j >= from {
                return u32::MAX;
            }
            let s = cur.symbols[j];
            if s == PUSH {
                match self.partner[j] {
                    u32::MAX => return u32::MAX,
                    close => j = close as usize + 1,
                }
            } else if s == POP {
                return u32::MAX;
            } else if ignored[s.index()] {
                j += 1;
            } else {
                return j as u32;
            }
        }
    }

    /// ABOP 1.8: walking right, branches not named by the pattern are skipped; `[` in the
    /// pattern enters a branch and `]` skips to the end of the current one.
    fn match_right(&mut self, cur: &Word, i: usize, pattern: &[CPattern]) -> bool {
        if let [p] = pattern
            && p.symbol != PUSH
            && p.symbol != POP
        {
            // As for the left: the walk from module `i` is made once for every production
            // tried on it.
            if self.near_right.0 != i as u32 {
                self.near_right = (i as u32, self.walk_right(cur, i + 1));
            }
            return self.names_module(cur, self.near_right.1, p);
        }
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
            let near = self.walk_right(cur, j);
            if !self.names_module(cur, near, p) {
                return false;
            }
            j = near as usize + 1;
        }
        true
    }

    pub(super) fn link_brackets(&mut self, cur: &Word) {
        // The walks remembered belong to the word before.
        self.near_left = (u32::MAX, u32::MAX);
        self.near_right = (u32::MAX, u32::MAX);
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

    /// For a module `i` whose symbol stays before itself
    /// ([`Compiled::stays_before_itself`]): the last module of that symbol in the run from
    /// `i` of modules of the symbol and ignored modules nothing rewrites. Every module of the
    /// symbol before it has the next one as its nearest right context, so stays.
    pub(super) fn run_before(&self, cur: &Word, i: usize, c: &Compiled) -> usize {
        let symbol = cur.symbols[i];
        let mut last = i;
        for (j, &t) in cur.symbols.iter().enumerate().skip(i + 1) {
            if t == symbol {
                last = j;
            } else if !c.ignored[t.index()] || c.rewritten[t.index()] {
                break;
            }
        }
        last
    }

    /// For a module `i` whose symbol stays after itself ([`Compiled::stays_after_itself`]):
    /// the end of the run after it whose every module of that symbol has its left context
    /// in the run, so stays. The run holds modules of the symbol, ignored symbols and
    /// brackets that nothing rewrites; a `]` only when its `[` is in the run, since a left
    /// context walks from `]` to its `[` and on.
    pub(super) fn run_after(&self, cur: &Word, i: usize, c: &Compiled) -> usize {
        let symbol = cur.symbols[i];
        let mut j = i + 1;
        while j < cur.len() {
            let t = cur.symbols[j];
            let stays = t == symbol
                || !c.rewritten[t.index()]
                    && (c.ignored[t.index()]
                        || t == PUSH
                        || t == POP && self.partner[j] != u32::MAX && self.partner[j] as usize > i);
            if !stays {
                break;
            }
            j += 1;
        }
        j
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use crate::LSystem;

    proptest! {
        /// Copying the modules that stay before themselves changes no word: a grammar with
        /// right contexts derives what it derives when every module is matched.
        #[test]
        fn modules_copied_before_themselves_are_the_ones_that_stay(
            word in "[ABC+]{1,12}(\\[[AB+]{1,3}\\])?[ABC+]{0,8}",
            right in prop::sample::select(vec!["A", "C", "C+A", "A B", "[A]"]),
            successor in "[ABC]{1,3}",
            other in "[AC+]{1,3}",
            generations in 1u32..5,
        ) {
            let text = format!(
                "#ignore: +\naxiom: {word}\nB > {right} -> {successor}\nC -> {other}\nA < C -> A"
            );
            let grammar = LSystem::parse(&text).unwrap();
            let mut matched = grammar.clone();
            matched.compiled.stays_before_itself.iter_mut().for_each(|s| *s = false);
            prop_assert_eq!(
                grammar.derive(generations, 0).unwrap(),
                matched.derive(generations, 0).unwrap(),
            );
        }
    }

    /// A signal at the far end of a long word: every B but the last stays, the last turns.
    #[test]
    fn a_signal_arrives_from_the_right() {
        let g = LSystem::parse("#ignore: +\naxiom: B+B+B+B+A\nB > A -> A").unwrap();
        assert!(g.compiled.stays_before_itself[g.alphabet().id_of("B").unwrap().index()]);
        assert_eq!(g.derive(1, 0).unwrap().to_string(), "B+B+B+A+A");
        assert_eq!(g.derive(3, 0).unwrap().to_string(), "B+A+A+A+A");
    }
}
