//! Known answers for fixed seeds across the crates, one hash each. A change that alters any of
//! these bytes must say why in its commit, and refresh the value here.
//!
//! The hash is FNV-1a over the raw bytes (little-endian floats and integers), written out
//! here so that the pins do not depend on any hash in the library.

use sylva::forest::{ForestBuilder, ForestConfig, Rect, Species};
use sylva::instancing::{HeroOptions, Similarity, build_cache};
use sylva::lsys::preset;
use sylva::terrain::{DiamondSquare, EdgeMode, HeightField};

/// FNV-1a, 64 bits.
#[derive(Debug)]
struct Fnv(u64);

impl Fnv {
    fn new() -> Self {
        Fnv(0xcbf2_9ce4_8422_2325)
    }
    fn bytes(&mut self, bytes: &[u8]) -> &mut Self {
        for &b in bytes {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
        }
        self
    }
    fn f32s(&mut self, values: &[f32]) -> &mut Self {
        values.iter().for_each(|v| {
            self.bytes(&v.to_le_bytes());
        });
        self
    }
    fn u32s(&mut self, values: &[u32]) -> &mut Self {
        values.iter().for_each(|v| {
            self.bytes(&v.to_le_bytes());
        });
        self
    }
    fn similarity(&mut self, s: &Similarity) -> &mut Self {
        self.f32s(&s.rotation.to_array())
            .f32s(&s.translation.to_array())
            .f32s(&[s.scale])
    }
}

#[test]
fn heightmap_of_seed_7_raw_and_smoothed() {
    let mut map = DiamondSquare::new(129)
        .with_seed(7)
        .with_roughness(0.8)
        .generate()
        .unwrap();
    let raw = Fnv::new().f32s(map.heights()).0;
    map.smooth(2.0, EdgeMode::Mirror).unwrap();
    let smooth = Fnv::new().f32s(map.heights()).0;
    assert_eq!(
        (raw, smooth),
        (0xcbd2_3067_48b0_9248, 0xd612_5655_b751_6ad8),
        "{raw:#x} {smooth:#x}"
    );
}

#[test]
fn derived_words_of_fixed_seeds() {
    let mut h = Fnv::new();
    for (name, generations, seed) in [
        ("goe-random", 6, 3),
        ("abop-honda", 8, 0),
        ("abop-1.24f", 5, 0),
    ] {
        let word = preset(name)
            .unwrap()
            .lsystem()
            .unwrap()
            .derive(generations, seed)
            .unwrap();
        h.bytes(word.to_string().as_bytes());
    }
    assert_eq!(h.0, 0x34b0_f70b_db4d_9330, "{:#x}", h.0);
}

#[test]
fn hero_cache_of_a_fixed_grammar_seed_and_budget() {
    let mut h = Fnv::new();
    for name in ["kenwood-leafy", "goe-random"] {
        let grammar = preset(name).unwrap().lsystem().unwrap();
        let options = HeroOptions::default()
            .with_budget(2 << 20)
            .with_generations(6)
            .with_seed(11);
        let cache = build_cache(&grammar, &options).unwrap().cache;
        for v in &cache.vertices {
            h.f32s(&v.position).f32s(&v.normal).f32s(&v.uv);
        }
        h.u32s(&cache.bark).u32s(&cache.leaves);
        for i in &cache.instances {
            h.u32s(&[
                i.id,
                i.age,
                i.bark.start,
                i.bark.count,
                i.leaves.start,
                i.leaves.count,
                i.exits.start,
                i.exits.count,
            ])
            .similarity(&i.frame_inverse);
        }
        for e in &cache.exits {
            h.u32s(&[e.id, e.age]).similarity(&e.frame);
        }
    }
    // Changed with issue 12: vertices carry wind data (48 bytes, were 32), so the same byte
    // budget holds fewer heroes. Changed with issue 31: a branch's bark continues its
    // parent's texture height (v) instead of starting at 0.
    assert_eq!(h.0, 0x823b_ff07_d343_5821, "{:#x}", h.0);
}

