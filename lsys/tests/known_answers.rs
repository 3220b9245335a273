//! Known answers: ABOP examples and every grammar feature on small inputs.

use sylva_lsys::{DeriveError, LSystem, Limits, PRESETS, Word};

fn derive(src: &str, generations: u32) -> String {
    LSystem::parse(src)
        .unwrap()
        .derive(generations, 1)
        .unwrap()
        .to_string()
}

#[test]
fn algae_grows_as_fibonacci() {
    let g = LSystem::parse("axiom: A\nA -> AB\nB -> A").unwrap();
    let lengths: Vec<usize> = (0..10).map(|n| g.derive(n, 0).unwrap().len()).collect();
    assert_eq!(lengths, [1, 2, 3, 5, 8, 13, 21, 34, 55, 89]);
    assert_eq!(g.derive(5, 0).unwrap().to_string(), "ABAABABAABAAB");
}

#[test]
fn abop_1_24d_second_generation() {
    let p = sylva_lsys::preset("abop-1.24d").unwrap();
    let w = p.lsystem().unwrap().derive(2, 0).unwrap();
    assert_eq!(
        w.to_string(),
        "FF[+F[+X]F[-X]+X]FF[-F[+X]F[-X]+X]+F[+X]F[-X]+X"
    );
}

#[test]
fn thesis_parametric_example() {
    // Garden of Eden thesis 5.1.2 (ABOP section 1.10.1).
    let src = "axiom: B(2)A(4,4)
        A(x,y) : y <= 3 -> A(x*2,x+y)
        A(x,y) : y > 3 -> B(x)A(x/y,0)
        B(x) : x < 1 -> C
        B(x) : x >= 1 -> B(x-1)";
    assert_eq!(derive(src, 1), "B(1)B(4)A(1,0)");
    assert_eq!(derive(src, 2), "B(0)B(3)A(2,1)");
    assert_eq!(derive(src, 3), "CB(2)A(4,3)");
    assert_eq!(derive(src, 4), "CB(1)A(8,7)");
}

#[test]
fn honda_tree_first_step_applies_constants() {
    let g = sylva_lsys::preset("abop-honda").unwrap().lsystem().unwrap();
    assert_eq!(g.constant("d"), Some(137.5));
    let w = g.derive(1, 0).unwrap().to_string();
    assert_eq!(
        w,
        "!(10)F(1)[&(45)B(0.6,7.069999999999999)]/(137.5)A(0.9,7.069999999999999)"
    );
}

#[test]
fn ternary_tree_rewrites_turtle_symbols() {
    let g = sylva_lsys::preset("abop-ternary")
        .unwrap()
        .lsystem()
        .unwrap();
    let w = g.derive(2, 0).unwrap();
    // The axiom's F(200) was elongated twice and its width raised twice.
    let first_f = w.iter().find(|m| m.symbol == 'F').unwrap();
    assert!((first_f.params[0] - 200.0 * 1.109 * 1.109).abs() < 1e-9);
    let first_w = w.iter().find(|m| m.symbol == '!').unwrap();
    assert!((first_w.params[0] - 1.732 * 1.732).abs() < 1e-9);
}

#[test]
fn signal_propagates_with_left_context() {
    // ABOP section 1.8: an acropetal signal moving along a filament.
    let src = "axiom: baaaa\nb < a -> b\nb -> a";
    let words: Vec<String> = (0..5).map(|n| derive(src, n)).collect();
    assert_eq!(words, ["baaaa", "abaaa", "aabaa", "aaaba", "aaaab"]);
}

#[test]
fn left_context_skips_branches_and_climbs_to_parent() {
    // C's left neighbour is A (the branch [B] is skipped); D's is B's parent chain: B then A.
    assert_eq!(derive("axiom: A[B]C\nA < C -> X", 1), "A[B]X");
    assert_eq!(derive("axiom: A[B]C\nB < C -> X", 1), "A[B]C");
    assert_eq!(derive("axiom: A[BD]\nA < B -> X", 1), "A[XD]");
}

