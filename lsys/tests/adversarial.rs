//! Hostile grammar text: each input must end quickly in an error with a location, or in a
//! usable grammar. None may panic, overflow the stack or take super-linear time.

use sylva_lsys::{
    Alphabet, BinaryOp, Expr, GrammarError, LSystem, Limits, MAX_EXPR_DEPTH, MAX_GRAMMAR_BYTES,
    ModuleTemplate, Word,
};

fn chain(terms: usize, op: &str) -> String {
    vec!["x"; terms].join(op)
}

fn parse_err(text: &str) -> (usize, usize, String) {
    let e = LSystem::parse(text).expect_err("must be refused");
    (e.location.line, e.location.column, e.message)
}

/// The report that opened this test: 200,000 terms overflowed the stack.
#[test]
fn long_operator_chain_is_refused_at_the_operator_that_is_too_deep() {
    let text = format!("axiom: A(1)\nA(x) -> A({})", chain(200_000, "+"));
    let (line, column, message) = parse_err(&text);
    assert_eq!(line, 2);
    // "A(x) -> A(" is 10 characters; term k starts at 11 + 2k and its '+' follows it.
    assert_eq!(column, 11 + 2 * (MAX_EXPR_DEPTH - 1) + 1);
    assert!(message.contains("deeper than"), "{message}");
}

#[test]
fn chains_within_the_limit_parse_derive_and_print_back() {
    for op in ["+", "*", "-", "/", "&&", "||", "<", "=="] {
        let text = format!("axiom: A(1)\nA(x) -> A({})", chain(MAX_EXPR_DEPTH, op));
        let g = LSystem::parse(&text).unwrap_or_else(|e| panic!("{op}: {e}"));
        g.derive(3, 0).unwrap();
        assert_eq!(LSystem::parse(&g.to_string()).unwrap(), g, "{op}");
    }
    let g = LSystem::parse(&format!("axiom: A(1)\nA(x) -> A({})", chain(256, "+"))).unwrap();
    assert_eq!(g.derive(2, 0).unwrap().params(0), &[256.0 * 256.0]);
}

#[test]
fn every_operator_level_counts_toward_the_depth() {
    // Alternating operators and a power tower nest as deep as a chain does.
    let mixed = (0..1000)
        .map(|i| if i % 2 == 0 { "x*" } else { "x+" })
        .collect::<String>()
        + "x";
    assert!(LSystem::parse(&format!("axiom: A(1)\nA(x) -> A({mixed})")).is_err());
    let tower = chain(400, "^");
    assert!(LSystem::parse(&format!("axiom: A(1)\nA(x) -> A({tower})")).is_err());
    let condition = chain(100_000, "&&");
    assert!(LSystem::parse(&format!("axiom: A(1)\nA(x) : {condition} -> A(x)")).is_err());
}

#[test]
fn deep_nesting_of_every_kind_is_an_error() {
    let parens = "(".repeat(100_000) + "1" + &")".repeat(100_000);
    let calls = "sin(".repeat(100_000) + "1" + &")".repeat(100_000);
    let unary = "-".repeat(100_000) + "1";
    let not = "!".repeat(100_000) + "1";
    for arg in [parens, calls, unary, not] {
        let (line, _, message) = parse_err(&format!("axiom: A(1)\nA(x) -> A({arg})"));
        assert_eq!(line, 2);
        assert!(
            message.contains("nested") || message.contains("deeper"),
            "{message}"
        );
    }
    let choices = "?(0.5)<".repeat(10_000) + "A" + &"><B>".repeat(10_000);
    let (line, _, message) = parse_err(&format!("axiom: A\nA -> {choices}"));
    assert_eq!(line, 2);
    assert!(message.contains("nested"), "{message}");
}

#[test]
fn megabyte_lines_parse_in_linear_time() {
    // A million modules in one successor and one axiom line.
    let successor = "F[+A]".repeat(200_000);
    let g = LSystem::parse(&format!("axiom: {successor}\nA -> {successor}")).unwrap();
    assert_eq!(g.axiom().len(), 1_000_000);
    // A megabyte comment and a megabyte number.
    let comment = format!("/*{}*/axiom: A", "x".repeat(1 << 20));
    assert!(LSystem::parse(&comment).is_ok());
    let digits = "9".repeat(1 << 20);
    let (_, column, message) = parse_err(&format!("axiom: A({digits})"));
    assert_eq!(column, 10);
    assert!(message.len() < 200, "the message quotes a bounded prefix");
    let fraction = format!("axiom: A(0.{digits})");
    assert!(LSystem::parse(&fraction).is_ok());
}

