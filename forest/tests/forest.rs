//! Density management, seams, constraints, export and bad input.

use std::path::Path;

use proptest::prelude::*;
use sylva_forest::{
    BarkPattern, Candidate, DensityModel, ForestBuilder, ForestConfig, ForestError, GltfOptions,
    LeafShape, PatchDensity, PatchSpecies, PlacementBlock, Rect, Species, Texture, write_glb,
};
use sylva_terrain::glam::Vec2;
use sylva_terrain::{DiamondSquare, FlatPlane, HeightField};

fn small_species() -> Vec<Species> {
    let mut leafy = Species::from_preset("kenwood-leafy", 4).unwrap();
    leafy.turtle.step = 0.6;
    leafy.weight = 2.0;
    let mut plant = Species::from_preset("abop-1.24e", 4).unwrap();
    plant.turtle.step = 0.5;
    vec![leafy, plant]
}

fn builder(seed: u64) -> ForestBuilder {
    let mut config = ForestConfig::new(small_species());
    config.budget = 2 << 20;
    config.seed = seed;
    ForestBuilder::new(config).unwrap()
}

fn plane(side: f32) -> FlatPlane {
    FlatPlane {
        height: 0.0,
        min: Vec2::splat(-side),
        max: Vec2::splat(side),
    }
}

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

/// A file path in a fresh temporary directory of this test.
fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("sylva-forest-test-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join("forest.glb")
}

fn export_case() -> (ForestBuilder, sylva_terrain::Heightmap, Rect) {
    let map = DiamondSquare::new(65)
        .with_spacing(3.0)
        .with_seed(1)
        .with_amplitude(10.0)
        .generate()
        .unwrap();
    let (lo, hi) = map.bounds();
    (builder(7), map, Rect::new(lo, hi))
}

#[test]
fn exported_glb_is_well_formed_and_counts_match() {
    let (b, map, region) = export_case();
    let path = scratch("well-formed");
    let stats = write_glb(
        &b,
        &map,
        region,
        Some(&map.mesh(1).unwrap()),
        &GltfOptions::default(),
        &path,
    )
    .unwrap();
    let bytes = std::fs::read(&path).unwrap();
    assert_eq!(stats.bytes, bytes.len());
    assert_eq!(&bytes[0..4], b"glTF");
    let json_len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    let json: serde_json::Value = serde_json::from_slice(&bytes[20..20 + json_len]).unwrap();
    assert_eq!(json["extensionsUsed"][0], "EXT_mesh_gpu_instancing");
    // Leaf cards carry an alpha-masked, double-sided texture embedded as PNG.
    let images = json["images"].as_array().unwrap();
    assert!(!images.is_empty() && images.iter().all(|i| i["mimeType"] == "image/png"));
    let leaf_materials: Vec<_> = json["materials"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|m| m["name"].as_str().unwrap().ends_with("leaves"))
        .collect();
    assert!(!leaf_materials.is_empty());
    for m in leaf_materials {
        assert_eq!(m["alphaMode"], "MASK");
        assert_eq!(m["doubleSided"], true);
        assert!(m["pbrMetallicRoughness"]["baseColorTexture"]["index"].is_u64());
    }
    let mut placements = 0u64;
    for node in json["nodes"].as_array().unwrap() {
        if let Some(ext) = node["extensions"].get("EXT_mesh_gpu_instancing") {
            let count = |attr: &str| {
                json["accessors"][ext["attributes"][attr].as_u64().unwrap() as usize]["count"]
                    .as_u64()
                    .unwrap()
            };
            assert_eq!(count("TRANSLATION"), count("ROTATION"));
            assert_eq!(count("ROTATION"), count("SCALE"));
            // Each tree's tint rides along as the instance colour.
            assert_eq!(count("SCALE"), count("_COLOR_0"));
            placements += count("TRANSLATION");
        }
    }
    // The in-memory forest of the same region places the same instances.
    let forest = b.build(&map, region);
    let drawable: usize = forest
        .placements()
        .unwrap()
        .iter()
        .map(|v| {
            let cache = &forest.variants[v.variant].cache;
            v.placements
                .groups
                .iter()
                .zip(&cache.instances)
                .filter(|(_, i)| !(i.bark.is_empty() && i.leaves.is_empty()))
                .map(|(g, _)| g.len())
                .sum::<usize>()
        })
        .sum();
    assert_eq!(placements as usize, drawable);
    assert_eq!(stats.placements, drawable);
    assert_eq!(stats.trees, forest.trees.len());
    assert!(drawable >= forest.trees.len() / 2);
}