#[test]
fn right_context_skips_branches_unless_entered() {
    assert_eq!(derive("axiom: A[B]C\nA > C -> X", 1), "X[B]C");
    assert_eq!(derive("axiom: A[B]C\nA > B -> X", 1), "A[B]C");
    assert_eq!(derive("axiom: A[B]C\nA > [B]C -> X", 1), "X[B]C");
    // `]` skips the rest of the current branch, so E does not stand in the way.
    assert_eq!(derive("axiom: A[BE]C\nB > ]C -> X", 1), "A[XE]C");
    assert_eq!(derive("axiom: A[BE]D\nB > ]C -> X", 1), "A[BE]D");
    assert_eq!(derive("axiom: A[B]C\nB > ]C -> X", 1), "A[X]C");
}

#[test]
fn ignored_symbols_are_transparent_to_context() {
    assert_eq!(derive("#ignore: +-\naxiom: A+-B\nA < B -> X", 1), "A+-X");
    assert_eq!(derive("axiom: A+-B\nA < B -> X", 1), "A+-B");
}

#[test]
fn context_parameters_bind_in_order() {
    assert_eq!(
        derive(
            "axiom: A(1)B(2)C(3)\nA(x) < B(y) > C(z) -> B(x*100+y*10+z)",
            1
        ),
        "A(1)B(123)C(3)"
    );
}

#[test]
fn age_symbol_records_generation() {
    assert_eq!(derive("axiom: A\nA -> B(#)A", 3), "B(1)B(2)B(3)A");
}

#[test]
fn cut_removes_rest_of_branch() {
    assert_eq!(derive("axiom: F[A]F\nA -> X%YZ", 1), "F[X]F");
    assert_eq!(derive("axiom: F[A[B]C]F\nA -> %", 1), "F[]F");
    assert_eq!(derive("axiom: FA[B]C\nA -> %", 1), "F");
}

#[test]
fn first_matching_deterministic_production_wins() {
    let src = "axiom: A(5)\nA(x) : x > 3 -> B\nA(x) : x > 1 -> C\nA(x) -> D";
    assert_eq!(derive(src, 1), "B");
    assert_eq!(
        derive("axiom: A(2)\nA(x) : x > 3 -> B\nA(x) : x > 1 -> C", 1),
        "C"
    );
    assert_eq!(derive("axiom: A(0)\nA(x) : x > 3 -> B", 1), "A(0)");
}

#[test]
fn productions_match_on_parameter_count() {
    assert_eq!(
        derive("axiom: A A(1) A(1,2)\nA(x) -> B", 1),
        "AB A(1,2)".replace(' ', "")
    );
}

#[test]
fn choice_extension_picks_alternatives() {
    assert_eq!(derive("axiom: A\nA -> ?(1)<X><Y>", 1), "X");
    assert_eq!(derive("axiom: A\nA -> ?(0)<X><Y(2)>", 1), "Y(2)");
    let w = derive(
        &format!("axiom: {}\nA -> ?(0.5)<X><Y>", "A".repeat(2000)),
        1,
    );
    let xs = w.chars().filter(|&c| c == 'X').count();
    assert!((800..1200).contains(&xs), "{xs} of 2000");
}

#[test]
fn functions_and_operators_evaluate() {
    let w = derive(
        "axiom: A(2)\nA(x) -> B(x^3, -x^2, min(x,1), max(x,3), abs(-x), floor(2.7), ceil(2.1), sqrt(16), (x>1)&&(x<3), !(x==2), x!=2 || 0, atan2(0,1), exp(0), log(1))",
        1,
    );
    assert_eq!(w, "B(8,-4,1,3,2,2,3,4,1,0,0,0,1,0)");
}

#[test]
fn random_functions_stay_in_range_and_follow_seed() {
    let g = LSystem::parse("axiom: A\nA -> A B(uniform(2,3)) C(ran(5))").unwrap();
    let w = g.derive(50, 9).unwrap();
    for m in w.iter() {
        match m.symbol {
            'B' => assert!((2.0..3.0).contains(&m.params[0])),
            'C' => assert!((0.0..5.0).contains(&m.params[0])),
            _ => {}
        }
    }
    assert_eq!(w, g.derive(50, 9).unwrap());
    assert_ne!(w, g.derive(50, 10).unwrap());
}

