//! Density management, seams, constraints, species files and bad input.

use sylva_testkit::{builder, plane, small_species};

use std::path::Path;

use proptest::prelude::*;
use sylva_forest::{
    Candidate, DensityModel, ForestBuilder, ForestConfig, ForestError, PatchDensity, PatchSpecies,
    Rect, Species,
};
use sylva_terrain::glam::Vec2;
use sylva_terrain::{DiamondSquare, HeightField};

/// A species of weight 1 with canopy radius `r`.
fn share(r: f32) -> PatchSpecies {
    PatchSpecies {
        canopy_radius: r,
        weight: 1.0,
    }
}

fn canopy_candidates(model: &PatchDensity, region: Rect, seed: u64) -> Vec<Candidate> {
    let mut out = Vec::new();
    model.candidates(region, seed, &mut out);
    out.retain(|c| !c.seedling);
    out
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    /// After the placement error is fixed no two canopy trees are closer than their spacing,
    /// and no patch holds more than one canopy tree.
    #[test]
    fn canopy_spacing_holds_after_the_fix(seed: u64, r1 in 2.0f32..10.0, r2 in 2.0f32..10.0, factor in 0.5f32..2.0) {
        let mut model = PatchDensity::new(vec![share(r1), share(r2)]);
        model.spacing_factor = factor;
        let region = Rect::new(Vec2::splat(-150.0), Vec2::splat(150.0));
        let trees = canopy_candidates(&model, region, seed);
        let radii = [r1, r2];
        for (i, a) in trees.iter().enumerate() {
            for b in &trees[i + 1..] {
                let spacing = (factor * radii[a.species].max(radii[b.species])).min(model.patch);
                prop_assert!(a.position.distance(b.position) >= spacing - 1e-3, "{:?} {:?}", a.position, b.position);
            }
        }
        let mut per_patch = std::collections::HashMap::new();
        for t in &trees {
            let key = ((t.position.x / model.patch).floor() as i64, (t.position.y / model.patch).floor() as i64);
            *per_patch.entry(key).or_insert(0) += 1;
        }
        prop_assert!(per_patch.values().all(|&n| n == 1));
        // Most patches keep their tree: the fix moves trees before it removes any. Spacing
        // near the patch size (factor near 2) leaves room for fewer.
        let patches = (300.0 / model.patch).powi(2);
        let floor = if factor <= 1.0 { 0.8 } else { 0.4 };
        prop_assert!(trees.len() as f32 > floor * patches, "{} trees in {patches} patches", trees.len());
    }
}

/// Seedlings survive with probability 1 - min(1, (r0 / d)^2) at distance d from the nearest
/// canopy tree. Over many patches, the survival fraction per distance band must follow it.
#[test]
fn seedlings_thin_out_near_canopy_trees() {
    let mut model = PatchDensity::new(vec![share(8.0)]);
    model.seedlings_per_patch = 40;
    model.seedling_clearance = 1.0;
    let region = Rect::new(Vec2::splat(0.0), Vec2::splat(800.0));
    let mut with = Vec::new();
    model.candidates(region, 5, &mut with);
    let canopy: Vec<Vec2> = with
        .iter()
        .filter(|c| !c.seedling)
        .map(|c| c.position)
        .collect();
    model.seedling_clearance = 0.0;
    let mut without = Vec::new();
    model.candidates(region, 5, &mut without);
    let nearest = |p: Vec2| {
        canopy
            .iter()
            .map(|c| c.distance(p))
            .fold(f32::INFINITY, f32::min)
    };
    // Same proposals either way (the draws are keyed by patch), so survival per band is
    // kept / proposed.
    let bands = [(0.0f32, 6.0f32), (6.0, 9.0), (9.0, 12.0), (12.0, 16.0)];
    for (lo, hi) in bands {
        let count = |v: &[Candidate]| {
            v.iter()
                .filter(|c| c.seedling)
                .filter(|c| (lo..hi).contains(&nearest(c.position)))
                .count() as f64
        };
        let (kept, proposed) = (count(&with), count(&without));
        // Expected survival: mean of 1 - (8/d)^2 over the band, for d uniform in area.
        let expected = {
            let n = 200;
            (0..n)
                .map(|k| lo + (hi - lo) * (k as f32 + 0.5) / n as f32)
                .map(|d| (1.0 - (8.0 / d).powi(2)).max(0.0) as f64 * f64::from(d))
                .sum::<f64>()
                / (0..n)
                    .map(|k| f64::from(lo + (hi - lo) * (k as f32 + 0.5) / n as f32))
                    .sum::<f64>()
        };
        let observed = kept / proposed;
        assert!(
            proposed > 200.0,
            "band {lo}..{hi}: only {proposed} proposals"
        );
        assert!(
            (observed - expected).abs() < 0.08,
            "band {lo}..{hi}: survival {observed:.3}, expected {expected:.3}"
        );
    }
}

