//! Known answers for cpfg's constructs beyond ABOP's notation, each worked by hand and read
//! back from sylva's notation: a section's maximum depth, `=` in right contexts, brackets in
//! string predecessors, `define:` arrays, `stop(n)`, the refused file functions and ring
//! L-systems.

use sylva_lsys::{Dialect, LSystem};

/// cpfg keeps a module that reaches its section's maximum depth as it is (drawn as it
/// stands, for a homomorphism); sylva's notation asks for that with `stop`, and prints it.
#[test]
fn a_section_that_stops_at_its_depth_keeps_the_modules_there() {
    // By hand: A -> B -> C in two passes; the third pass (C -> D) is beyond depth 2.
    let g =
        LSystem::parse("axiom: A\n#decomposition depth 2 stop\nA -> B\nB -> C\nC -> D").unwrap();
    assert_eq!(g.derive(0, 0).unwrap().to_string(), "C");
    let again = LSystem::parse(&g.to_string()).unwrap();
    assert_eq!(again.derive(0, 0).unwrap().to_string(), "C");
    assert!(g.to_string().contains("#decomposition depth 2 stop"));
    // The same in cpfg: F(l) --> @O F(l) recurses; at depth 1 one pass is made.
    let cpfg = LSystem::parse_dialect(
        "Lsystem: 1\nderivation length: 1\nAxiom: F(1)\nhomomorphism\nmaximum depth: 1\nF(l) --> G F(l)\nendlsystem",
        Dialect::Cpfg,
    )
    .unwrap();
    let word = cpfg.derive(1, 0).unwrap();
    assert_eq!(cpfg.interpretation(&word, 0).unwrap().to_string(), "GF(1)");
    // A word after 'depth N' other than 'stop' is an error at its place.
    let err = LSystem::parse("axiom: A\n#homomorphism depth 2 halt\nA -> B").unwrap_err();
    assert_eq!((err.location.line, err.location.column), (2, 23), "{err}");
}

/// cpfg's `=` in a right context skips to the end of the current branch (the pipe model's
/// `I > [I(w1)=][I(w2)=]I(w3)` sums the first module of each branch, whatever follows it).
#[test]
fn cpfg_equals_skips_to_the_end_of_a_branch() {
    let src = "Lsystem: 1\nderivation length: 1\nAxiom: I(0)[I(1)F][I(2)F F]I(4)\n\
               I(w) > [I(a)=][I(b)=]I(c) --> I(a+b+c)\nendlsystem";
    let g = LSystem::parse_dialect(src, Dialect::Cpfg).unwrap();
    // By hand: the first I sees 1, 2 and 4 past the rest of each branch: 7.
    assert_eq!(
        g.derive(1, 0).unwrap().to_string(),
        "I(7)[I(1)F][I(2)FF]I(4)"
    );
    // Printed in sylva's notation and read back, it derives the same.
    let again = LSystem::parse(&g.to_string()).unwrap();
    assert_eq!(again.derive(1, 0).unwrap(), g.derive(1, 0).unwrap());
    // A '=' with something other than ']' after it is refused at its context.
    let odd = "Lsystem: 1\nderivation length: 1\nAxiom: A B\nA > =B --> C\nendlsystem";
    let err = LSystem::parse_dialect(odd, Dialect::Cpfg).unwrap_err();
    assert!(err.to_string().contains("unsupported: '='"), "{err}");
    assert_eq!(err.location.line, 4, "{err}");
}

/// cpfg matches brackets in a string predecessor as they stand: a whole branch whose plant
/// is too old is removed (the Ecosystem model's `[f(y)-f(z)P(r)?E(x)] : ... --> *`).
#[test]
fn brackets_in_a_string_predecessor_are_matched_as_they_stand() {
    let src = "Lsystem: 1\nderivation length: 1\nAxiom: [fP(3)][fP(12)]F\n\
               [f P(r)] : r > 9 --> *\nendlsystem";
    let g = LSystem::parse_dialect(src, Dialect::Cpfg).unwrap();
    // By hand: the second branch's P is 12, over 9: the branch goes, the first stays.
    assert_eq!(g.derive(1, 0).unwrap().to_string(), "[fP(3)]F");
    let again = LSystem::parse(&g.to_string()).unwrap();
    assert_eq!(again.derive(1, 0).unwrap(), g.derive(1, 0).unwrap());
}

/// cpfg's `define:` arrays: values row-major with zeros after them, indices clamped to each
/// dimension, elements assigned in blocks; printed as `#array` and read back.
#[test]
fn cpfg_arrays_read_row_major_clamp_and_assign() {
    let src = "#define N 3\nLsystem: 1\nDefine: {\n\tarray len[2][N] = {1, 2, 3,\n\t\t4, 5}, w[2];\n}\n\
               Start: { w[1] = len[1][0] * 10; }\nderivation length: 1\nAxiom: A(1,1) A(0,2) A(1,7) A(-3,0) B\n\
               A(o,i) --> F(len[o][i])\nB --> F(w[1]) F(w[0])\nendlsystem";
    let g = LSystem::parse_dialect(src, Dialect::Cpfg).unwrap();
    // By hand: len is [[1,2,3],[4,5,0]]. len[1][1] = 5, len[0][2] = 3, len[1][7] clamps
    // to len[1][2] = 0 (no value given), len[-3][0] clamps to len[0][0] = 1; w[1] = 40.
    assert_eq!(
        g.derive(1, 0).unwrap().to_string(),
        "F(5)F(3)F(0)F(1)F(40)F(0)"
    );
    let printed = g.to_string();
    assert!(
        printed.contains("#array len[2][3] = {1, 2, 3, 4, 5}"),
        "{printed}"
    );
    let again = LSystem::parse(&printed).unwrap();
    assert_eq!(again.derive(1, 0).unwrap(), g.derive(1, 0).unwrap());
    // Wrong numbers of indices and sizes are errors at their place.
    let two = src.replace("F(len[o][i])", "F(len[o])");
    let err = LSystem::parse_dialect(&two, Dialect::Cpfg).unwrap_err();
    assert!(err.to_string().contains("takes 2 index(es)"), "{err}");
    let huge = src.replace("len[2][N]", "len[100000][N]");
    let err = LSystem::parse_dialect(&huge, Dialect::Cpfg).unwrap_err();
    assert!(err.to_string().contains("a constant from 1 to"), "{err}");
    assert_eq!(err.location.line, 4, "{err}");
}

