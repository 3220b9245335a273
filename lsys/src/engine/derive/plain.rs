//! The plain pass: a step of a D0L or stochastic 0L system (ABOP's plants, Lindenmayer's
//! algae, ABOP 1.27's stochastic plant) over a word without parameters, when every
//! production always fires or is drawn by weight and its successor is known in advance
//! ([`Compiled::plain`]). Each module is one lookup (and a draw): its successor's symbols
//! copied, or itself. Nothing is matched, bound or evaluated, and no parameter offsets are
//! kept but the zeros a parameterless word has. The draws are the general pass's, one per
//! drawn module in order, so both derive the same word from a seed.

use crate::engine::compile::{Compiled, PlainRule};
use crate::error::DeriveError;
use crate::model::alphabet::SymbolId;
use crate::model::word::Word;

use super::Deriver;
use super::choose::pick;

impl Deriver<'_> {
    /// Rewrites `cur` (without parameters) into `out` (cleared) with the plain table
    /// `rules` of `c`, producing generation `generation`. The module limit is checked as
    /// the general pass checks it: before each successor is written, and at the end.
    pub(super) fn plain_pass(
        &mut self,
        cur: &Word,
        out: &mut Word,
        (c, rules): (&Compiled, &[PlainRule]),
        generation: u32,
    ) -> Result<(), DeriveError> {
        let max = self.limits.max_modules;
        let too_many = || DeriveError::TooManyModules {
            generation,
            limit: max,
        };
        let mut fired = 0;
        let mut last = None;
        let emit = |out: &mut Word, (a, b): (u32, u32)| -> Result<(), DeriveError> {
            let successor: &[SymbolId] = &c.const_symbols[a as usize..b as usize];
            if out.symbols.len() + successor.len() > max {
                return Err(too_many());
            }
            for &s in successor {
                out.symbols.push(s);
            }
            Ok(())
        };
        for &symbol in &cur.symbols {
            match &rules[symbol.index()] {
                PlainRule::Copied => out.symbols.push(symbol),
                &PlainRule::Fixed(p, a, b) => {
                    emit(out, (a, b))?;
                    fired += 1;
                    last = Some(p);
                }
                PlainRule::Drawn { total, choices } => {
                    if *total <= 0.0 {
                        out.symbols.push(symbol);
                        continue;
                    }
                    let u = self.rng.unit() * total;
                    // Picked by position among the choices: the same draw lands on the same
                    // production as the general pass's pick among production indices.
                    let positions = choices.iter().enumerate().map(|(k, c)| (k as u32, c.1));
                    let chosen = pick(u, positions).and_then(|k| choices.get(k as usize));
                    match chosen {
                        Some(&(p, _, span)) => {
                            emit(out, span)?;
                            fired += 1;
                            last = Some(p);
                        }
                        None => out.symbols.push(symbol),
                    }
                }
            }
        }
        if out.symbols.len() > max {
            return Err(too_many());
        }
        self.fired = fired;
        self.bound_for = None;
        if last.is_some() {
            self.last_fired = last;
        }
        // A parameterless module's parameters end where they start: at 0.
        out.offsets.resize(out.symbols.len() + 1, 0);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use std::collections::HashMap;

    use proptest::prelude::*;

    use crate::LSystem;

    /// Rewrites `word` by `rules` character by character: the D0L step, by hand.
    fn by_hand(word: &str, rules: &HashMap<char, String>) -> String {
        word.chars()
            .map(|c| rules.get(&c).cloned().unwrap_or_else(|| c.to_string()))
            .collect()
    }

    proptest! {
        /// A D0L system derives, through the plain pass, the word rewriting by hand gives,
        /// with its brackets, turns and symbols no production rewrites.
        #[test]
        fn a_d0l_system_derives_the_word_rewritten_by_hand(
            axiom in "[ABCF]{1,4}",
            rules in proptest::collection::hash_map(
                prop::sample::select(vec!['A', 'B', 'C', 'F']),
                "[ABCF+\\-]{1,3}(\\[[ABF+]{1,3}\\])?[ABCF]{0,2}",
                1..4,
            ),
            generations in 0u32..6,
        ) {
            let text: String = std::iter::once(format!("axiom: {axiom}"))
                .chain(rules.iter().map(|(p, s)| format!("{p} -> {s}")))
                .collect::<Vec<_>>()
                .join("\n");
            let grammar = LSystem::parse(&text).unwrap();
            prop_assert!(grammar.compiled.plain.is_some(), "{}", text);
            let mut expected = axiom.clone();
            for _ in 0..generations {
                expected = by_hand(&expected, &rules);
            }
            prop_assert_eq!(grammar.derive(generations, 0).unwrap().to_string(), expected);
        }
    }

    /// The grammar with its plain table taken away: the general pass derives every word.
    fn general(grammar: &LSystem) -> LSystem {
        let mut g = grammar.clone();
        g.compiled.plain = None;
        g
    }

    proptest! {
        /// A stochastic 0L system derives the same word from a seed through the plain pass
        /// as through the general one: the same draws, in the same order, land on the same
        /// productions.
        #[test]
        fn a_stochastic_system_draws_as_the_general_pass_draws(
            successors in proptest::collection::vec("[ABF+\\-]{1,3}(\\[[AF+]{1,2}\\])?", 2..5),
            weights in proptest::collection::vec(0.0f64..3.0, 5),
            fixed in "[AF]{1,3}",
            seed in 0u64..1000,
            generations in 1u32..6,
        ) {
            let mut text = String::from("axiom: AB\n");
            for (k, s) in successors.iter().enumerate() {
                text.push_str(&format!("A -> {s} : {}\n", weights[k]));
            }
            text.push_str(&format!("B -> {fixed}B"));
            let grammar = LSystem::parse(&text).unwrap();
            prop_assert!(grammar.compiled.plain.is_some(), "{}", text);
            let general = general(&grammar);
            prop_assert!(general.compiled.plain.is_none());
            prop_assert_eq!(
                grammar.derive(generations, seed).unwrap(),
                general.derive(generations, seed).unwrap(),
            );
        }
    }

    /// A production with parameters, a condition or a context leaves the table to the
    /// general pass; a word with parameters takes the general pass even when the table is
    /// plain.
    #[test]
    fn what_a_lookup_cannot_do_takes_the_general_pass() {
        for text in [
            "axiom: A\nA -> AB\nB(x) -> A",
            "axiom: A\nA : 1 > 0 -> AB",
            "axiom: A\nB < A -> AB",
            "axiom: A\nA -> A%",
        ] {
            assert!(
                LSystem::parse(text).unwrap().compiled.plain.is_none(),
                "{text}"
            );
        }
        let g = LSystem::parse("axiom: A(1)B\nA -> AB\nB -> A").unwrap();
        assert!(g.compiled.plain.is_some());
        // A(1) has a parameter: no production of no parameters rewrites it.
        assert_eq!(g.derive(2, 0).unwrap().to_string(), "A(1)AB");
    }

    /// The module limit refuses a word before it is written.
    #[test]
    fn a_word_past_the_limit_is_refused() {
        let g = LSystem::parse("axiom: A\nA -> AA").unwrap();
        let err = g.derive(40, 0).unwrap_err();
        assert!(err.to_string().contains("modules"), "{err}");
    }
}