#[test]
fn tiles_generated_apart_equal_the_area_generated_at_once() {
    let b = builder(3);
    let ground = plane(400.0);
    let whole = b.trees(&ground, Rect::new(Vec2::splat(-100.0), Vec2::splat(100.0)));
    let mut tiles = Vec::new();
    for (x, z) in [(-100.0, -100.0), (0.0, -100.0), (-100.0, 0.0), (0.0, 0.0)] {
        tiles.extend(b.trees(
            &ground,
            Rect::new(Vec2::new(x, z), Vec2::new(x + 100.0, z + 100.0)),
        ));
    }
    let key = |t: &sylva_instancing::CompactTree| {
        (t.position[0].to_bits(), t.position[2].to_bits(), t.seed)
    };
    let mut a: Vec<_> = whole.iter().map(key).collect();
    let mut b2: Vec<_> = tiles.iter().map(key).collect();
    a.sort_unstable();
    b2.sort_unstable();
    assert!(!a.is_empty());
    assert_eq!(a, b2);
}

#[test]
fn trees_stand_on_the_terrain_and_avoid_cliffs_and_heights() {
    let b = builder(4);
    let map = DiamondSquare::new(129)
        .with_spacing(2.0)
        .with_seed(2)
        .with_amplitude(60.0)
        .generate()
        .unwrap();
    let (lo, hi) = map.bounds();
    let trees = b.trees(&map, Rect::new(lo, hi));
    assert!(!trees.is_empty());
    for t in &trees {
        let [x, y, z] = t.position;
        assert!((y - map.height(x, z)).abs() < 1e-4);
        assert!(
            map.normal(x, z).y >= 35f32.to_radians().cos() - 1e-4,
            "tree on a cliff"
        );
        assert!((0.9..=1.1).contains(&t.scale));
    }
    // A height window and a mask both thin the forest.
    let mut config = ForestConfig::new(small_species());
    config.budget = 2 << 20;
    config.seed = 4;
    config.constraints.max_height = map.stats().mean;
    config.constraints.mask = Some(std::sync::Arc::new(
        |x: f32, _z: f32| if x < 128.0 { 0.0 } else { 1.0 },
    ));
    let limited = ForestBuilder::new(config)
        .unwrap()
        .trees(&map, Rect::new(lo, hi));
    assert!(limited.len() < trees.len());
    assert!(
        limited
            .iter()
            .all(|t| t.position[0] >= 128.0 && t.position[1] <= map.stats().mean)
    );
}

#[test]
fn a_terrain_without_room_gives_an_empty_forest() {
    let b = builder(1);
    // A wall: every sample is steeper than 35 degrees.
    let wall: Vec<f32> = (0..33 * 33).map(|i| (i % 33) as f32 * 5.0).collect();
    let wall = sylva_terrain::Heightmap::from_heights(33, 1.0, wall).unwrap();
    assert!(
        b.trees(&wall, Rect::new(Vec2::ZERO, Vec2::splat(32.0)))
            .is_empty()
    );
    // Empty and inverted regions, and regions off the terrain, are empty too.
    assert!(
        b.trees(&plane(10.0), Rect::new(Vec2::ZERO, Vec2::ZERO))
            .is_empty()
    );
    assert!(
        b.trees(&plane(10.0), Rect::new(Vec2::splat(5.0), Vec2::splat(-5.0)))
            .is_empty()
    );
    assert!(
        b.trees(
            &plane(10.0),
            Rect::new(Vec2::splat(100.0), Vec2::splat(200.0))
        )
        .is_empty()
    );
}

/// Issue 60: a 1 MB species name was copied into every node and mesh name (a 50 m forest
/// became a 1.24 GB GLB); names are bounded, refused with their line.
#[test]
fn long_species_names_are_refused_with_their_line() {
    let limit = sylva_forest::limits::MAX_SPECIES_NAME_CHARS;
    let text = format!("grammar: kenwood-leafy\nname: {}\n", "o".repeat(limit + 1));
    match Species::parse_file(&text, Path::new("long.species")) {
        Err(ForestError::SpeciesFile { line, message, .. }) => {
            assert_eq!(line, 2);
            assert!(
                message.contains(&format!("more than the limit of {limit}")),
                "{message}"
            );
        }
        other => panic!("{other:?}"),
    }
    let fits = format!("grammar: kenwood-leafy\nname: {}\n", "o".repeat(limit));
    assert!(Species::parse_file(&fits, Path::new("fits.species")).is_ok());
}

