//! proptest strategies shared by the property tests, all with bounded sizes.

use proptest::prelude::*;

/// A bracket-balanced successor over `A B F + - &`, up to a few levels deep.
pub(crate) fn balanced_successor() -> impl Strategy<Value = String> {
    let leaf = prop::sample::select(vec!["A", "B", "F", "+", "-", "&", "F(2)", "A(1)"])
        .prop_map(str::to_string);
    leaf.prop_recursive(3, 24, 4, |inner| {
        prop_oneof![
            prop::collection::vec(inner.clone(), 1..4).prop_map(|v| v.concat()),
            inner.prop_map(|s| format!("[{s}]")),
        ]
    })
}

/// A D0L system over {A, B, C}: axiom and one successor per letter, as strings.
pub(crate) fn d0l() -> impl Strategy<Value = (String, [String; 3])> {
    let word = |min| {
        prop::collection::vec(prop::sample::select(vec!['A', 'B', 'C']), min..4)
            .prop_map(|v| v.into_iter().collect::<String>())
    };
    (word(1), [word(0), word(0), word(0)])
}

/// Grammar text with stochastic, parametric and bracketed productions.
pub(crate) fn stochastic_grammar() -> impl Strategy<Value = String> {
    (balanced_successor(), balanced_successor(), balanced_successor(), 1u32..5, 1u32..5).prop_map(|(a, b, c, w1, w2)| {
        format!("axiom: A\nA -> {a} : {w1}\nA -> {b} : {w2}\nB -> {c}\nA(x) -> F(x*uniform(0.5,1.5))A\nF(x) -> F(x+1)")
    })
}

/// A word's text with random finite parameters.
pub(crate) fn word_text() -> impl Strategy<Value = String> {
    let module = (
        prop::sample::select(vec!['A', 'F', '+', '[', ']', '!', '$', '/']),
        prop::collection::vec(
            prop::num::f64::NORMAL | prop::num::f64::ZERO | prop::num::f64::SUBNORMAL,
            0..3,
        ),
    )
        .prop_map(|(c, params)| {
            if params.is_empty() {
                c.to_string()
            } else {
                let p: Vec<String> = params.iter().map(|v| v.to_string()).collect();
                format!("{c}({})", p.join(","))
            }
        });
    prop::collection::vec(module, 0..20).prop_map(|v| v.concat())
}

/// Lines that look like grammar text: the characters the parser cares about, in any order.
pub(crate) fn grammar_like_text() -> impl Strategy<Value = String> {
    prop::collection::vec("[ABFxy0-9 +\\-*/^()\\[\\],:<>#.!%?&|=→ω]{0,24}|axiom: [AB(1)]{0,6}|#define [a-z] [0-9.]{1,3}|#ignore: [+\\-]", 0..6)
        .prop_map(|lines| lines.join("\n"))
}