/// Chunked writing gathers a few instances per pass; the file is the same as in one pass,
/// and the same with one thread as with several.
#[test]
fn the_file_is_the_same_at_any_chunk_size_and_thread_count() {
    let (b, map, region) = export_case();
    let write = |name: &str, threads: usize, chunk_bytes: usize| {
        let path = scratch(name);
        let mut options = GltfOptions::default();
        options.chunk_bytes = chunk_bytes;
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let stats = pool
            .install(|| write_glb(&b, &map, region, None, &options, &path))
            .unwrap();
        (stats.passes, std::fs::read(&path).unwrap())
    };
    let (one_pass, reference) = write("one", 1, usize::MAX);
    assert_eq!(one_pass, 2);
    let (passes, chunked) = write("chunked", 1, 4096);
    assert!(passes > 10, "{passes} passes");
    assert!(chunked == reference, "chunked writing changed the file");
    for threads in [2, 3, 8] {
        let (_, parallel) = write(&format!("threads-{threads}"), threads, 64 << 10);
        assert!(parallel == reference, "{threads} threads changed the file");
    }
}

/// A bad destination is an error, and nothing is left behind: no file, no temporary file.
#[test]
fn a_failed_write_leaves_nothing_behind() {
    let (b, map, region) = export_case();
    let missing = std::env::temp_dir().join("sylva-no-such-dir-for-tests/forest.glb");
    assert!(write_glb(&b, &map, region, None, &GltfOptions::default(), &missing).is_err());
    assert!(!missing.exists());
    // The destination is a directory: everything is written, then the rename fails.
    let path = scratch("onto-a-directory");
    std::fs::create_dir_all(&path).unwrap();
    std::fs::write(path.join("keep"), b"x").unwrap();
    let err = write_glb(&b, &map, region, None, &GltfOptions::default(), &path);
    assert!(matches!(err, Err(ForestError::Io { .. })), "{err:?}");
    let left: Vec<_> = std::fs::read_dir(path.parent().unwrap())
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    assert_eq!(
        left,
        vec!["forest.glb".to_string()],
        "only the directory itself remains"
    );
}

/// A streamed forest is the in-memory forest cut into blocks: the same trees and the same
/// placements, in block order.
#[test]
fn streamed_blocks_hold_the_whole_forest() {
    let (b, map, region) = export_case();
    let forest = b.build(&map, region);
    let mut trees = Vec::new();
    let mut placements = 0;
    let stats = b
        .stream(&map, region, &mut |block: &PlacementBlock| {
            trees.extend_from_slice(&block.trees);
            placements += block.placements.len();
            Ok(())
        })
        .unwrap();
    let key = |t: &sylva_instancing::CompactTree| (t.position.map(f32::to_bits), t.seed, t.variant);
    let mut a: Vec<_> = trees.iter().map(key).collect();
    let mut whole: Vec<_> = forest.trees.iter().map(key).collect();
    a.sort_unstable();
    whole.sort_unstable();
    assert_eq!(a, whole);
    let expanded: usize = forest
        .placements()
        .unwrap()
        .iter()
        .map(|v| v.placements.count)
        .sum();
    assert_eq!(placements, expanded);
    assert_eq!(stats.placements, expanded);
    assert!(stats.blocks >= 1 && stats.trees == forest.trees.len());
}

