//! Rewriting throughput in modules per second, sylva side by side with the `symbios` crate on
//! the same grammars (the closest Rust peer: structure-of-arrays, bytecode expressions).
//!
//! Grammars are written with spaces between modules because symbios reads multi-letter names;
//! sylva ignores the spaces. Throughput counts every module produced over all generations.

use std::hint::black_box;

use criterion::{BatchSize, Criterion, Throughput, criterion_group, criterion_main};
use sylva::lsys::{Dialect, LSystem};

struct Case {
    name: &'static str,
    defines: &'static [&'static str],
    axiom: String,
    rules: &'static [&'static str],
    generations: u32,
}

fn cases() -> Vec<Case> {
    vec![
        Case {
            name: "d0l_plant_abop_1.24d",
            defines: &[],
            axiom: "X".into(),
            rules: &["X -> F [ + X ] F [ - X ] + X", "F -> F F"],
            generations: 9,
        },
        Case {
            name: "honda_tree",
            defines: &[
                "#define r1 0.9",
                "#define r2 0.6",
                "#define a0 45",
                "#define a2 45",
                "#define d 137.5",
                "#define wr 0.707",
            ],
            axiom: "A(1,10)".into(),
            rules: &[
                "A(l,w) -> !(w) F(l) [ &(a0) B(l*r2,w*wr) ] /(d) A(l*r1,w*wr)",
                "B(l,w) -> !(w) F(l) [ -(a2) $ C(l*r2,w*wr) ] C(l*r1,w*wr)",
                "C(l,w) -> !(w) F(l) [ +(a2) $ B(l*r2,w*wr) ] B(l*r1,w*wr)",
            ],
            generations: 15,
        },
        Case {
            name: "ternary_tree",
            defines: &[
                "#define d1 94.74",
                "#define d2 132.63",
                "#define a 18.95",
                "#define lr 1.109",
                "#define vr 1.732",
            ],
            axiom: "!(1) F(200) /(45) A".into(),
            rules: &[
                "A -> !(vr) F(50) [ &(a) F(50) A ] /(d1) [ &(a) F(50) A ] /(d2) [ &(a) F(50) A ]",
                "F(l) -> F(l*lr)",
                "!(w) -> !(w*vr)",
            ],
            generations: 8,
        },
        Case {
            name: "stochastic_bush",
            defines: &[],
            axiom: "A".into(),
            rules: &["A -> F [ + A ] A : 0.5", "A -> F [ - A ] [ & A ] : 0.5"],
            generations: 18,
        },
        Case {
            name: "stochastic_bush_three",
            defines: &[],
            axiom: "A".into(),
            rules: &[
                "A -> F [ + A ] A : 0.4",
                "A -> F [ - A ] A : 0.35",
                "A -> F [ & A ] [ ^ A ] : 0.25",
            ],
            generations: 17,
        },
        Case {
            // A signal entering a long word of B: the B after an A turns into one. (With
            // `B -> B B` beside it, symbios 1.5 and sylva disagree on the length: sylva's
            // 393,235 after 16 steps from A and eight B is the count worked by hand,
            // a + b with a = 1 + n and b = 6 * 2^n + 2.)
            name: "context_signal_plain",
            defines: &[],
            axiom: format!("A {}", "B ".repeat(300_000)),
            rules: &["A < B -> A"],
            generations: 1,
        },
        Case {
            name: "context_signal",
            defines: &[],
            axiom: "A(1) B(1) C(1) ".repeat(100_000),
            rules: &["A(x) < B(y) > C(z) -> B(x+y+z)"],
            generations: 1,
        },
    ]
}

fn sylva_source(c: &Case) -> String {
    let mut s = c.defines.join("\n");
    s.push_str(&format!("\naxiom: {}\n", c.axiom));
    s.push_str(&c.rules.join("\n"));
    s
}

/// symbios writes the probability first: `0.5: A -> ...`.
fn symbios_system(c: &Case) -> symbios::System {
    let mut sys = symbios::System::new();
    sys.max_capacity = 50_000_000;
    for d in c.defines {
        sys.add_directive(d).expect("symbios directive");
    }
    for r in c.rules {
        let rule = match r.rsplit_once(" : ") {
            Some((body, p)) => format!("{p}: {body}"),
            None => r.to_string(),
        };
        sys.add_rule(&rule).expect("symbios rule");
    }
    sys.set_axiom(&c.axiom).expect("symbios axiom");
    sys
}

fn rewriting(crit: &mut Criterion) {
    let mut group = crit.benchmark_group("rewriting");
    group.sample_size(10);
    for case in cases() {
        let grammar = LSystem::parse(&sylva_source(&case)).expect("grammar parses");
        let produced: u64 = (1..=case.generations)
            .map(|n| grammar.derive(n, 1).expect("derives").len() as u64)
            .sum();
        // Both engines must agree on the size of what they build, or the ratio means nothing.
        let mut check = symbios_system(&case);
        check
            .derive(case.generations as usize)
            .expect("symbios derives");
        let ours = grammar.derive(case.generations, 1).expect("derives").len();
        if !case.name.starts_with("stochastic") {
            assert_eq!(check.state.len(), ours, "{}: engines disagree", case.name);
        }
        group.throughput(Throughput::Elements(produced));
        group.bench_function(format!("sylva/{}", case.name), |b| {
            b.iter(|| {
                grammar
                    .derive(black_box(case.generations), 1)
                    .expect("derives")
            })
        });
        group.bench_function(format!("symbios/{}", case.name), |b| {
            b.iter_batched(
                || symbios_system(&case),
                |mut sys| {
                    sys.derive(black_box(case.generations as usize))
                        .expect("symbios derives")
                },
                BatchSize::LargeInput,
            )
        });
    }
    group.finish();
}

/// A cpfg grammar deriving F into FF, for wrapping in preprocessor text.
const CPFG: &str = "lsystem: 1\nderivation length: 2\naxiom: F\nF --> FF\nendlsystem\n";

/// Parsing megabyte cpfg files of one preprocessor construct each: linear in their length
/// (the nested `#if 1` took 17 s before issue 28). Throughput is bytes.
fn preprocess(crit: &mut Criterion) {
    let mut group = crit.benchmark_group("preprocess");
    group.sample_size(10);
    let n = 100_000;
    let inputs = [
        (
            "nested_if",
            format!("{}{CPFG}{}", "#if 1\n".repeat(n), "#endif\n".repeat(n)),
        ),
        (
            "defines",
            (0..n)
                .map(|k| format!("#define M{k} {k}\n"))
                .collect::<String>()
                + CPFG,
        ),
        (
            "macro_uses",
            format!(
                "#define X F\nlsystem: 1\nderivation length: 1\naxiom: {}\nendlsystem\n",
                "X ".repeat(400_000)
            ),
        ),
        (
            "function_macros",
            format!(
                "#define G(a,b) a b\nlsystem: 1\nderivation length: 1\naxiom: {}\nendlsystem\n",
                "G(F,+) ".repeat(140_000)
            ),
        ),
    ];
    for (name, text) in &inputs {
        group.throughput(Throughput::Bytes(text.len() as u64));
        group.bench_function(*name, |b| {
            b.iter(|| LSystem::parse_dialect(black_box(text), Dialect::Cpfg).expect("parses"))
        });
    }
    group.finish();
}

criterion_group!(benches, rewriting, preprocess);
criterion_main!(benches);
