//! Property tests: determinism, bracket balance, growth, stochastic frequencies, round trips,
//! and that no input panics the parser or the engine.

mod common;

use proptest::prelude::*;
use sylva_lsys::{LSystem, Limits, Word};

fn balanced(w: &Word) -> bool {
    let mut depth = 0i64;
    for m in w.iter() {
        match m.symbol {
            '[' => depth += 1,
            ']' => depth -= 1,
            _ => {}
        }
        if depth < 0 {
            return false;
        }
    }
    depth == 0
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn same_seed_same_word(src in common::stochastic_grammar(), seed: u64) {
        let g = LSystem::parse(&src).unwrap();
        let limits = Limits::default().with_max_modules(200_000);
        let a = g.derive_with(5, seed, &limits);
        let b = g.derive_with(5, seed, &limits);
        prop_assert_eq!(a, b);
    }

    #[test]
    fn balanced_productions_keep_brackets_balanced(a in common::balanced_successor(), b in common::balanced_successor(), seed: u64) {
        let g = LSystem::parse(&format!("axiom: A[B]A\nA -> {a}\nB -> {b}")).unwrap();
        if let Ok(w) = g.derive_with(4, seed, &Limits::default().with_max_modules(200_000)) {
            prop_assert!(balanced(&w), "{}", w);
        }
    }

    #[test]
    fn d0l_length_follows_growth_matrix((axiom, succ) in common::d0l(), generations in 0u32..7) {
        let src = format!("axiom: {axiom}\nA -> {}\nB -> {}\nC -> {}", succ[0], succ[1], succ[2]);
        let g = LSystem::parse(&src).unwrap();
        // counts[i] after n generations = counts after n-1 generations times the growth matrix M[i][j]
        // (number of letter j in the successor of letter i).
        let idx = |c: char| (c as u8 - b'A') as usize;
        let mut m = [[0u64; 3]; 3];
        for (i, s) in succ.iter().enumerate() {
            for c in s.chars() { m[i][idx(c)] += 1; }
        }
        let mut v = [0u64; 3];
        for c in axiom.chars() { v[idx(c)] += 1; }
        for _ in 0..generations {
            let mut next = [0u64; 3];
            for i in 0..3 { for j in 0..3 { next[j] += v[i] * m[i][j]; } }
            v = next;
        }
        let w = g.derive(generations, 0).unwrap();
        prop_assert_eq!(w.len() as u64, v.iter().sum::<u64>());
    }

    #[test]
    fn words_print_and_parse_back(text in common::word_text()) {
        let w: Word = text.parse().unwrap();
        let again = Word::parse(&w.to_string(), w.alphabet().clone()).unwrap();
        prop_assert_eq!(again, w);
    }

    #[test]
    fn grammars_print_and_parse_back(src in common::stochastic_grammar()) {
        let g = LSystem::parse(&src).unwrap();
        let printed = g.to_string();
        let again = LSystem::parse(&printed).unwrap();
        prop_assert_eq!(&again, &g);
        prop_assert_eq!(again.derive(3, 5).unwrap(), g.derive(3, 5).unwrap());
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    #[test]
    fn arbitrary_text_never_panics(src in "\\PC{0,80}") {
        let _ = LSystem::parse(&src);
        let _ = src.parse::<Word>();
    }

    #[test]
    fn grammar_like_text_never_panics(src in common::grammar_like_text(), seed: u64) {
        if let Ok(g) = LSystem::parse(&src) {
            let limits = Limits::default().with_max_modules(10_000).with_max_params(10_000).with_max_generations(6);
            let _ = g.derive_with(6, seed, &limits);
            let _ = LSystem::parse(&g.to_string()).unwrap();
        }
    }
}

/// Chi-square test of stochastic choice against the weights. With 2 degrees of freedom the
/// critical value 13.82 gives a false-alarm rate of 0.1 per cent per seed; the seeds are
/// fixed, so the test is deterministic and was checked to pass.
#[test]
fn stochastic_choice_follows_weights() {
    let n = 30_000;
    let src = format!(
        "axiom: {}\nA -> X : 1\nA -> Y : 2\nA -> Z : 3",
        "A".repeat(n)
    );
    let g = LSystem::parse(&src).unwrap();
    for seed in 0..5 {
        let w = g.derive(1, seed).unwrap();
        let mut counts = [0f64; 3];
        for m in w.iter() {
            counts[(m.symbol as u8 - b'X') as usize] += 1.0;
        }
        let expected = [n as f64 / 6.0, n as f64 / 3.0, n as f64 / 2.0];
        let chi2: f64 = counts
            .iter()
            .zip(expected)
            .map(|(o, e)| (o - e) * (o - e) / e)
            .sum();
        assert!(chi2 < 13.82, "seed {seed}: counts {counts:?}, chi2 {chi2}");
    }
}

/// Conditions filter candidates before the weighted draw: only matching productions share
/// the probability mass.
#[test]
fn stochastic_choice_is_among_matching_productions() {
    let src = format!(
        "axiom: {}\nA(x) : x > 5 -> X : 1\nA(x) -> Y : 1\nA(x) -> Z : 1",
        "A(1)".repeat(3000)
    );
    let w = LSystem::parse(&src).unwrap().derive(1, 3).unwrap();
    assert!(w.iter().all(|m| m.symbol != 'X'));
    let ys = w.iter().filter(|m| m.symbol == 'Y').count();
    assert!((1350..1650).contains(&ys), "{ys}");
}

/// A bracketed word over `A B C + [ ]` with balanced brackets.
fn signal_word() -> impl Strategy<Value = String> {
    prop::collection::vec(0u8..7, 0..60).prop_map(|picks| {
        let mut text = String::new();
        let mut depth = 0;
        for p in picks {
            match p {
                0 | 1 => text.push('B'),
                2 => text.push('A'),
                3 => text.push('C'),
                4 => text.push('+'),
                5 => {
                    text.push('[');
                    depth += 1;
                }
                _ if depth > 0 => {
                    text.push(']');
                    depth -= 1;
                }
                _ => text.push('B'),
            }
        }
        text.push_str(&"]".repeat(depth));
        text
    })
}

/// ABOP 1.8's left context, walked by hand over characters: the nearest module to the left
/// of `i`, skipping ignored `+`, stepping out of a branch at `[` and over a whole branch at `]`.
fn left_neighbour(word: &[char], i: usize) -> Option<char> {
    let mut j = i;
    while j > 0 {
        j -= 1;
        match word[j] {
            '+' | '[' => {}
            ']' => {
                let mut depth = 0;
                loop {
                    match word[j] {
                        ']' => depth += 1,
                        '[' => depth -= 1,
                        _ => {}
                    }
                    if depth == 0 {
                        break;
                    }
                    j -= 1;
                }
            }
            c => return Some(c),
        }
    }
    None
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    /// Signals in a bracketed word with an ignore set: the engine (which copies runs of B
    /// after a B in bulk) agrees with a walk done module by module.
    #[test]
    fn left_context_signals_agree_with_a_walk_by_hand(word in signal_word()) {
        let g = LSystem::parse(&format!("#ignore: +\naxiom: {word}\nA < B -> A\nC < B -> CC")).unwrap();
        let chars: Vec<char> = word.chars().collect();
        let expected: String = chars
            .iter()
            .enumerate()
            .map(|(i, &c)| match (c, left_neighbour(&chars, i)) {
                ('B', Some('A')) => "A".to_string(),
                ('B', Some('C')) => "CC".to_string(),
                _ => c.to_string(),
            })
            .collect();
        prop_assert_eq!(g.derive(1, 0).unwrap().to_string(), expected);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    /// A symbol rewritten by weighted productions alone takes its draw without matching;
    /// the same productions with a condition that always holds go through matching. Both
    /// make the same draws, so they derive the same word for every seed.
    #[test]
    fn draws_without_matching_agree_with_draws_after_matching(
        weights in prop::collection::vec(0u8..5, 2..5),
        seed: u64,
    ) {
        let successors = ["F[+A]A", "F[-A]A", "F[&A][^A]", "FA"];
        let productions = |condition: &str| -> String {
            weights
                .iter()
                .zip(successors)
                .map(|(w, s)| format!("A{condition} -> {s} : {w}\n"))
                .collect()
        };
        let drawn = LSystem::parse(&format!("axiom: A\n{}", productions(""))).unwrap();
        let matched = LSystem::parse(&format!("axiom: A\n{}", productions(" : 1"))).unwrap();
        let limits = Limits::default().with_max_modules(100_000);
        prop_assert_eq!(
            drawn.derive_with(6, seed, &limits),
            matched.derive_with(6, seed, &limits)
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    /// A ring has no first module: turning the axiom round by `k` places turns every word
    /// derived from it by `k` (each production here writes one module, so places keep).
    #[test]
    fn a_ring_derives_the_same_from_any_starting_place(
        word in proptest::collection::vec(prop_oneof![Just('A'), Just('B'), Just('C')], 1..24),
        k in 0usize..24,
        steps in 0u32..6,
    ) {
        let rules = "#ring\nA < B > C -> A\nB < A -> C\nC > A -> B\nA < C -> A";
        let turn = |w: &str, by: usize| {
            let chars: Vec<char> = w.chars().collect();
            let by = by % chars.len();
            chars[by..].iter().chain(&chars[..by]).collect::<String>()
        };
        let axiom: String = word.iter().collect();
        let g = LSystem::parse(&format!("axiom: {axiom}\n{rules}")).unwrap();
        let turned = LSystem::parse(&format!("axiom: {}\n{rules}", turn(&axiom, k))).unwrap();
        let a = g.derive(steps, 0).unwrap().to_string();
        let b = turned.derive(steps, 0).unwrap().to_string();
        prop_assert_eq!(turn(&a, k), b);
    }
}