#[test]
fn explosive_growth_fails_fast_with_a_clear_error() {
    let g = LSystem::parse("axiom: F\nF -> FF").unwrap();
    let err = g.derive(64, 0).unwrap_err();
    assert!(matches!(err, DeriveError::TooManyModules { .. }), "{err}");
    assert!(err.to_string().contains("limit of 10000000 modules"));
    let small = Limits::default().with_max_modules(100);
    assert_eq!(
        g.derive_with(10, 0, &small).unwrap_err(),
        DeriveError::TooManyModules {
            generation: 7,
            limit: 100
        }
    );
    let params = LSystem::parse("axiom: F(1)\nF(x) -> F(x)F(x)").unwrap();
    assert!(matches!(
        params.derive_with(10, 0, &Limits::default().with_max_params(50)),
        Err(DeriveError::TooManyParams { .. })
    ));
    assert!(matches!(
        g.derive_with(5, 0, &Limits::default().with_max_generations(4)),
        Err(DeriveError::TooManyGenerations {
            requested: 5,
            limit: 4
        })
    ));
}

#[test]
fn non_finite_parameters_are_reported() {
    let g = LSystem::parse("axiom: A(1)\nA(x) -> A(x/0)").unwrap();
    assert!(matches!(
        g.derive(1, 0),
        Err(DeriveError::NonFiniteParameter { symbol, .. }) if symbol == "A"
    ));
}

#[test]
fn parse_errors_name_line_column_and_expectation() {
    let cases: &[(&str, usize, usize, &str)] = &[
        ("A -> B", 1, 1, "no axiom"),
        ("axiom: A\nA -> B(", 2, 8, "expected a number"),
        ("axiom: A\nA(x) -> B(y)", 2, 11, "unknown name 'y'"),
        ("axiom: A\nA -> B(foo(1))", 2, 8, "unknown function"),
        ("axiom: A\nA -> B(sin(1,2))", 2, 8, "takes 1 argument"),
        ("axiom: A\n#bogus", 2, 2, "unknown directive"),
        ("axiom: A\naxiom: B", 2, 1, "second axiom"),
        (
            "axiom: A\n  A  B",
            2,
            7,
            "expected '->' after the predecessor",
        ),
        ("axiom: A\n[ -> C", 2, 1, "cannot be '[' or ']' alone"),
        ("axiom: A\nA : x > 1 -> B", 2, 5, "unknown name 'x'"),
        ("axiom: A /* never closed", 1, 10, "never closed"),
        ("axiom: A\nA(x,x) -> B", 2, 5, "named twice"),
        ("axiom: A\nA -> B : -1", 2, 10, "probability"),
        ("axiom: A\nA -> ?(0.5)<B>", 2, 15, "'<' to open"),
        ("axiom: A\nA -> B(1e999)", 2, 8, "not a finite number"),
    ];
    for &(src, line, col, needle) in cases {
        let err = LSystem::parse(src).unwrap_err();
        assert_eq!(
            (err.location.line, err.location.column),
            (line, col),
            "{src:?}: {err}"
        );
        assert!(err.message.contains(needle), "{src:?}: {err}");
    }
}

#[test]
fn abop_notation_with_labels_and_star_conditions_parses() {
    let g = LSystem::parse("ω: A(1)\np1: A(l) : * → F(l)A(l+1)\n// a comment line\n/* block */")
        .unwrap();
    assert_eq!(g.derive(2, 0).unwrap().to_string(), "F(1)F(2)A(3)");
}

#[test]
fn every_preset_parses_derives_and_prints_back() {
    for p in PRESETS {
        let g = p.lsystem().unwrap_or_else(|e| panic!("{}: {e}", p.name));
        let w = g
            .derive(p.generations, 42)
            .unwrap_or_else(|e| panic!("{}: {e}", p.name));
        assert!(w.len() > 10, "{}", p.name);
        let reparsed = LSystem::parse(&g.to_string()).unwrap();
        assert_eq!(reparsed, g, "{}", p.name);
        assert_eq!(
            Word::parse(&w.to_string(), w.alphabet().clone()).unwrap(),
            w,
            "{}",
            p.name
        );
    }
}

#[test]
fn kenwood_leafy_tree_has_the_papers_shape() {
    let g = sylva_lsys::preset("kenwood-leafy")
        .unwrap()
        .lsystem()
        .unwrap();
    let w = g.derive(1, 0).unwrap().to_string();
    assert_eq!(w, "FF[&FL!A]////[^FL!A]/////[&FL!A]");
}

