//! The properties the instancing method must have: assembled trees equal direct ones for
//! deterministic grammars, assembled trees are valid derivations for stochastic ones, the
//! budget holds, and the compact rewriting has the paper's distribution.

use std::collections::HashMap;

use proptest::prelude::*;
use sylva_instancing::internal::InstancingGrammar;
use sylva_instancing::{
    Assembler, CompactTree, HeroOptions, InstanceCache, InstancingError, Markers, REPEAT_PROBES,
    Similarity, build_cache,
};
use sylva_lsys::{LSystem, Word, preset};
use sylva_turtle::glam::Vec3;
use sylva_turtle::{BranchShape, MeshBuilder, TurtleOptions, interpret};

type Tri = [Vec3; 3];

fn direct_triangles(
    grammar: &LSystem,
    generations: u32,
    turtle: &TurtleOptions,
    root: &Similarity,
) -> Vec<Tri> {
    let word = grammar.derive(generations, 0).unwrap();
    let mut b = MeshBuilder::new(turtle);
    interpret(&word, turtle, &mut b).unwrap();
    b.mesh.triangles(&root.to_affine()).collect()
}

fn assembled_triangles(cache: &InstanceCache, tree: &CompactTree) -> Vec<Tri> {
    let mut out = Vec::new();
    Assembler::new()
        .expand_with(cache, tree, |i, t| {
            let inst = &cache.instances[i as usize];
            let ranges = [(&cache.bark, inst.bark), (&cache.leaves, inst.leaves)];
            for (indices, span) in ranges {
                for tri in indices[span.range()].chunks_exact(3) {
                    out.push([0, 1, 2].map(|k| {
                        t.transform_point(Vec3::from(cache.vertices[tri[k] as usize].position))
                    }));
                }
            }
        })
        .unwrap();
    out
}

/// Whether two triangle soups are equal up to order, within `tol`, via a hash grid on centroids.
fn same_triangles(a: &[Tri], b: &[Tri], tol: f32) -> Result<(), String> {
    if a.len() != b.len() {
        return Err(format!("{} triangles against {}", a.len(), b.len()));
    }
    let cell = 0.05f32;
    let key = |t: &Tri| {
        let c = (t[0] + t[1] + t[2]) / 3.0 / cell;
        (c.x.floor() as i64, c.y.floor() as i64, c.z.floor() as i64)
    };
    let mut grid: HashMap<(i64, i64, i64), Vec<usize>> = HashMap::new();
    for (i, t) in b.iter().enumerate() {
        grid.entry(key(t)).or_default().push(i);
    }
    let mut used = vec![false; b.len()];
    for t in a {
        let (x, y, z) = key(t);
        let mut found = false;
        'search: for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    for &j in grid
                        .get(&(x + dx, y + dy, z + dz))
                        .map_or(&[][..], Vec::as_slice)
                    {
                        if !used[j] && (0..3).all(|k| t[k].distance(b[j][k]) <= tol) {
                            used[j] = true;
                            found = true;
                            break 'search;
                        }
                    }
                }
            }
        }
        if !found {
            return Err(format!("no match for triangle {t:?}"));
        }
    }
    Ok(())
}

fn deterministic_case(name: &str, grammar: LSystem, generations: u32, turtle: TurtleOptions) {
    for p in [0.0, 0.25, 0.5, 0.75, 1.0] {
        let options = HeroOptions::default()
            .with_budget(8 << 20)
            .with_generations(generations)
            .with_probability(p, p)
            .with_max_heroes(12)
            .with_turtle(turtle.clone());
        let built = build_cache(&grammar, &options).unwrap();
        for seed in 0..4u32 {
            let tree = CompactTree {
                position: [3.0, -1.0, 7.0],
                yaw: 0.7 * seed as f32,
                scale: 1.0 + 0.1 * seed as f32,
                seed,
                ..Default::default()
            };
            let direct = direct_triangles(&grammar, generations, &turtle, &tree.root());
            let assembled = assembled_triangles(&built.cache, &tree);
            same_triangles(&direct, &assembled, 2e-3)
                .unwrap_or_else(|e| panic!("{name}, P = {p}, seed {seed}: {e}"));
        }
    }
}