/// No copy beside its copy (Kenwood 7.1): no tree stands within two canopy radii of a tree
/// of the same variant with the same composition.
#[test]
fn no_tree_stands_beside_its_copy() {
    // A cache with at least as many crowns per variant as crown classes (9 for canopy trees,
    // 27 for seedlings): below that the classes cannot all have crowns of their own.
    let mut config = ForestConfig::new(small_species());
    config.budget = 16 << 20;
    config.seed = 3;
    let b = ForestBuilder::new(config).unwrap();
    for v in b.variants().iter() {
        let crowns = v
            .cache
            .lookup(0, 0)
            .iter()
            .filter(|&&i| !v.cache.instances[i as usize].exits.is_empty())
            .count();
        assert!(crowns >= 27, "{crowns} crowns");
    }
    let region = Rect::new(Vec2::splat(-200.0), Vec2::splat(200.0));
    let forest = b.build(&plane(200.0), region);
    let mut assembler = sylva_instancing::Assembler::new();
    let compositions: Vec<u64> = forest
        .trees
        .iter()
        .map(|t| {
            assembler
                .composition(&forest.variants[t.variant as usize].cache, t)
                .unwrap()
        })
        .collect();
    let radius = forest
        .canopies
        .iter()
        .map(|c| c.radius())
        .fold(0.0f32, f32::max);
    let mut near = 0;
    for (i, a) in forest.trees.iter().enumerate() {
        for (j, c) in forest.trees.iter().enumerate().skip(i + 1) {
            let d =
                Vec2::new(a.position[0] - c.position[0], a.position[2] - c.position[2]).length();
            if d < 2.0 * radius && a.variant == c.variant {
                near += 1;
                assert_ne!(
                    compositions[i],
                    compositions[j],
                    "trees {i} and {j} are copies {d} m apart: {a:?} {c:?}, crowns {}",
                    forest.variants[a.variant as usize].cache.lookup(0, 0).len()
                );
            }
        }
    }
    assert!(near > 1_000, "only {near} close pairs checked");
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
    // A grammar file with an error is reported in that file's terms.
    let dir = std::env::temp_dir().join(format!("sylva-species-{}", std::process::id()));
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
    let mut tiny = ForestConfig::new(small_species());
    tiny.budget = 100;
    assert!(matches!(
        ForestBuilder::new(tiny),
        Err(ForestError::Instancing(_))
    ));
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
    assert!(message.contains("larger than the limit"), "{message}");
}