/// Found by the fuzzer: a successor `/` followed by `*` printed as a comment opener.
#[test]
fn slash_then_star_prints_back_without_opening_a_comment() {
    let g = LSystem::parse("axiom: / *\nA -> / * B").unwrap();
    let printed = g.to_string();
    assert_eq!(LSystem::parse(&printed).unwrap(), g, "{printed}");
}

/// Found by the fuzzer: ignore sets and contexts holding `/` and `*` printed as comments.
#[test]
fn slashes_in_ignore_sets_and_contexts_print_back() {
    let g = LSystem::parse("#ignore: / *\naxiom: A\n/ / < A > / * -> B").unwrap();
    let printed = g.to_string();
    assert_eq!(LSystem::parse(&printed).unwrap(), g, "{printed}");
}

/// cpfg's decomposition (Prusinkiewicz, Hanan and Mech, "An L-system-based plant modeling
/// language", 1999, section 3): a module standing for a structure is split into its parts
/// after every step, recursively, before the next step sees the word. Worked by hand: the
/// apex lays down a metamer `M(n)`, which decomposes into an internode and a node `N`, which
/// decomposes into a leaf and a bud.
#[test]
fn decomposition_splits_modules_after_every_step() {
    let src = "axiom: A(1)
        A(n) -> M(n) A(n+1)
        #decomposition depth 2
        M(n) -> I(n) N
        N -> [L][B]";
    assert_eq!(derive(src, 0), "A(1)");
    assert_eq!(derive(src, 1), "I(1)[L][B]A(2)");
    assert_eq!(derive(src, 2), "I(1)[L][B]I(2)[L][B]A(3)");
    // The axiom is decomposed too.
    let axiom = "axiom: M(0)\nA -> A\n#decomposition depth 2\nM(n) -> I(n) N\nN -> [L]";
    assert_eq!(derive(axiom, 0), "I(0)[L]");
}

/// A decomposition that would need more passes than its maximum depth is an error, not a
/// silent truncation and never a hang.
#[test]
fn decomposition_beyond_its_depth_is_an_error() {
    let g =
        LSystem::parse("axiom: A\nA -> A\n#decomposition depth 3\nA -> B\nB -> C\nC -> D\nD -> E")
            .unwrap();
    let err = g.derive(1, 0).unwrap_err();
    // The fourth pass would still fire D -> E, at line 7 of the text.
    assert!(
        matches!(
            err,
            DeriveError::TooDeep {
                section: "decomposition",
                depth: 3,
                generation: 0,
                at: Some(sylva_lsys::Location { line: 7, column: 1 }),
            }
        ),
        "{err}"
    );
    assert!(err.to_string().contains("line 7, column 1"), "{err}");
    // Endless recursion ends at the depth too.
    let endless = LSystem::parse("axiom: A\n#decomposition depth 100\nA -> AA").unwrap();
    assert!(matches!(
        endless.derive(0, 0),
        Err(DeriveError::TooDeep { depth: 100, .. }) | Err(DeriveError::TooManyModules { .. })
    ));
}

/// The homomorphism changes what is drawn, never what develops: derived words keep their
/// modules, and `interpretation` maps them recursively (ABOP's interpretation rules; cpfg's
/// `homomorphism` with `maximum depth`).
#[test]
fn homomorphism_rewrites_for_interpretation_only() {
    let src = "axiom: A(2)
        A(n) -> I(n) A(n+1)
        #homomorphism depth 4
        I(n) -> C(n, 2)
        C(l, k) : k > 0 -> F(l) C(l, k - 1)
        C(l, k) : k <= 0 ->";
    let g = LSystem::parse(src).unwrap();
    let word = g.derive(2, 0).unwrap();
    assert_eq!(word.to_string(), "I(2)I(3)A(4)");
    assert_eq!(
        g.interpretation(&word, 0).unwrap().to_string(),
        "F(2)F(2)F(3)F(3)A(4)"
    );
    // I -> C(n,2) -> F C(n,1) -> F F C(n,0) -> F F: four passes; three are too few.
    let shallow = LSystem::parse(&src.replace("depth 4", "depth 3")).unwrap();
    assert!(matches!(
        shallow.interpretation(&word, 0),
        Err(DeriveError::TooDeep { depth: 3, .. })
    ));
    // A grammar without a homomorphism draws its word as it is.
    let plain = LSystem::parse("axiom: F+F").unwrap();
    let w = plain.derive(0, 0).unwrap();
    assert_eq!(plain.interpretation(&w, 0).unwrap(), w);
}

