//! proptest strategies for property tests of your own grammars (feature `proptest`).
//!
//! State what must hold of every word your grammar derives, and let proptest look for a
//! counterexample over seeds, step counts and starting words:
//!
//! ```
//! use proptest::prelude::*;
//! use sylva_lsys::{LSystem, strategies};
//!
//! let plant: LSystem = "
//!     axiom: A(1)
//!     A(x) : x < 8 -> F(x) [+A(x*1.5)] [-A(x+1)] : 1
//!     A(x) : x < 8 -> F(x) A(x+2) : 1
//!     F(x) -> F(x*1.1)"
//!     .parse()
//!     .unwrap();
//! proptest!(|(seed in any::<u64>(), steps in 0u32..6,
//!             start in strategies::words(&plant, 12))| {
//!     for word in [plant.derive(steps, seed).unwrap(), start] {
//!         // Brackets balance: every '[' has its ']'.
//!         let mut depth = 0i64;
//!         for m in word.iter() {
//!             depth += match m.symbol { '[' => 1, ']' => -1, _ => 0 };
//!             prop_assert!(depth >= 0);
//!         }
//!         prop_assert_eq!(depth, 0);
//!         // No parameter is NaN or infinite.
//!         prop_assert!(word.iter().all(|m| m.params.iter().all(|p| p.is_finite())));
//!     }
//!     // Growth is bounded: at most three new modules per A per step.
//!     let grown = plant.derive(steps, seed).unwrap().len();
//!     prop_assert!(grown <= 1 + 10 * 3usize.pow(steps));
//! });
//! ```
//!
//! [`grammars`] makes arbitrary well-formed grammars of bounded size, for properties of
//! code that takes any grammar (a turtle, an exporter).

use proptest::prelude::*;

use crate::{LSystem, Word};

/// Finite parameter values in `[-1000, 1000]`, zero and tiny magnitudes included.
pub fn parameter() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(0.0),
        -1000.0f64..1000.0,
        (-1.0f64..1.0).prop_map(|v| v * 1e-6),
    ]
}

/// How many parameters each symbol of `grammar` is written with: the largest count seen in
/// its axiom and successors (0 for symbols seen only bare).
fn arities(grammar: &LSystem) -> Vec<usize> {
    let mut arity = vec![0usize; grammar.alphabet().len()];
    let mut note = |m: &crate::ModuleTemplate| {
        let a = &mut arity[m.symbol.index()];
        *a = (*a).max(m.args.len());
    };
    grammar.axiom().iter().for_each(&mut note);
    let mut pending: Vec<&crate::SuccessorItem> = grammar
        .productions()
        .iter()
        .flat_map(|p| &p.successor)
        .collect();
    while let Some(item) = pending.pop() {
        match item {
            crate::SuccessorItem::Module(m) => note(m),
            crate::SuccessorItem::Choice {
                then, otherwise, ..
            } => pending.extend(then.iter().chain(otherwise)),
        }
    }
    arity
}

/// Bracket-balanced words of up to `max_modules` modules over `grammar`'s symbols, each
/// with as many parameters as the grammar writes it with, values from [`parameter`].
pub fn words(grammar: &LSystem, max_modules: usize) -> impl Strategy<Value = Word> + use<> {
    let alphabet = grammar.alphabet().clone();
    let arity = arities(grammar);
    // Brackets are placed by the shape below; '%' would cut the word short.
    let symbols: Vec<(crate::SymbolId, usize)> = (3..alphabet.len() as u16)
        .map(crate::SymbolId)
        .map(|s| (s, arity[s.index()]))
        .collect();
    let module = prop::sample::select(if symbols.is_empty() {
        vec![(crate::PUSH, 0)]
    } else {
        symbols
    })
    .prop_flat_map(|(s, n)| (Just(s), prop::collection::vec(parameter(), n)));
    // Each module may open a branch before it or close one after it.
    let shape = prop::collection::vec((module, 0u8..8), 0..=max_modules.max(1));
    shape.prop_map(move |modules| {
        let mut word = Word::empty(alphabet.clone());
        let mut open = 0usize;
        for ((symbol, params), roll) in modules {
            if symbol == crate::PUSH {
                continue;
            }
            if roll == 0 {
                word.push(crate::PUSH, &[]);
                open += 1;
            }
            word.push(symbol, &params);
            if roll == 1 && open > 0 {
                word.push(crate::POP, &[]);
                open -= 1;
            }
        }
        for _ in 0..open {
            word.push(crate::POP, &[]);
        }
        word
    })
}