#[test]
fn species_files_report_file_line_and_column() {
    let file = Path::new("oak.species");
    let ok = Species::parse_file(
        "name: oak\ngrammar: kenwood-leafy\ngenerations: 4\nbark: 0.3 0.2 0.1\n",
        file,
    )
    .unwrap();
    assert_eq!((ok.name.as_str(), ok.generations), ("oak", 4));
    let err = |text: &str| match Species::parse_file(text, file) {
        Err(ForestError::SpeciesFile {
            line,
            column,
            message,
            ..
        }) => (line, column, message),
        other => panic!("{other:?}"),
    };
    assert_eq!(err("grammar: kenwood-leafy\ngenerations: many").0, 2);
    assert_eq!(err("grammar: kenwood-leafy\ngenerations: many").1, 14);
    assert!(
        err("grammar: kenwood-leafy\nbark: 2 0 0")
            .2
            .contains("three numbers")
    );
    assert!(
        err("grammar: kenwood-leafy\ncolour: red")
            .2
            .contains("unknown key")
    );
    assert!(
        err("grammar: kenwood-leafy\nno colon here")
            .2
            .contains("key: value")
    );
    assert!(err("name: x").2.contains("missing 'grammar:'"));
    // Leaf and bark looks: unknown textures and out-of-range facing name their place.
    assert_eq!(
        err("grammar: kenwood-leafy\nleaf_shape: fern"),
        (
            2,
            13,
            "leaf_shape must be 'broadleaf', 'lobed', 'serrated', 'needles', 'needle-tuft', 'rounded', 'deltoid', 'palmate' or 'pine-shoot', not 'fern'"
                .into()
        )
    );
    assert_eq!(err("grammar: kenwood-leafy\nbark_texture: velvet").0, 2);
    assert_eq!(
        err("grammar: kenwood-leafy\nleaf_facing: 1.5"),
        (
            2,
            14,
            "leaf_facing must be a number from 0 to 1, not '1.5'".into()
        )
    );
    let facing = Species::parse_file("grammar: kenwood-leafy\nleaf_facing: 0.25", file).unwrap();
    assert_eq!(facing.turtle.leaf_facing, 0.25);
    let flared = Species::parse_file("grammar: kenwood-leafy\nroot_flare: 0.6", file).unwrap();
    assert_eq!(flared.turtle.root_flare, 0.6);
    assert_eq!(err("grammar: kenwood-leafy\nroot_flare: 9").0, 2);
    // A grammar file with an error is reported in that file's terms.
    let dir = std::env::temp_dir().join("sylva-species");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("bad.lsys"), "axiom: A\nA -> B(").unwrap();
    match Species::parse_file("grammar: bad.lsys", &dir.join("x.species")) {
        Err(ForestError::SpeciesFile {
            file, line, column, ..
        }) => {
            assert!(file.ends_with("bad.lsys"));
            assert_eq!((line, column), (2, 8));
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn impossible_configurations_are_errors() {
    assert!(ForestBuilder::new(ForestConfig::new(Vec::new())).is_err());
    let mut zero_budget = ForestConfig::new(small_species());
    zero_budget.budget = 0;
    assert!(ForestBuilder::new(zero_budget).is_err());
    // A budget too small for one hero is raised to one hero per species and form (issue
    // 51: a small forest's budget, sized to its trees, is smaller than its heroes).
    let mut tiny = ForestConfig::new(small_species());
    tiny.budget = 100;
    let tiny = ForestBuilder::new(tiny).expect("one hero per form");
    assert!(tiny.stats().heroes as usize >= tiny.variants().len());
    assert!(
        tiny.variants()
            .iter()
            .all(|v| !v.cache.instances.is_empty())
    );
    let mut no_weight = ForestConfig::new(small_species());
    no_weight.species.iter_mut().for_each(|s| s.weight = 0.0);
    assert!(ForestBuilder::new(no_weight).is_err());
}

/// Large regions are processed in blocks of patches; the trees must not depend on it.
#[test]
fn large_regions_in_blocks_equal_small_tiles() {
    let mut model = PatchDensity::new(vec![share(0.5)]);
    model.seedlings_per_patch = 1;
    let whole_region = Rect::new(Vec2::ZERO, Vec2::splat(300.0));
    let mut whole = Vec::new();
    model.candidates(whole_region, 9, &mut whole);
    let mut tiles = Vec::new();
    for i in 0..4 {
        for j in 0..4 {
            let min = Vec2::new(i as f32, j as f32) * 75.0;
            model.candidates(Rect::new(min, min + Vec2::splat(75.0)), 9, &mut tiles);
        }
    }
    let key = |c: &Candidate| (c.position.x.to_bits(), c.position.y.to_bits(), c.key);
    let mut a: Vec<_> = whole.iter().map(key).collect();
    let mut b: Vec<_> = tiles.iter().map(key).collect();
    a.sort_unstable();
    b.sort_unstable();
    assert!(a.len() > 50_000);
    assert_eq!(a, b);
}

/// More species than the density model was told of, or a model edited to fewer species, must
/// never index out of bounds: the species list pairs each radius with its weight.
#[test]
fn density_species_come_in_pairs() {
    let mut model = PatchDensity::new(vec![share(3.0), share(5.0)]);
    model.species.truncate(1);
    let mut out = Vec::new();
    model.candidates(Rect::new(Vec2::ZERO, Vec2::splat(100.0)), 3, &mut out);
    assert!(out.iter().all(|c| c.species == 0));
    model.species.clear();
    out.clear();
    model.candidates(Rect::new(Vec2::ZERO, Vec2::splat(100.0)), 3, &mut out);
    assert!(out.is_empty());
}

/// Found in review: a species file naming `grammar: /dev/zero` made the forest example read
/// until it was killed (21 GB resident after 60 s).
#[test]
#[cfg(unix)]
fn a_grammar_path_to_an_endless_device_is_an_error() {
    let err =
        Species::parse_file("grammar: /dev/zero\n", Path::new("/tmp/zero.species")).unwrap_err();
    let ForestError::SpeciesFile {
        line,
        column,
        message,
        ..
    } = err
    else {
        panic!("{err}");
    };
    assert_eq!((line, column), (1, 10));
    assert!(
        message.contains("a device, not a regular file"),
        "{message}"
    );
}

/// Hostile species files end in an error with a place, or in a species; never a panic.
#[test]
fn hostile_species_files() {
    let file = Path::new("hostile.species");
    // A name is bounded (issue 60): a megabyte of it is refused, not copied into files.
    let long_value = format!("grammar: kenwood-leafy\nname: {}\n", "x".repeat(1 << 20));
    assert!(Species::parse_file(&long_value, file).is_err());
    let many_keys = "grammar: kenwood-leafy\n".to_string() + &"weight: 1\n".repeat(100_000);
    assert!(Species::parse_file(&many_keys, file).is_ok());
    assert!(Species::parse_file("\u{feff}grammar: kenwood-leafy\n", file).is_ok());
    for (text, line) in [
        ("grammar: kenwood-leafy\nweight: NaN\n", 2),
        ("grammar: kenwood-leafy\nweight: inf\n", 2),
        ("grammar: kenwood-leafy\nbark: 1 2\n", 2),
        ("grammar: kenwood-leafy\ngenerations: 99999999999\n", 2),
        ("grammar: kenwood-leafy\nleaf_size: -1 -1\n", 2),
        ("grammar: kenwood-leafy\nleaf_shape: maple\n", 2),
        ("grammar: kenwood-leafy\nbark_texture: mossy\n", 2),
        ("grammar: \u{0}\n", 1),
        ("\u{feff}grammar: kenwood-leafy\nnonsense\n", 2),
        ("\u{feff}\u{feff}grammar: kenwood-leafy\n", 1),
    ] {
        match Species::parse_file(text, file) {
            Err(ForestError::SpeciesFile { line: l, .. }) => assert_eq!(l, line, "{text:?}"),
            other => panic!("{text:?}: {other:?}"),
        }
    }
}

/// Tropism reaches the forest: presets keep their published tropism, species files may set
/// their own, and a bad one is an error at its place.
#[test]
fn tropism_is_honoured_in_species() {
    let ternary = Species::from_preset("abop-ternary", 4).unwrap();
    let t = ternary
        .turtle
        .tropism
        .expect("ABOP 2.8a bends towards gravity");
    assert!(t.direction.y < 0.0 && t.susceptibility > 0.0);
    let file = Path::new("bent.species");
    let bent = Species::parse_file("grammar: kenwood-leafy\ntropism: 0 -1 0 0.3\n", file).unwrap();
    assert_eq!(bent.turtle.tropism.map(|t| t.susceptibility), Some(0.3));
    for bad in [
        "tropism: 0 0 0 0.3",
        "tropism: 0 -1 0",
        "tropism: 0 -1 0 99",
    ] {
        let text = format!("grammar: kenwood-leafy\n{bad}\n");
        match Species::parse_file(&text, file) {
            Err(ForestError::SpeciesFile {
                line: 2,
                column: 10,
                ..
            }) => {}
            other => panic!("{bad}: {other:?}"),
        }
    }
}