/// cpfg's `stop(n)` ends the derivation after the step under way, unless `n` is 1;
/// its file functions are refused at their place, not mistaken for unknown names.
#[test]
fn cpfg_stop_ends_the_derivation_and_file_functions_are_refused() {
    let src = "Lsystem: 1\nderivation length: 10\nAxiom: A(0)\n\
               A(n) --> A(n+1) B(stop(n >= 3 ? 0 : 1))\nendlsystem";
    let g = LSystem::parse_dialect(src, Dialect::Cpfg).unwrap();
    // By hand: steps 1 to 3 call stop(1) (n = 0, 1, 2); step 4 calls stop(0) with n = 3
    // and is the last of the ten asked for.
    assert_eq!(g.derive(10, 0).unwrap().to_string(), "A(4)B(0)B(1)B(1)B(1)");
    // A stop in the first step ends there too.
    let first = LSystem::parse_dialect(&src.replace("n >= 3", "n >= 0"), Dialect::Cpfg).unwrap();
    assert_eq!(first.derive(10, 0).unwrap().to_string(), "A(1)B(0)");
    let files = "Lsystem: 1\nStart: { f = fopen(\"out.txt\", \"w\"); }\nderivation length: 1\n\
                 Axiom: A\nendlsystem";
    let err = LSystem::parse_dialect(files, Dialect::Cpfg).unwrap_err();
    assert!(
        err.to_string()
            .contains("unsupported: cpfg's file function 'fopen'"),
        "{err}"
    );
    assert_eq!((err.location.line, err.location.column), (2, 14), "{err}");
}

/// vlab's Ring model: a decomposition lays out 31 B and one A in a ring, and the A passes
/// round it, one place a step, leftward or rightward as `dir` says; past the word's end it
/// comes back at its start.
#[test]
fn a_ring_lsystem_passes_its_signal_round() {
    let ring = |dir: u32| {
        format!(
            "#define dir {dir}\n#define NR 8\nLsystem: 0\nring lsystem\nderivation length: 1\n\
             Axiom: X(NR)\nA < B : dir==0 --> A\nB > A : dir==1 --> A\nA --> B\n\
             decomposition\nmaximum depth: 100\nX(n) : n>1 --> X(n-1)B\nX(n) : n==1 --> A\nendlsystem\n"
        )
    };
    let forward = LSystem::parse_dialect(&ring(0), Dialect::Cpfg).unwrap();
    assert!(forward.is_ring());
    // The axiom decomposes to A B B B B B B B; by hand each step moves the A one place
    // right, and the eighth brings it back.
    assert_eq!(forward.derive(0, 0).unwrap().to_string(), "ABBBBBBB");
    assert_eq!(forward.derive(1, 0).unwrap().to_string(), "BABBBBBB");
    assert_eq!(forward.derive(7, 0).unwrap().to_string(), "BBBBBBBA");
    assert_eq!(forward.derive(8, 0).unwrap().to_string(), "ABBBBBBB");
    // With dir 1 the A moves left: from the first place to the last at once (its right
    // context wraps from the end of the word).
    let back = LSystem::parse_dialect(&ring(1), Dialect::Cpfg).unwrap();
    assert_eq!(back.derive(1, 0).unwrap().to_string(), "BBBBBBBA");
    // Printed in sylva's notation with #ring, it reads back and derives the same.
    let printed = forward.to_string();
    assert!(printed.contains("#ring"), "{printed}");
    let again = LSystem::parse(&printed).unwrap();
    assert_eq!(again.derive(5, 0).unwrap(), forward.derive(5, 0).unwrap());
}

/// The ring joins the word's ends only: a context walk from inside a branch still ends at
/// the branch's `]`, and a walk that goes all the way round without a match fails.
#[test]
fn a_ring_joins_the_ends_of_the_word_only() {
    // B's right context: in the branch, `]` comes first (no match); at the top level the
    // walk wraps past the end to the first module, A.
    let g = LSystem::parse("#ring\naxiom: A[B]B\nB > A -> C").unwrap();
    assert_eq!(g.derive(1, 0).unwrap().to_string(), "A[B]C");
    // Nothing matches round the whole ring: the walk ends after one turn (no hang).
    let none = LSystem::parse("#ring\naxiom: BBB\nA < B -> C\nB > A -> C").unwrap();
    assert_eq!(none.derive(3, 0).unwrap().to_string(), "BBB");
    // A ring of one module is its own neighbour.
    let one = LSystem::parse("#ring\naxiom: A\nA < A -> B").unwrap();
    assert_eq!(one.derive(1, 0).unwrap().to_string(), "B");
    // #ring takes nothing after it.
    let err = LSystem::parse("#ring now\naxiom: A").unwrap_err();
    assert_eq!((err.location.line, err.location.column), (1, 7), "{err}");
}