#[test]
fn deterministic_leafy_tree_assembles_to_the_direct_tree_for_every_probability() {
    let p = preset("kenwood-leafy").unwrap();
    deterministic_case(
        p.name,
        p.lsystem().unwrap(),
        4,
        TurtleOptions::for_preset(p).with_width(0.05),
    );
}

#[test]
fn deterministic_abop_plants_assemble_to_the_direct_plants() {
    for name in ["abop-1.24d", "abop-1.24e", "abop-1.24f"] {
        let p = preset(name).unwrap();
        deterministic_case(
            name,
            p.lsystem().unwrap(),
            5,
            TurtleOptions::for_preset(p).with_width(0.3),
        );
    }
}

/// Parameters that depend only on a branch's age keep (id, age) a faithful key, so a
/// parametric grammar assembles exactly too; frustum tubes and caps included.
#[test]
fn deterministic_parametric_tree_assembles_exactly_with_frustums_and_caps() {
    let grammar = LSystem::parse(
        "#define r 0.8\naxiom: !(1)A(2)\nA(l) -> !(l*0.5)F(l)[&(40)!(l*0.3)A(l*r)]/(120)[&(40)!(l*0.3)A(l*r)]/(120)F(l*0.5)A(l*r)",
    )
    .unwrap();
    let turtle = TurtleOptions::default()
        .with_shape(BranchShape::Frustum)
        .with_caps(true)
        .with_radial_segments(6);
    deterministic_case("parametric", grammar, 5, turtle);
}

/// Replaces each get-instance in `word` with the word of a randomly chosen candidate,
/// recursively, and drops the start/stop markers.
fn splice(
    word: &Word,
    cache: &InstanceCache,
    words: &[Word],
    markers: &Markers,
    rng: &mut u64,
    out: &mut String,
) {
    for m in word.iter() {
        if m.symbol == markers.start || m.symbol == markers.stop {
            continue;
        }
        if m.symbol == markers.get {
            let candidates = cache.lookup(m.params[0] as u32, m.params[1] as u32);
            assert!(!candidates.is_empty(), "exit without candidate");
            *rng = rng
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let pick = candidates[((*rng >> 33) % candidates.len() as u64) as usize];
            splice(&words[pick as usize], cache, words, markers, rng, out);
            continue;
        }
        out.push(m.symbol);
    }
}

/// Whether `word` can be derived from `symbol` in exactly `generations` rewrites of a context-free
/// non-parametric grammar (each module rewritten by one of its productions, or copied when it
/// has none). Dynamic programming over (position, symbol, generations) -> reachable end positions.
fn derivable(
    word: &[char],
    rules: &HashMap<char, Vec<Vec<char>>>,
    symbol: char,
    generations: u32,
) -> bool {
    fn ends(
        w: &[char],
        rules: &HashMap<char, Vec<Vec<char>>>,
        at: usize,
        s: char,
        k: u32,
        memo: &mut HashMap<(usize, char, u32), Vec<usize>>,
    ) -> Vec<usize> {
        if let Some(v) = memo.get(&(at, s, k)) {
            return v.clone();
        }
        let mut out = Vec::new();
        match rules.get(&s) {
            Some(succs) if k > 0 => {
                for succ in succs {
                    let mut positions = vec![at];
                    for &c in succ {
                        let mut next = Vec::new();
                        for &p in &positions {
                            for e in ends(w, rules, p, c, k - 1, memo) {
                                if !next.contains(&e) {
                                    next.push(e);
                                }
                            }
                        }
                        positions = next;
                    }
                    for p in positions {
                        if !out.contains(&p) {
                            out.push(p);
                        }
                    }
                }
            }
            _ => {
                if w.get(at) == Some(&s) {
                    out.push(at + 1);
                }
            }
        }
        memo.insert((at, s, k), out.clone());
        out
    }
    ends(word, rules, 0, symbol, generations, &mut HashMap::new()).contains(&word.len())
}