/// Sections print and parse back to the same system.
#[test]
fn rule_sets_round_trip_through_text() {
    let src = "#define D 4
        axiom: A(1)
        A(n) -> M(n) A(n+1)
        #decomposition depth D
        M(n) : n > 1 -> I(n) [L]
        #homomorphism depth 2
        I(n) -> F(n)
        L -> +F";
    let g = LSystem::parse(src).unwrap();
    assert_eq!(g.decomposition().max_depth, 4);
    assert_eq!(g.homomorphism().productions.len(), 2);
    let printed = g.to_string();
    assert!(printed.contains("#decomposition depth 4"), "{printed}");
    let again = LSystem::parse(&printed).unwrap();
    assert_eq!(again, g);
}

/// Module names of several characters (L-Py's `module Apex`, cpfg's `@Gs`): declared with
/// `#module`, read by the longest declared name, printed with spaces between modules, and
/// parsed back.
#[test]
fn long_module_names_derive_and_round_trip() {
    let src = "#module Apex Internode In
        axiom: Apex(1)
        Apex(n) : n < 3 -> Internode(n) [+ Apex(n+1)] In Apex(n+1)";
    let g = LSystem::parse(src).unwrap();
    let w = g.derive(1, 0).unwrap();
    assert_eq!(w.to_string(), "Internode(1) [ + Apex(2) ] In Apex(2)");
    assert_eq!(w.iter().next().unwrap().name, "Internode");
    let again = LSystem::parse(&g.to_string()).unwrap();
    assert_eq!(again, g);
    assert_eq!(
        Word::parse(&w.to_string(), g.alphabet().clone()).unwrap(),
        w
    );
    // Without the declaration the same text is one-character modules.
    let short = LSystem::parse("axiom: Apex").unwrap();
    assert_eq!(short.axiom().len(), 4);
    // Names must be names.
    let err = LSystem::parse("#module A(b)\naxiom: A").unwrap_err();
    assert_eq!((err.location.line, err.location.column), (1, 9));
}

/// Statement blocks (cpfg's C-like blocks, sylva's notation too): a block before the
/// condition may change the production's own parameters, a block after it sets block
/// variables the successor reads, and `#start` runs before the derivation. Worked by hand:
/// the counter c goes 10, 11, 12 and the apex reads it each step.
#[test]
fn statement_blocks_run_around_conditions_and_derivations() {
    let src = "#start { c = 10; }
        axiom: A(0)
        A(n) : { n = n + 2; } n < 5 { c = c + 1; } -> B(n, c) A(n)";
    let g = LSystem::parse(src).unwrap();
    assert!(g.globals().contains(&"c".to_string()));
    assert_eq!(g.derive(1, 0).unwrap().to_string(), "B(2,11)A(2)");
    assert_eq!(g.derive(2, 0).unwrap().to_string(), "B(2,11)B(4,12)A(4)");
    // n becomes 6: the condition fails and A(4) is copied unchanged.
    assert_eq!(g.derive(3, 0).unwrap().to_string(), "B(2,11)B(4,12)A(4)");
    // Loops and branches; the grammar prints back to itself.
    let loops = "axiom: A(5)
        A(n) : { s = 0; k = 0; while (k < n) { s = s + k; k = k + 1; } if (s > 9) { s = -s; } else { s = 0; } } * -> S(s)";
    let g = LSystem::parse(loops).unwrap();
    assert_eq!(g.derive(1, 0).unwrap().to_string(), "S(-10)");
    assert_eq!(LSystem::parse(&g.to_string()).unwrap(), g);
}