/// The size of the grammars [`grammars`] makes; start from `GrammarSize::default()`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GrammarSize {
    /// Non-turtle symbols (`A`, `B`, ...), 1 to 26. Default: 3.
    pub symbols: usize,
    /// Most productions per symbol. Default: 2.
    pub productions: usize,
    /// Most modules in a successor (turtle symbols and brackets included). Default: 8.
    pub successor: usize,
    /// Whether modules carry a parameter, with conditions and arithmetic on it. Default: true.
    pub parametric: bool,
    /// Whether a symbol's productions are weighted (stochastic). Default: true.
    pub stochastic: bool,
}

impl Default for GrammarSize {
    fn default() -> Self {
        GrammarSize {
            symbols: 3,
            productions: 2,
            successor: 8,
            parametric: true,
            stochastic: true,
        }
    }
}

/// Arbitrary well-formed grammars of at most `size`: bracket-balanced successors over
/// `A`, `B`, ... and `F + - & ^ /`, parametric and stochastic as asked.
pub fn grammars(size: GrammarSize) -> impl Strategy<Value = LSystem> {
    let letters: Vec<char> = ('A'..='Z').take(size.symbols.clamp(1, 26)).collect();
    let p = size.parametric;
    let module = {
        let letters = letters.clone();
        (0..letters.len() + 6, 0u8..4, 1u8..4).prop_map(move |(k, op, c)| {
            let name = letters
                .get(k)
                .copied()
                .unwrap_or_else(|| ['F', '+', '-', '&', '^', '/'][k - letters.len()]);
            match (p, name.is_ascii_uppercase(), op) {
                (false, _, _) => name.to_string(),
                (true, true, 0) => format!("{name}(x*{c})"),
                (true, true, 1) => format!("{name}(x+{c})"),
                (true, true, _) => format!("{name}(x)"),
                (true, false, _) => format!("{name}({})", 10 * c),
            }
        })
    };
    let successor =
        prop::collection::vec((module, 0u8..6), 0..=size.successor.max(1)).prop_map(|items| {
            let mut out = String::new();
            let mut open = 0;
            for (m, roll) in items {
                if roll == 0 {
                    out.push('[');
                    open += 1;
                }
                out.push_str(&m);
                if roll == 1 && open > 0 {
                    out.push(']');
                    open -= 1;
                }
            }
            out.extend(std::iter::repeat_n(']', open));
            out
        });
    let production = (successor, 1u8..5, 0u8..3);
    let per_letter = prop::collection::vec(production, 1..=size.productions.max(1));
    prop::collection::vec(per_letter, letters.len()).prop_filter_map(
        "every generated grammar parses",
        move |rules| {
            let arg = if p { "(x)" } else { "" };
            let mut text = format!("axiom: {}{}\n", letters[0], if p { "(1)" } else { "" });
            for (letter, productions) in letters.iter().zip(rules) {
                for (succ, weight, guard) in productions {
                    let condition = match (p, guard) {
                        (true, 0) => " : x < 50",
                        (true, 1) => " : x >= 0",
                        _ => "",
                    };
                    let weight = if size.stochastic {
                        format!(" : {weight}")
                    } else {
                        String::new()
                    };
                    text.push_str(&format!("{letter}{arg}{condition} -> {succ}{weight}\n"));
                }
            }
            LSystem::parse(&text).ok()
        },
    )
}