#[test]
fn non_finite_literals_and_values_are_errors_with_their_place() {
    assert_eq!(parse_err("axiom: A(1e999)").1, 10);
    let (_, column, message) = parse_err("axiom: A(nan)");
    assert_eq!(column, 10);
    assert!(message.contains("unknown name 'nan'"), "{message}");
    assert_eq!(parse_err("axiom: A(inf)").1, 10);
    // Values that only become infinite when evaluated.
    let (line, column, message) = parse_err("#define big 1e300\n\naxiom: F B(1) A(big*big)");
    assert_eq!((line, column), (3, 15), "{message}");
    assert!(message.contains("not finite"), "{message}");
    let (line, column, _) = parse_err("axiom: A\n#define k 1/0");
    assert_eq!((line, column), (2, 9));
    let (line, column, _) = parse_err("axiom: A\nA -> B : 1/0");
    assert_eq!((line, column), (2, 10));
    assert!("F(1e999)".parse::<Word>().is_err());
    assert!("F(1/0)".parse::<Word>().is_err());
}

#[test]
fn absurd_counts_of_productions_constants_and_parameters() {
    // 100,000 productions over 60,000 distinct symbols.
    let symbols: Vec<char> = (0x4E00u32..0x4E00 + 60_000)
        .filter_map(char::from_u32)
        .collect();
    let mut text = String::from("axiom: A\n");
    for k in 0..100_000 {
        let s = symbols[k % symbols.len()];
        text.push_str(&format!("{s} -> F{s}\n"));
    }
    let g = LSystem::parse(&text).unwrap();
    assert_eq!(g.productions().len(), 100_000);
    // 100,000 constants, each defined from the one before: evaluated once each, not again
    // at every use.
    let mut text = String::from("#define c0 1\n");
    for k in 1..100_000 {
        text.push_str(&format!("#define c{k} c{}+1\n", k - 1));
    }
    text.push_str("axiom: A(c99999)");
    let g = LSystem::parse(&text).unwrap();
    assert_eq!(g.axiom_word().params(0), &[100_000.0]);
    // A module with 256 parameters, and a context of 50,000 parameterised modules.
    let params = (0..256)
        .map(|i| format!("p{i}"))
        .collect::<Vec<_>>()
        .join(",");
    assert!(LSystem::parse(&format!("axiom: A\nA({params}) -> A")).is_err());
    let context = (0..50_000).map(|i| format!("B(b{i})")).collect::<String>();
    let g = LSystem::parse(&format!("axiom: A\n{context} < A(x) -> A(b49999+x)")).unwrap();
    assert_eq!(g.productions()[0].binding_count(), 50_001);
    // Derivation stays within its limits.
    let limits = Limits::default().with_max_modules(10_000);
    assert!(
        LSystem::parse("axiom: A\nA -> AAAAAAAAAA")
            .unwrap()
            .derive_with(40, 0, &limits)
            .is_err()
    );
}

#[test]
fn oversized_text_is_refused_before_parsing() {
    let text = " ".repeat(MAX_GRAMMAR_BYTES + 1);
    let e = LSystem::parse(&text).unwrap_err();
    assert_eq!((e.location.line, e.location.column), (1, 1));
    assert!(e.message.contains("longer than"));
}

#[test]
fn a_byte_order_mark_is_not_part_of_the_grammar() {
    let g = LSystem::parse("\u{feff}axiom: A\nA -> AB").unwrap();
    assert_eq!(g.derive(2, 0).unwrap().to_string(), "ABB");
}

#[test]
fn hostile_bytes_never_panic() {
    for text in [
        "\0\0\0",
        "axiom:",
        "axiom: A\n->",
        "axiom: A\nA(",
        "axiom: A\nA(x) -> A(x",
        "axiom: A\nA -> ?(",
        "axiom: A\nA -> ?(1)<",
        "axiom: A\nA -> B : ",
        "#define",
        "#define x",
        "#ignore:",
        "axiom: A\r\nA -> B\r\n",
        "axiom: \u{10FFFF}\u{200B}",
        "axiom: A(1,)",
        "axiom: A(,1)",
        "axiom: A()",
        "axiom: A\nA -> B(sin())",
        "axiom: A\nA -> B(atan2(1,2,3,4,5,6))",
        "\u{feff}\u{feff}axiom: A",
    ] {
        let _ = LSystem::parse(text);
        let _ = text.parse::<Word>();
    }
}

/// An expression built by hand, deeper than any parser would build.
fn left_chain(depth: usize) -> Expr {
    let mut e = Expr::Number(1.0);
    for _ in 1..depth {
        e = Expr::Binary(BinaryOp::Add, Box::new(e), Box::new(Expr::Number(1.0)));
    }
    e
}