#[test]
fn forest_of_seed_1_trees_and_placements() {
    let mut leafy = Species::from_preset("kenwood-leafy", 5).unwrap();
    leafy.turtle.step = 0.6;
    leafy.weight = 2.0;
    let mut plant = Species::from_preset("abop-1.24e", 4).unwrap();
    plant.turtle.step = 0.5;
    let mut config = ForestConfig::new(vec![leafy, plant]);
    config.budget = 2 << 20;
    config.seed = 1;
    let builder = ForestBuilder::new(config).unwrap();
    let terrain = DiamondSquare::new(65)
        .with_spacing(4.0)
        .with_seed(1)
        .with_amplitude(2.0)
        .generate()
        .unwrap();
    let (lo, hi) = terrain.bounds();
    let forest = builder.build(&terrain, Rect::new(lo, hi));
    let mut trees = Fnv::new();
    for t in &forest.trees {
        trees
            .f32s(&t.position)
            .f32s(&[t.yaw, t.scale])
            .u32s(&[t.seed, u32::from(t.variant)]);
    }
    let mut placements = Fnv::new();
    for variant_placements in forest.placements().unwrap() {
        placements.u32s(&[variant_placements.variant as u32]);
        for group in &variant_placements.placements.groups {
            placements.u32s(&[group.len() as u32]);
            group.iter().for_each(|s| {
                placements.similarity(s);
            });
        }
    }
    assert_eq!(
        (forest.trees.len(), trees.0, placements.0),
        // Changed with issue 12: patches of 0.8 times the weighted mean canopy diameter (was
        // the widest) and eight seedlings per patch (was three), so that the canopy closes;
        // placements again when vertices grew to 48 bytes (wind data: fewer heroes fit).
        // Changed with issue 31: patches of 0.76 times the mean diameter (more trees).
        // Changed with issue 50: patches of 0.65 times the mean diameter of the crowns'
        // cover seen from above (more trees again).
        (3453, 0x4008_739f_a52d_10ce, 0xcf10_439d_c641_ed69),
        "{} {:#x} {:#x}",
        forest.trees.len(),
        trees.0,
        placements.0
    );
}

#[test]
fn forest_over_time_of_seed_1() {
    use sylva::forest::succession::{Succession, SuccessionOptions};
    let region = Rect::new(
        sylva::terrain::glam::Vec2::ZERO,
        sylva::terrain::glam::Vec2::splat(100.0),
    );
    let mut forest = Succession::new(
        sylva::presets::species().unwrap(),
        region,
        SuccessionOptions::default().with_storm_rate(0.2),
    )
    .unwrap();
    forest.run(60, |_| Ok(())).unwrap();
    let mut stems = Fnv::new();
    for s in forest.stems() {
        stems
            .f32s(&s.position)
            .f32s(&[s.height, s.vigour])
            .bytes(&s.key.to_le_bytes())
            .u32s(&[u32::from(s.age), u32::from(s.species), s.state as u32]);
    }
    assert_eq!(
        (forest.stems().len(), stems.0),
        // Issue 25: the bundled species grown from bare ground for 60 years. Issue 50: the
        // spruce, pine, birch and hazel grammars drawn again (their crowns' widths seed the
        // succession).
        (8283, 0x9dbc_e997_385c_bd03),
        "{} {:#x}",
        forest.stems().len(),
        stems.0
    );
}

/// What the Python package reads of fixed seeds, pinned with the same values by
/// `python/tests/test_same_as_rust.py`: the bundled oak of seed 1 (its positions, then its
/// bark and leaf triangles, as `sylva.tree("oak", seed=1)` gives them) and the placements of
/// a 150 m world of seed 3 with geometry (`sylva.Forest(area=150, seed=3).placements()`,
/// column by column: positions, rotations, scales, variants, instances), hashed over their
/// little-endian bytes.
#[test]
fn what_python_reads_of_an_oak_and_a_world() {
    use sylva::forest::PlacementBlock;
    use sylva::world::{Ground, Quiet, WorldBuilder};

    let oak = sylva::presets::named_or_file("oak").unwrap();
    let mesh = oak.mesh(oak.generations, 1).unwrap();
    let positions: Vec<f32> = mesh.vertices.iter().flat_map(|v| v.position).collect();
    let tree = Fnv::new()
        .f32s(&positions)
        .u32s(&mesh.bark)
        .u32s(&mesh.leaves)
        .0;

    let ground = Ground::generated(3, 150.0).unwrap();
    let world = WorldBuilder::new(sylva::presets::species().unwrap())
        .with_seed(3)
        .build(ground, &Quiet)
        .unwrap();
    let variants = world.forest.variants();
    let mut columns: [Vec<f32>; 3] = Default::default();
    let mut ids: [Vec<u32>; 2] = Default::default();
    world
        .forest
        .stream(
            &world.ground.map,
            world.region(),
            &mut |b: &PlacementBlock| {
                for p in &b.placements {
                    let inst = &variants[p.variant as usize].cache.instances[p.instance as usize];
                    // Instances without geometry are left out, as the files leave them out.
                    if !inst.has_geometry() {
                        continue;
                    }
                    let x = &p.transform;
                    columns[0].extend(x.translation.to_array());
                    columns[1].extend(x.rotation.to_array());
                    columns[2].push(x.scale);
                    ids[0].push(p.variant);
                    ids[1].push(p.instance);
                }
                Ok(())
            },
        )
        .unwrap();
    let mut placements = Fnv::new();
    for c in &columns {
        placements.f32s(c);
    }
    for c in &ids {
        placements.u32s(c);
    }
    assert_eq!(
        (mesh.vertices.len(), tree, ids[0].len(), placements.0),
        (34_386, 0xce84_0083_bdb6_7140, 10_104, 0x8074_86d9_eb2f_a626),
        "{} {:#x} {} {:#x}",
        mesh.vertices.len(),
        tree,
        ids[0].len(),
        placements.0
    );
}