#[test]
fn stochastic_trees_assemble_into_valid_derivations() {
    let src = "axiom: A\nA -> F[+A][-A]A : 1\nA -> F[&B]A : 1\nA -> F : 0.3\nB -> F[^A]B : 1\nB -> FF : 1";
    let grammar = LSystem::parse(src).unwrap();
    let mut rules: HashMap<char, Vec<Vec<char>>> = HashMap::new();
    for line in src.lines().skip(1) {
        let (pred, rest) = line.split_once(" -> ").unwrap();
        let succ = rest.split(" : ").next().unwrap();
        rules
            .entry(pred.chars().next().unwrap())
            .or_default()
            .push(succ.chars().collect());
    }
    let generations = 4;
    let options = HeroOptions::default()
        .with_budget(1 << 20)
        .with_generations(generations)
        .with_probability(0.5, 0.9)
        .with_words(true)
        .with_max_heroes(40);
    let built = build_cache(&grammar, &options).unwrap();
    assert_eq!(built.words.len(), built.cache.instances.len());
    let markers = Markers::default();
    for seed in 0..40u64 {
        let roots = built.cache.lookup(0, 0);
        let root = &built.words[roots[seed as usize % roots.len()] as usize];
        let mut text = String::new();
        let mut rng = seed;
        splice(
            root,
            &built.cache,
            &built.words,
            &markers,
            &mut rng,
            &mut text,
        );
        // The whole-tree instance wraps the axiom in brackets; the tree itself is inside.
        let text = &text[1..text.len() - 1];
        let chars: Vec<char> = text.chars().collect();
        assert!(
            derivable(&chars, &rules, 'A', generations),
            "seed {seed}: {text} is not a derivation"
        );
    }
    // The checker itself rejects what the grammar cannot make.
    let chars = |s: &str| s.chars().collect::<Vec<_>>();
    assert!(derivable(&chars("F[+F][-F]F"), &rules, 'A', 2));
    assert!(!derivable(&chars("F[+F][-F]F"), &rules, 'A', 1));
    assert!(!derivable(&chars("F[+F]F"), &rules, 'A', 2));
}

#[test]
fn explicit_form_weights_sum_to_the_original_weights() {
    let g = LSystem::parse("axiom: A\nA -> F[+A][-A][+A] : 2\nA -> F[&A] : 1\nB -> [A]F").unwrap();
    let ig = InstancingGrammar::new(&g, Markers::default()).unwrap();
    let ex = ig.explicit(0.3).unwrap();
    let sum = |pred: char| -> f64 {
        let id = ex.alphabet().id(pred).unwrap();
        ex.productions()
            .iter()
            .filter(|p| p.predecessor.symbol == id)
            .map(|p| p.weight.unwrap_or(1.0))
            .sum()
    };
    assert!((sum('A') - 3.0).abs() < 1e-12);
    assert!((sum('B') - 1.0).abs() < 1e-12);
    assert_eq!(ex.productions().len(), 8 + 2 + 2);
    // [+A] appears twice in the first production and shares one id.
    assert_eq!(ig.branch_count(), 4);
}

#[test]
fn markers_already_in_the_grammar_are_refused() {
    let g = LSystem::parse("axiom: ◆\n◆ -> [◆]").unwrap();
    assert_eq!(
        InstancingGrammar::new(&g, Markers::default()).unwrap_err(),
        InstancingError::MarkerInUse('◆')
    );
}

#[test]
fn a_budget_too_small_for_one_tree_is_an_error() {
    let g = preset("kenwood-leafy").unwrap().lsystem().unwrap();
    let err = build_cache(
        &g,
        &HeroOptions::default().with_budget(1000).with_generations(5),
    )
    .unwrap_err();
    assert!(
        matches!(err, InstancingError::BudgetTooSmall { budget: 1000, .. }),
        "{err}"
    );
    assert!(build_cache(&g, &HeroOptions::default().with_budget(0)).is_err());
}