#[test]
fn trees_built_by_hand_are_measured_checked_and_dropped_without_recursion() {
    let deep = left_chain(1_000_000);
    assert_eq!(deep.depth(), 1_000_000);
    let mut alphabet = Alphabet::new();
    let a = alphabet.intern('A').unwrap();
    let axiom = vec![ModuleTemplate {
        symbol: a,
        args: vec![deep],
    }];
    let err = LSystem::from_parts(alphabet, vec![], vec![], axiom, vec![]).unwrap_err();
    assert!(
        matches!(err, GrammarError::InvalidAxiom { module: 0, .. }),
        "{err}"
    );
    // `axiom` (and the million-level tree in it) was dropped inside from_parts.
    let shallow = left_chain(MAX_EXPR_DEPTH);
    let mut alphabet = Alphabet::new();
    let a = alphabet.intern('A').unwrap();
    let g = LSystem::from_parts(
        alphabet,
        vec![],
        vec![],
        vec![ModuleTemplate {
            symbol: a,
            args: vec![shallow],
        }],
        vec![],
    )
    .unwrap();
    assert_eq!(g.axiom_word().params(0), &[MAX_EXPR_DEPTH as f64]);
}

/// Found by fuzzing: a keyword alone on its line, in each dialect, is an error or an empty
/// declaration, never a panic.
#[test]
fn bare_dialect_keywords_do_not_panic() {
    use sylva_lsys::Dialect;
    for text in [
        "module",
        "module ",
        "Axiom:",
        "derivation length:",
        "maximum depth:",
        "production:",
        "endlsystem",
        "group 1",
        "x =",
    ] {
        for dialect in [Dialect::Cpfg, Dialect::LPy, Dialect::Sylva] {
            let _ = LSystem::parse_dialect(text, dialect);
        }
    }
}

/// A cpfg grammar deriving F into FF twice, for wrapping in hostile preprocessor text.
const CPFG: &str = "lsystem: 1\nderivation length: 2\naxiom: F\nF --> FF\nendlsystem\n";

fn cpfg(text: &str) -> Result<LSystem, sylva_lsys::ParseError> {
    LSystem::parse_dialect(text, sylva_lsys::Dialect::Cpfg)
}

/// Modules after two derivation steps.
fn twice(g: LSystem) -> usize {
    g.derive(2, 0).unwrap().len()
}

/// The preprocessor's constructs at a megabyte each: the report that opened this test
/// (issue 28) was 100,000 nested `#if 1` taking 17 s, each line asking every open `#if`
/// whether it was taken. Each is linear now; `cargo bench --bench lsys -- preprocess`
/// measures them.
#[test]
fn megabyte_preprocessor_constructs_end_in_a_grammar_or_an_error() {
    let n = 100_000;
    let nested = format!("{}{CPFG}{}", "#if 1\n".repeat(n), "#endif\n".repeat(n));
    assert_eq!(twice(cpfg(&nested).unwrap()), 4);
    let skipped = format!("{}x\n{}{CPFG}", "#if 0\n".repeat(n), "#endif\n".repeat(n));
    assert_eq!(twice(cpfg(&skipped).unwrap()), 4);
    // Every #else flips a branch: n/2 pairs leave the grammar inside taken branches.
    let flipped = format!(
        "{}{CPFG}{}",
        "#ifdef X\n#else\n".repeat(n / 2),
        "#endif\n".repeat(n / 2)
    );
    assert!(cpfg(&flipped).is_ok());
    let defines: String = (0..n).map(|k| format!("#define M{k} {k}\n")).collect();
    assert!(cpfg(&format!("{defines}{CPFG}")).is_ok());
    // 400,000 uses of a macro on one line expand whole.
    let used = format!(
        "#define X F\nlsystem: 1\nderivation length: 1\naxiom: {}\nendlsystem\n",
        "X ".repeat(400_000)
    );
    assert_eq!(cpfg(&used).unwrap().axiom().len(), 400_000);
    let calls = format!(
        "#define G(a,b) a b\nlsystem: 1\nderivation length: 1\naxiom: {}\nendlsystem\n",
        "G(F,+) ".repeat(140_000)
    );
    assert_eq!(cpfg(&calls).unwrap().axiom().len(), 280_000);
    // A condition of 80,000 `defined(A)` is answered in one pass, then refused as too deep.
    let defined = format!(
        "#if {}\n#endif\n{CPFG}",
        vec!["defined(A)"; 80_000].join(" || ")
    );
    let e = cpfg(&defined).unwrap_err();
    assert_eq!(e.location.line, 1);
    assert!(e.message.contains("deeper"), "{}", e.message);
    // 300,000 spliced lines make one macro.
    let spliced = format!("#define Q \\\n{}F\n{CPFG}", "F \\\n".repeat(300_000));
    assert!(cpfg(&spliced).is_ok());
    // Unclosed #if and stray #endif at a megabyte are errors with their place.
    let open = format!("{}{CPFG}", "#if 1\n".repeat(n));
    assert!(cpfg(&open).unwrap_err().message.contains("without #endif"));
    let stray = format!("{CPFG}{}", "#endif\n".repeat(n));
    assert_eq!(cpfg(&stray).unwrap_err().location.line, 6);
}