/// Hostile species files end in an error with a place, or in a species; never a panic.
#[test]
fn hostile_species_files() {
    let file = Path::new("hostile.species");
    let long_value = format!("grammar: kenwood-leafy\nname: {}\n", "x".repeat(1 << 20));
    assert!(Species::parse_file(&long_value, file).is_ok());
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
        ("grammar: kenwood-leafy\nbark_texture: scaly\n", 2),
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

/// Regions of no area stream nothing; a patch far too small for the region is refused before
/// anything is allocated; a species whose trees have no geometry is refused.
#[test]
fn degenerate_streams_are_empty_or_errors() {
    let mut b = builder(5);
    let mut blocks = 0;
    let empty = Rect::new(Vec2::splat(10.0), Vec2::splat(10.0));
    let stats = b
        .stream(&plane(100.0), empty, &mut |_: &PlacementBlock| {
            blocks += 1;
            Ok(())
        })
        .unwrap();
    assert_eq!((stats.blocks, stats.trees, blocks), (0, 0, 0));
    let nan = Rect::new(Vec2::splat(f32::NAN), Vec2::splat(10.0));
    assert_eq!(b.blocks(nan).unwrap().len(), 0);
    b.density_mut().patch = 1e-6;
    let huge = Rect::new(Vec2::ZERO, Vec2::splat(20_000.0));
    assert!(matches!(b.blocks(huge), Err(ForestError::BadParameter(_))));
    assert!(
        b.stream(&plane(20_000.0), huge, &mut |_: &PlacementBlock| Ok(()))
            .is_err()
    );
    // A species whose trees draw nothing is refused by name.
    let mut config = ForestConfig::new(vec![LSystemSpecies::bare()]);
    config.budget = 1 << 20;
    let err = ForestBuilder::new(config).unwrap_err();
    assert!(err.to_string().contains("'bare' draws nothing"), "{err}");
}

/// A species whose grammar draws nothing.
struct LSystemSpecies;

impl LSystemSpecies {
    fn bare() -> Species {
        let text = "name: bare\ngrammar: bare.lsys\ngenerations: 3\n";
        let dir = std::env::temp_dir().join(format!("sylva-bare-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("bare.lsys"), "axiom: A\nA -> [+A][-A]A").unwrap();
        Species::parse_file(text, &dir.join("bare.species")).unwrap()
    }
}

/// Blocks tile a region exactly: every tree of the whole region lands in exactly one block,
/// at odd offsets and sizes that do not divide evenly.
#[test]
fn blocks_tile_the_region_without_gaps_or_overlaps() {
    let mut b = builder(11);
    b.density_mut().patch = 3.3; // blocks of 211.2 m
    b.density_mut().seedlings_per_patch = 0;
    let region = Rect::new(Vec2::new(-123.4, 77.7), Vec2::new(401.9, 560.05));
    let blocks = b.blocks(region).unwrap();
    assert_eq!(blocks.len(), 9);
    for pair in blocks.windows(2) {
        if pair[0].min.y == pair[1].min.y {
            assert_eq!(pair[0].max.x, pair[1].min.x);
        }
    }
    assert_eq!(blocks[0].min, region.min);
    assert_eq!(blocks[8].max, region.max);
    let ground = plane(1_000.0);
    let key = |t: &sylva_instancing::CompactTree| (t.position.map(f32::to_bits), t.seed);
    let mut streamed = Vec::new();
    b.stream(&ground, region, &mut |block: &PlacementBlock| {
        streamed.extend(block.trees.iter().map(key));
        Ok(())
    })
    .unwrap();
    let mut whole: Vec<_> = b.trees(&ground, region).iter().map(key).collect();
    streamed.sort_unstable();
    whole.sort_unstable();
    assert!(whole.len() > 1_000, "{} trees", whole.len());
    assert_eq!(streamed, whole);
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

/// Bark textures are pure functions of their pattern; smooth (birch) bark is paler, with dark
/// lenticels.
#[test]
fn bark_textures_tile_and_differ_by_pattern() {
    let furrowed = Texture::bark(BarkPattern::Furrowed);
    let smooth = Texture::bark(BarkPattern::Smooth);
    assert!(furrowed != smooth);
    for t in [&furrowed, &smooth] {
        assert_eq!(
            t,
            &Texture::bark(if *t == furrowed {
                BarkPattern::Furrowed
            } else {
                BarkPattern::Smooth
            })
        );
        assert!(t.rgba.chunks_exact(4).all(|p| p[3] == 255));
    }
    // Birch bark is paler on average than furrowed bark, with dark lenticels.
    let mean = |t: &Texture| {
        t.rgba.chunks_exact(4).map(|p| f32::from(p[0])).sum::<f32>() / (t.rgba.len() / 4) as f32
    };
    assert!(mean(&smooth) > mean(&furrowed));
    assert!(smooth.rgba.chunks_exact(4).any(|p| p[0] < 110));
    let birch = Species::parse_file(
        "grammar: sylva-birch\nbark_texture: smooth\n",
        Path::new("b.species"),
    )
    .unwrap();
    assert_eq!(birch.bark_pattern, BarkPattern::Smooth);
}

/// Leaf textures are pure functions of their shape, opaque inside the leaves and clear
/// outside, and their PNG decodes to the same pixels.
#[test]
fn leaf_textures_are_deterministic_alpha_masks() {
    for shape in [LeafShape::Broadleaf, LeafShape::Needles] {
        let t = Texture::leaf(shape);
        assert_eq!(t, Texture::leaf(shape));
        let alphas: Vec<u8> = t.rgba.chunks_exact(4).map(|p| p[3]).collect();
        assert!(
            alphas.iter().all(|&a| a == 0 || a == 255),
            "{shape:?}: a mask"
        );
        let covered = alphas.iter().filter(|&&a| a == 255).count() as f32 / alphas.len() as f32;
        assert!((0.1..0.8).contains(&covered), "{shape:?} covers {covered}");
        let png = t.png();
        let mut reader = png::Decoder::new(std::io::Cursor::new(png))
            .read_info()
            .unwrap();
        let mut pixels = vec![0; reader.output_buffer_size().unwrap()];
        reader.next_frame(&mut pixels).unwrap();
        assert!(pixels == t.rgba);
    }
}
