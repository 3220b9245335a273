//! The `proptest` feature's strategies, used as a user would: arbitrary grammars print and
//! read back, derive within bounds and keep brackets balanced; arbitrary words over a
//! grammar's alphabet are balanced and print back.

use proptest::prelude::*;
use sylva_lsys::strategies::{GrammarSize, grammars, words};
use sylva_lsys::{LSystem, Limits, Word};

fn balanced(word: &Word) -> bool {
    let mut depth = 0i64;
    for m in word.iter() {
        depth += match m.symbol {
            '[' => 1,
            ']' => -1,
            _ => 0,
        };
        if depth < 0 {
            return false;
        }
    }
    depth == 0
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn arbitrary_grammars_print_back_and_derive_balanced_words(
        grammar in grammars(GrammarSize::default()),
        seed in any::<u64>(),
        steps in 0u32..5,
    ) {
        prop_assert_eq!(&LSystem::parse(&grammar.to_string()).unwrap(), &grammar);
        let limits = Limits::DEFAULT.with_max_modules(200_000);
        if let Ok(word) = grammar.derive_with(steps, seed, &limits) {
            prop_assert!(balanced(&word), "{}", word);
            prop_assert!(word.iter().all(|m| m.params.iter().all(|p| p.is_finite())));
        }
    }

    #[test]
    fn arbitrary_words_are_balanced_and_print_back(
        word in words(&"axiom: A(1)B\nA(x) -> F(x)[+A(x)]B\nB -> B".parse::<LSystem>().unwrap(), 30),
    ) {
        prop_assert!(balanced(&word));
        let again = Word::parse(&word.to_string(), word.alphabet().clone()).unwrap();
        prop_assert_eq!(again, word);
    }

    #[test]
    fn plain_grammars_are_not_parametric(
        grammar in grammars(GrammarSize { parametric: false, stochastic: false, ..GrammarSize::default() }),
    ) {
        prop_assert!(grammar.productions().iter().all(|p| p.predecessor.params.is_empty() && p.weight.is_none()));
    }
}