/// Outcome of one derivation step from the axiom: which of the three branches became exits.
fn outcome(word: &Word, get: char) -> usize {
    let mut mask = 0;
    let mut branch = 0;
    for m in word.iter() {
        if m.symbol == '⟦' && m.params[0] != 0.0 || m.symbol == get {
            if m.symbol == get {
                mask |= 1 << branch;
            }
            branch += 1;
        }
    }
    mask
}

/// The compact form (one choice per branch) and the paper's explicit 2^B form give the same
/// distribution over which branches are instanced. Chi-square with 7 degrees of freedom; the
/// critical value 24.32 has a false-alarm rate of 0.1 per cent. Seeds are fixed, so the test
/// is deterministic.
#[test]
fn compact_and_explicit_forms_have_the_same_distribution() {
    let g = LSystem::parse("axiom: A\nA -> F[+A][-A][&A]").unwrap();
    let ig = InstancingGrammar::new(&g, Markers::default()).unwrap();
    let p = 0.3;
    let compact = ig.compact(|_| sylva_lsys::Expr::Number(p)).unwrap();
    let explicit = ig.explicit(p).unwrap();
    let n = 8000;
    let mut counts = [[0f64; 8]; 2];
    for (k, g) in [&compact, &explicit].into_iter().enumerate() {
        for seed in 0..n {
            counts[k][outcome(&g.derive(1, seed).unwrap(), '◆')] += 1.0;
        }
    }
    let expected: Vec<f64> = (0..8u32)
        .map(|m| {
            n as f64 * p.powi(m.count_ones() as i32) * (1.0 - p).powi(3 - m.count_ones() as i32)
        })
        .collect();
    for (k, c) in counts.iter().enumerate() {
        let chi2: f64 = c
            .iter()
            .zip(&expected)
            .map(|(o, e)| (o - e) * (o - e) / e)
            .sum();
        assert!(
            chi2 < 24.32,
            "form {k}: {c:?} against {expected:?}, chi2 {chi2}"
        );
    }
    // Two-sample test between the forms.
    let chi2: f64 = (0..8)
        .map(|i| {
            let (a, b) = (counts[0][i], counts[1][i]);
            if a + b == 0.0 {
                0.0
            } else {
                (a - b) * (a - b) / (a + b)
            }
        })
        .sum();
    assert!(chi2 < 24.32, "forms differ: {counts:?}, chi2 {chi2}");
}

