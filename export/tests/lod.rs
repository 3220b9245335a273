//! Levels of detail: coarser meshes stay within their error of the full one, keep the leaf
//! area, and cost fewer triangles on every default species.

use sylva_export::lod::{LodLevel, simplify_mesh};
use sylva_turtle::Mesh;

fn card_area(mesh: &Mesh) -> f32 {
    use glam::Vec3;
    mesh.leaves
        .chunks_exact(3)
        .map(|t| {
            let [a, b, c] =
                [t[0], t[1], t[2]].map(|i| Vec3::from(mesh.vertices[i as usize].position));
            0.5 * (b - a).cross(c - a).length()
        })
        .sum()
}

/// The five default species, from the repository's species files.
fn default_species() -> Vec<sylva_forest::Species> {
    ["oak", "birch", "spruce", "pine", "hazel"]
        .iter()
        .map(|name| {
            let path = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
                .join(format!("../world/species/{name}/{name}.species"));
            let text = std::fs::read_to_string(&path).expect("species file");
            sylva_forest::Species::parse_file(&text, &path).expect("species parses")
        })
        .collect()
}

#[test]
fn every_species_costs_fewer_triangles_at_each_level() {
    for species in default_species() {
        let full = species.mesh(species.generations, 1).expect("mesh");
        for level in [
            LodLevel {
                bark_error: 0.03,
                leaf_keep: 0.5,
                leaf_growth: None,
            },
            LodLevel {
                bark_error: 0.12,
                leaf_keep: 0.25,
                leaf_growth: None,
            },
        ] {
            let coarse = simplify_mesh(&full, &level);
            println!(
                "{} {:?}: bark {} -> {}, leaves {} -> {}, leaf area {:.1} -> {:.1}",
                species.name,
                level,
                full.bark.len() / 3,
                coarse.bark.len() / 3,
                full.leaves.len() / 3,
                coarse.leaves.len() / 3,
                card_area(&full),
                card_area(&coarse)
            );
        }
    }
}

/// The distance from `p` to the triangle `abc`.
fn point_triangle(p: glam::Vec3, [a, b, c]: [glam::Vec3; 3]) -> f32 {
    let n = (b - a).cross(c - a);
    if n.length_squared() > 1e-12 {
        // Inside the prism over the triangle: the distance to its plane.
        let inside = [(a, b), (b, c), (c, a)]
            .iter()
            .all(|&(u, v)| (v - u).cross(p - u).dot(n) >= 0.0);
        if inside {
            return (p - a).dot(n.normalize()).abs();
        }
    }
    let segment = |u: glam::Vec3, v: glam::Vec3| {
        let d = v - u;
        let t = if d.length_squared() > 0.0 {
            ((p - u).dot(d) / d.length_squared()).clamp(0.0, 1.0)
        } else {
            0.0
        };
        p.distance(u + d * t)
    };
    segment(a, b).min(segment(b, c)).min(segment(c, a))
}

/// A branching axis of `segments` pieces, each turned and rolled, wider than `radius`.
fn tube_word(turns: &[(f32, f32, f32)], width: f32) -> sylva_lsys::Word {
    let mut text = format!("!({width})");
    for (k, &(turn, pitch, length)) in turns.iter().enumerate() {
        text.push_str(&format!("F({length})+({turn})&({pitch})"));
        if k % 4 == 2 {
            text.push_str(&format!("[&(40)!({})F(1)F(1)]", width * 0.7));
        }
    }
    text.parse().expect("word parses")
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(24))]

    /// Every bark vertex of the full mesh lies within the level's error of the coarse bark,
    /// for branches too thick to be left out.
    #[test]
    fn coarse_bark_stays_within_its_error(
        turns in proptest::collection::vec((-12.0f32..12.0, -12.0f32..12.0, 0.2f32..1.5), 2..14),
        sides in 5u32..10,
        error in 0.01f32..0.2,
        width in 0.6f32..2.0,
    ) {
        use glam::Vec3;
        let word = tube_word(&turns, width);
        let mut options = sylva_turtle::TurtleOptions::default();
        options.radial_segments = sides;
        let mut builder = sylva_turtle::MeshBuilder::new(&options);
        sylva_turtle::interpret(&word, &options, &mut builder).expect("interprets");
        let full = builder.finish();
        let coarse = simplify_mesh(&full, &LodLevel { bark_error: error, leaf_keep: 1.0, leaf_growth: None });
        let triangles: Vec<[Vec3; 3]> = coarse
            .bark
            .chunks_exact(3)
            .map(|t| [t[0], t[1], t[2]].map(|i| Vec3::from(coarse.vertices[i as usize].position)))
            .collect();
        proptest::prop_assert!(coarse.bark.len() <= full.bark.len());
        for &i in &full.bark {
            let p = Vec3::from(full.vertices[i as usize].position);
            let d = triangles.iter().map(|&t| point_triangle(p, t)).fold(f32::INFINITY, f32::min);
            proptest::prop_assert!(d <= error * 1.01 + 1e-4, "vertex {i} is {d} from the coarse bark (error {error})");
        }
    }
}