/// A block that never ends is an error after MAX_BLOCK_STATEMENTS, never a hang.
#[test]
fn endless_blocks_are_errors() {
    let g = LSystem::parse("axiom: A\nA : { k = 0; while (1) { k = k + 1; } } * -> B").unwrap();
    let err = g.derive(1, 0).unwrap_err();
    assert!(
        matches!(
            err,
            DeriveError::EndlessBlock {
                generation: 1,
                at: Some(sylva_lsys::Location { line: 2, column: 1 }),
                ..
            }
        ),
        "{err}"
    );
}

/// cpfg's blocks as vlab models write them: over several lines, `Start:` and a parameter
/// changed before the condition (Lychnis's S(x_rel, x_max)).
#[test]
fn cpfg_blocks_over_several_lines() {
    let src = "#define N 4
        Lsystem: 1
        derivation length: 1
        Start: { total = 0;
                 step = 1/N; }
        Axiom: S(0, 2)
        S(x, m) : { x = x + step;
                    total = total + 1; } x <= 1 -->
            f(m/N) S(x, m)
        S(x, m) : x > 1 --> *
        endlsystem";
    let g = LSystem::parse_dialect(src, sylva_lsys::Dialect::Cpfg).unwrap();
    assert_eq!(g.derive(1, 0).unwrap().to_string(), "f(0.5)S(0.25,2)");
}

/// C's conditional `c ? a : b`, `%` and `fabs`, as cpfg models write them.
#[test]
fn conditional_remainder_and_fabs_evaluate() {
    let g = LSystem::parse(
        "axiom: A(7)\nA(x) -> B(x > 5 ? 1 : 2, x % 4, fabs(0 - x), x < 5 ? 1 : x < 9 ? 2 : 3)",
    )
    .unwrap();
    assert_eq!(g.derive(1, 0).unwrap().to_string(), "B(1,3,7,2)");
    // It prints as select(...), which reads back the same.
    let again = LSystem::parse(&g.to_string()).unwrap();
    assert_eq!(again.derive(1, 0).unwrap(), g.derive(1, 0).unwrap());
}

/// Blocks that each end but together would run for ever stop at the derivation's budget.
#[test]
fn block_statements_are_bounded_per_derivation() {
    let g = LSystem::parse("axiom: A\nA : { k = 0; while (k < 200000) { k = k + 1; } } * -> AA")
        .unwrap();
    let limits = Limits::DEFAULT.with_max_statements(5_000_000);
    assert!(matches!(
        g.derive_with(10, 0, &limits),
        Err(DeriveError::TooManyStatements {
            limit: 5_000_000,
            ..
        })
    ));
}

/// Found by fuzzing: a cpfg production for the width module '#' prints back readably.
#[test]
fn a_production_for_cpfg_width_prints_back() {
    let g = LSystem::parse("Lsystem: 1\nAxiom: L\nL --> +L#\n# --> -L\nendlsystem").unwrap();
    let again = LSystem::parse(&g.to_string()).unwrap();
    assert_eq!(
        again.derive(2, 0).unwrap().to_string(),
        g.derive(2, 0).unwrap().to_string()
    );
}

/// L-Py's declarative subset: modules of several characters, constants, sections and
/// Python operators; Python code is refused at its line and column, never misread.
#[test]
fn lpy_declarative_models_load_and_python_is_refused() {
    let src = "# A branching apex
module Apex, Internode(l)
ratio = 0.5 ** 2
Axiom: Apex(1)
derivation length: 2
production:
Apex(x) --> Internode(x) [+Apex(x*ratio)] Apex(x + 1 if False else x)
interpretation:
Internode(l) --> F(l)
endlsystem
";
    let refused = LSystem::parse_dialect(src, sylva_lsys::Dialect::LPy).unwrap_err();
    // Python's conditional expression is Python code sylva does not read.
    assert_eq!(refused.location.line, 7, "{refused}");
    let src = src.replace("Apex(x + 1 if False else x)", "Apex(x + (1 and 0))");
    let g = LSystem::parse_dialect(&src, sylva_lsys::Dialect::LPy).unwrap();
    assert_eq!(g.derivation_length(), Some(2));
    let word = g.derive(1, 0).unwrap();
    assert_eq!(word.to_string(), "Internode(1) [ + Apex(0.25) ] Apex(1)");
    assert_eq!(
        g.interpretation(&word, 0).unwrap().to_string(),
        "F(1) [ + Apex(0.25) ] Apex(1)"
    );
    for (python, line) in [
        ("import math\nAxiom: A\n", 1),
        ("Axiom: A\nproduction:\nA :\n  produce B\n", 3),
        ("def f(x):\n  return x\nAxiom: A\n", 1),
    ] {
        let err = LSystem::parse_dialect(python, sylva_lsys::Dialect::LPy).unwrap_err();
        assert!(err.message.starts_with("unsupported: Python code"), "{err}");
        assert_eq!(err.location.line, line, "{python}: {err}");
    }
}