fn small_grammar() -> impl Strategy<Value = String> {
    let succ = prop::sample::select(vec![
        "F[+A]A",
        "F[-A][&A]",
        "FF",
        "F[A]",
        "F[+B]A",
        "F[J]A",
        "[^A]F",
    ]);
    (succ.clone(), succ.clone(), succ, 1u32..4, 1u32..4).prop_map(|(a, b, c, w1, w2)| {
        format!("axiom: FA\nA -> {a} : {w1}\nA -> {b} : {w2}\nB -> {c}\nF -> F")
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    #[test]
    fn the_budget_is_never_exceeded(src in small_grammar(), budget in 2_000usize..400_000, seed: u64, generations in 2u32..6) {
        let g = LSystem::parse(&src).unwrap();
        let options = HeroOptions::default().with_budget(budget).with_generations(generations).with_seed(seed).with_max_heroes(200);
        match build_cache(&g, &options) {
            Ok(built) => {
                prop_assert!(built.cache.bytes() <= budget, "{} > {budget}", built.cache.bytes());
                prop_assert_eq!(built.stats.bytes, built.cache.bytes());
                // Every exit of every instance can be filled.
                for e in &built.cache.exits {
                    prop_assert!(!built.cache.lookup(e.id, e.age).is_empty());
                }
            }
            Err(InstancingError::BudgetTooSmall { .. }) => {}
            Err(e) => prop_assert!(false, "{e}"),
        }
    }

    #[test]
    fn explicit_weights_sum_per_predecessor(src in small_grammar(), p in 0.0f64..=1.0) {
        let g = LSystem::parse(&src).unwrap();
        let ig = InstancingGrammar::new(&g, Markers::default()).unwrap();
        let ex = ig.explicit(p).unwrap();
        for pred in ['A', 'B'] {
            let id = g.alphabet().id(pred).unwrap();
            let before: f64 = g.productions().iter().filter(|q| q.predecessor.symbol == id).map(|q| q.weight.unwrap_or(1.0)).sum();
            let after: f64 = ex.productions().iter().filter(|q| q.predecessor.symbol == id).map(|q| q.weight.unwrap_or(1.0)).sum();
            prop_assert!((before - after).abs() < 1e-9, "{pred}: {before} vs {after}");
        }
    }
}

/// Kenwood's granularity: a tree is a few large instances (one crown plus whole branches),
/// and trees are varied: almost every tree's composition is its own.
#[test]
fn trees_are_few_large_instances_and_varied() {
    for (name, generations) in [("kenwood-leafy", 5), ("goe-random", 5), ("abop-honda", 7)] {
        let grammar = preset(name).unwrap().lsystem().unwrap();
        let options = HeroOptions::default()
            .with_budget(16 << 20)
            .with_generations(generations);
        let built = build_cache(&grammar, &options).unwrap();
        let mut assembler = Assembler::new();
        let mut compositions = HashMap::new();
        let mut placements = 0;
        for seed in 0..10_000 {
            let tree = CompactTree {
                scale: 1.0,
                seed,
                ..Default::default()
            };
            let placed = assembler
                .expand_with(&built.cache, &tree, |_, _| {})
                .unwrap();
            assert!(
                placed <= 1 + options.max_tree_exits as usize,
                "{name}: {placed} placements"
            );
            placements += placed;
            let c = assembler.composition(&built.cache, &tree).unwrap();
            *compositions.entry(c).or_insert(0) += 1;
        }
        let mean = placements as f64 / 10_000.0;
        let unique = compositions.values().filter(|&&n| n == 1).count();
        assert!(
            (2.0..=16.0).contains(&mean),
            "{name}: {mean} placements per tree"
        );
        assert!(
            unique >= 9_900,
            "{name}: {unique} of 10,000 compositions are unique"
        );
    }
}

/// An instance appears once per tree while its key has at least REPEAT_PROBES complete
/// candidates (the bound stated on [`REPEAT_PROBES`]).
#[test]
fn no_instance_repeats_within_a_crown() {
    let grammar = preset("goe-random").unwrap().lsystem().unwrap();
    let built = build_cache(
        &grammar,
        &HeroOptions::default()
            .with_budget(8 << 20)
            .with_generations(5),
    )
    .unwrap();
    let cache = &built.cache;
    let complete = |i: u32| {
        let inst = &cache.instances[i as usize];
        cache
            .lookup(inst.id, inst.age)
            .iter()
            .filter(|&&c| cache.instances[c as usize].exits.is_empty())
            .count()
    };
    let mut assembler = Assembler::new();
    let mut checked = 0;
    for seed in 0..2_000 {
        let tree = CompactTree {
            scale: 1.0,
            seed,
            ..Default::default()
        };
        let mut seen = Vec::new();
        assembler
            .expand_with(cache, &tree, |i, _| seen.push(i))
            .unwrap();
        for (k, &i) in seen.iter().enumerate().skip(1) {
            if complete(i) >= REPEAT_PROBES {
                assert!(!seen[..k].contains(&i), "tree {seed} repeats instance {i}");
                checked += 1;
            }
        }
    }
    assert!(
        checked > 1_000,
        "only {checked} placements had enough candidates to check"
    );
}