/// The JSON chunk of a GLB file.
fn glb_json(bytes: &[u8]) -> serde_json::Value {
    let len = u32::from_le_bytes(bytes[12..16].try_into().expect("chunk length")) as usize;
    serde_json::from_slice(&bytes[20..20 + len]).expect("the JSON chunk parses")
}

fn small_chain() -> sylva_export::lod::LodChain {
    let mut chain = sylva_export::lod::LodChain::default();
    chain.impostor = chain.impostor.with_view_size(24);
    chain
}

/// A pack holds a GLB per variant whose scene is one node with a child per level, named
/// NAME_LOD0 .. NAME_LODn (the canopy variants' last level the impostor's cards, over the
/// atlas), the atlases, and every tree of the region in its placements.
#[test]
fn a_pack_holds_every_variants_levels_and_every_tree() {
    use sylva_export::write_asset_pack;
    let (builder, map, region) = sylva_testkit::export_case();
    let dir = sylva_testkit::scratch("pack").with_file_name("pack");
    let stats = write_asset_pack(&builder, &map, region, &small_chain(), &dir).expect("pack");
    let trees = builder.trees(&map, region).len();
    assert_eq!(stats.trees, trees);
    let manifest: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("pack.json")).expect("manifest"))
            .expect("json");
    let variants = manifest["variants"].as_array().expect("variants");
    assert_eq!(variants.len(), builder.variants().len());
    for (v, entry) in builder.variants().iter().zip(variants) {
        let name = entry["name"].as_str().expect("name");
        let doc =
            glb_json(&std::fs::read(dir.join(entry["file"].as_str().expect("file"))).expect("glb"));
        let nodes = doc["nodes"].as_array().expect("nodes");
        let scene: Vec<usize> = doc["scenes"][0]["nodes"]
            .as_array()
            .expect("scene")
            .iter()
            .map(|n| n.as_u64().expect("index") as usize)
            .collect();
        assert_eq!(scene.len(), 1, "{name}: one root");
        let root = &nodes[scene[0]];
        assert_eq!(root["name"], name);
        let children: Vec<String> = root["children"]
            .as_array()
            .expect("children")
            .iter()
            .map(|c| {
                nodes[c.as_u64().expect("index") as usize]["name"]
                    .as_str()
                    .expect("name")
                    .to_owned()
            })
            .collect();
        let levels = if v.seedling { 3 } else { 4 };
        let expected: Vec<String> = (0..levels).map(|k| format!("{name}_LOD{k}")).collect();
        assert_eq!(children, expected);
        // Each level is drawn from farther than the one before.
        let from: Vec<f64> = root["children"]
            .as_array()
            .expect("children")
            .iter()
            .map(|c| {
                nodes[c.as_u64().expect("index") as usize]["extras"]["from_distance_1080p"]
                    .as_f64()
                    .expect("distance")
            })
            .collect();
        assert!(from.windows(2).all(|w| w[0] <= w[1]), "{name}: {from:?}");
        if !v.seedling {
            for kind in ["colour", "normal", "depth"] {
                assert!(dir.join(format!("{name}_impostor_{kind}.png")).exists());
            }
        }
    }
    let csv = std::fs::read_to_string(dir.join("placements.csv")).expect("csv");
    assert_eq!(csv.lines().count(), trees + 1);
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("placements.json")).expect("json"))
            .expect("json");
    assert_eq!(json["trees"].as_array().expect("trees").len(), trees);
    std::fs::remove_dir_all(&dir).ok();
}

/// A folder with somebody else's files is refused, and nothing in it changes.
#[test]
fn a_pack_is_not_written_over_a_foreign_folder() {
    use sylva_export::ExportError;
    use sylva_export::write_asset_pack;
    let (builder, map, region) = sylva_testkit::export_case();
    let dir = sylva_testkit::scratch("foreign").with_file_name("mine");
    std::fs::create_dir_all(&dir).expect("folder");
    std::fs::write(dir.join("notes.txt"), "keep me").expect("file");
    let refused = write_asset_pack(&builder, &map, region, &small_chain(), &dir);
    assert!(
        matches!(refused, Err(ExportError::NotPackFolder { .. })),
        "{refused:?}"
    );
    assert_eq!(
        std::fs::read_to_string(dir.join("notes.txt")).expect("kept"),
        "keep me"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// The same inputs make the same pack, byte for byte.
#[test]
fn a_pack_is_a_pure_function_of_its_inputs() {
    use sylva_export::write_asset_pack;
    let (builder, map, region) = sylva_testkit::export_case();
    let a = sylva_testkit::scratch("pure-a").with_file_name("pack");
    let b = sylva_testkit::scratch("pure-b").with_file_name("pack");
    write_asset_pack(&builder, &map, region, &small_chain(), &a).expect("pack");
    write_asset_pack(&builder, &map, region, &small_chain(), &b).expect("pack");
    let mut names: Vec<_> = std::fs::read_dir(&a)
        .expect("dir")
        .flatten()
        .map(|e| e.file_name())
        .collect();
    names.sort();
    assert!(names.len() > 5);
    for name in names {
        assert_eq!(
            std::fs::read(a.join(&name)).expect("a"),
            std::fs::read(b.join(&name)).expect("b"),
            "{name:?}"
        );
    }
    std::fs::remove_dir_all(&a).ok();
    std::fs::remove_dir_all(&b).ok();
}