/// cpfg's sub-L-systems: `?(id, scale) ... $` hands the modules between to L-system `id`,
/// whose productions rewrite them; the markers belong to the system around them. Worked by
/// hand: the main apex A makes a leaf L inside sub-L-system 2, where L grows as L -> LX;
/// outside it L is the main system's (L -> K).
#[test]
fn sub_lsystems_rewrite_their_own_modules() {
    let src = "Lsystem: 1
derivation length: 2
Axiom: A L
A --> F ?(2,0.5) L $ A
L --> K
endlsystem

Lsystem: 2
Axiom: L
L --> L X
endlsystem";
    let g = LSystem::parse(src).unwrap();
    assert_eq!(g.subsystems().len(), 1);
    assert_eq!(g.derive(1, 0).unwrap().to_string(), "F ?(2,0.5) L $ A K");
    assert_eq!(
        g.derive(2, 0).unwrap().to_string(),
        "F ?(2,0.5) L X $ F ?(2,0.5) L $ A K"
    );
    // In sylva's notation too (`#lsystem 2`): it prints back and derives the same words.
    let printed = g.to_string();
    assert!(printed.contains("#lsystem 2"), "{printed}");
    let again = LSystem::parse(&printed).unwrap();
    assert_eq!(again.subsystems().len(), 1);
    assert_eq!(
        again.derive(2, 0).unwrap().to_string(),
        g.derive(2, 0).unwrap().to_string()
    );
}

/// String predecessors (cpfg's `A B --> ...`), worked by hand: the modules must follow one
/// another, are matched left to right, and are rewritten together.
#[test]
fn string_predecessors_rewrite_their_modules_together() {
    let derive = |src: &str, n: u32| {
        LSystem::parse(src)
            .unwrap()
            .derive(n, 0)
            .unwrap()
            .to_string()
    };
    assert_eq!(derive("axiom: A B A B\nA B -> C", 1), "CC");
    // Left to right: the first two of three A are one match, the third stays.
    assert_eq!(derive("axiom: A A A\nA A -> B", 1), "BA");
    // Parameters bind in order: predecessor modules, then the right context.
    assert_eq!(
        derive("axiom: A(1) B(2) A(3)\nA(x) B(y) -> C(x+y)", 1),
        "C(3)A(3)"
    );
    assert_eq!(
        derive(
            "axiom: X(1) A(2) B(3) Y(4)\nX(a) < A(b) B(c) > Y(d) -> Z(a*1000+b*100+c*10+d)",
            1
        ),
        "X(1)Z(1234)Y(4)"
    );
    // Without its right context the string is left alone.
    assert_eq!(derive("axiom: X A B\nX < A B > Y -> Z", 1), "XAB");
    // Productions are tried in order: where the string does not follow, the next one fires.
    assert_eq!(derive("axiom: A B A\nA B -> C\nA -> D", 1), "CD");
    // cpfg's dialect reads them too, and printing gives a grammar that reads back the same.
    let cpfg = "Lsystem: 1\nderivation length: 2\naxiom: A B\nA B --> B A B\nB --> A\nendlsystem\n";
    let g = LSystem::parse_dialect(cpfg, sylva_lsys::Dialect::Cpfg).unwrap();
    // A B -> B A B; then B -> A, and "A B" -> "B A B": A + B A B.
    assert_eq!(g.derive(2, 0).unwrap().to_string(), "ABAB");
    let printed = LSystem::parse(&g.to_string()).unwrap();
    assert_eq!(printed.derive(2, 0).unwrap(), g.derive(2, 0).unwrap());
    assert_eq!(g.productions()[0].predecessor_rest.len(), 1);
}
