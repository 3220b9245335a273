//! Renders the viewer's default scene offscreen and checks the picture: what covers it
//! (terrain, bark, leaves and sky, from a flat material-id render) and how far it is from the
//! committed reference image. Runs on any adapter, Mesa's software drivers included.
//!
//! Without an adapter the test reports and passes, unless `SYLVA_REQUIRE_GPU` is set (CI sets
//! it after installing lavapipe). `SYLVA_BLESS=1` rewrites the reference image:
//! `SYLVA_BLESS=1 cargo test -p sylva-viewer golden`.

use crate::coverage::Coverage;
use crate::offscreen::Offscreen;
use crate::render::Mode;
use crate::scene::{Camera, Scene};
use crate::world::{self, SceneOptions};

const SIZE: (u32, u32) = (320, 180);
const GOLDEN: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/golden/default_scene.png"
);

pub(crate) fn read_png(path: &str) -> Option<Vec<u8>> {
    let file = std::fs::File::open(path).ok()?;
    let mut reader = png::Decoder::new(std::io::BufReader::new(file))
        .read_info()
        .ok()?;
    let mut buf = vec![0; reader.output_buffer_size()?];
    let info = reader.next_frame(&mut buf).ok()?;
    buf.truncate(info.buffer_size());
    Some(buf)
}

fn write_png(path: &str, pixels: &[u8]) {
    crate::write_png(path, SIZE, pixels).expect("golden file is writable");
}

fn default_scene() -> Scene {
    Scene::build(SceneOptions {
        seed: 1,
        side: 800.0,
        trees: None,
        species: world::default_species().expect("bundled species"),
        budget: Some(32 << 20),
        paint: None,
        specimen: false,
        floor: true,
        year: None,
        constraints: Default::default(),
        terrain: None,
        ground: None,
        density: None,
    })
    .expect("default scene builds")
}

/// An offscreen target, or `None` (after saying why) where no adapter is available and the
/// environment does not require one.
fn offscreen(scene: &Scene, size: (u32, u32)) -> Option<Offscreen> {
    match pollster::block_on(Offscreen::new(scene, size.0, size.1)) {
        Ok(o) => Some(o),
        Err(e) if std::env::var_os("SYLVA_REQUIRE_GPU").is_none() => {
            eprintln!("skipping the headless render: {e}");
            None
        }
        Err(e) => panic!("{e}"),
    }
}

/// Issue 12's measure of a closed canopy: seen straight down from 200 m over the middle of
/// the default forest, foliage covers at least 70% of the picture.
#[test]
fn canopy_closes_seen_from_above() {
    let mut scene = default_scene();
    let size = (256, 256);
    let Some(mut offscreen) = offscreen(&scene, size) else {
        return;
    };
    let above = Camera::parse("400,400,0,-89.9,200").expect("camera");
    let (ids, _) = offscreen
        .frame(&mut scene, &above, Mode::Ids)
        .expect("id render");
    let coverage = Coverage::of_ids(&ids);
    eprintln!("from above: {coverage}");
    assert!(coverage.leaves >= 0.70, "{coverage}");
    assert!(coverage.other < 0.01, "{coverage}");
}

/// Issue 50's seasons, seen straight down like the canopy measure: in winter the deciduous
/// crowns are bare (the evergreens keep theirs), so far less of the picture is leaves and
/// more is ground; in autumn every card is still on the trees; in midsummer the seasons
/// played draw what the species as given draw.
#[test]
fn the_seasons_take_the_leaves_off_in_winter() {
    let mut scene = default_scene();
    let size = (256, 256);
    let Some(mut offscreen) = offscreen(&scene, size) else {
        return;
    };
    let above = Camera::parse("400,400,0,-89.9,200").expect("camera");
    let mut leaves_on = |season: Option<f32>| {
        offscreen.season = season;
        let (ids, _) = offscreen
            .frame(&mut scene, &above, Mode::Ids)
            .expect("id render");
        let coverage = Coverage::of_ids(&ids);
        eprintln!("day {season:?}: {coverage}");
        coverage
    };
    let (given, summer) = (leaves_on(None), leaves_on(Some(200.0)));
    let (autumn, winter) = (leaves_on(Some(290.0)), leaves_on(Some(20.0)));
    assert!(
        (given.leaves - summer.leaves).abs() < 0.01,
        "{given} / {summer}"
    );
    assert!(
        (autumn.leaves - summer.leaves).abs() < 0.05,
        "{autumn} / {summer}"
    );
    assert!(winter.leaves < 0.7 * summer.leaves, "{winter} / {summer}");
    assert!(winter.terrain > summer.terrain + 0.1, "{winter} / {summer}");
    // The evergreens (spruce and pine, two fifths of the trees) stay green.
    assert!(winter.leaves > 0.15, "{winter}");
}

#[test]
fn default_scene_renders_terrain_and_trees() {
    let mut scene = default_scene();
    let camera = Camera::overview(scene.side(), 40.0);
    let Some(mut offscreen) = offscreen(&scene, SIZE) else {
        return;
    };
    // Every branch of every tree, then the levels of detail the distances ask for: they cover
    // the picture within three points of each other (issue 24's measure).
    offscreen.full_detail = true;
    let (full, all) = offscreen
        .frame(&mut scene, &camera, Mode::Ids)
        .expect("id render");
    offscreen.full_detail = false;
    let (ids, levels) = offscreen
        .frame(&mut scene, &camera, Mode::Ids)
        .expect("id render");
    let (a, b) = (Coverage::of_ids(&full), Coverage::of_ids(&ids));
    eprintln!("coverage at full detail: {a}; with levels of detail: {b}");
    for (x, y) in [(a.leaves, b.leaves), (a.terrain, b.terrain), (a.sky, b.sky)] {
        assert!((x - y).abs() < 0.03, "full detail {a}, with levels {b}");
    }
    assert!(
        levels.triangles * 4 < all.triangles,
        "{levels:?} against {all:?}"
    );
    let Coverage {
        terrain,
        bark,
        leaves,
        sky,
        other,
    } = Coverage::of_ids(&ids);
    let total = f64::from(SIZE.0 * SIZE.1);
    eprintln!("coverage: {}", Coverage::of_ids(&ids));
    // Over a closed canopy the ground shows only in gaps and at the near edge.
    assert!(
        (0.01..0.85).contains(&terrain),
        "terrain covers {terrain:.3}"
    );
    assert!((0.05..0.6).contains(&sky), "sky covers {sky:.3}");
    assert!(bark > 0.01, "bark covers {bark:.4}");
    assert!(leaves > 0.3, "leaves cover {leaves:.4}");
    assert!(other < 0.01, "unexpected colours cover {other:.4}");

    let (shaded, stats) = offscreen
        .frame(&mut scene, &camera, Mode::Shaded)
        .expect("shaded render");
    let adapter = offscreen.adapter.clone();
    assert!(stats.draws > 100 && stats.instances > 1000, "{stats:?}");
    // Shaded frames draw each tree at its level of detail; the first id frame drew every
    // branch.
    eprintln!(
        "triangles: {} shaded at the levels of detail, {} at full detail",
        stats.triangles, all.triangles
    );
    assert!(
        stats.triangles * 4 < all.triangles,
        "{stats:?} against {all:?}"
    );
    // The frame's placements picked from the GPU's pool of the cells' placements, and
    // copied on the CPU: the same picture, pixel for pixel.
    assert!(
        stats.picked || std::env::var_os("SYLVA_REQUIRE_GPU").is_none(),
        "{adapter} runs compute shaders, so frames pick their placements on the GPU"
    );
    offscreen.renderer.instances.pick = false;
    let (copied, copied_stats) = offscreen
        .frame(&mut scene, &camera, Mode::Shaded)
        .expect("shaded render");
    offscreen.renderer.instances.pick = true;
    assert!(!copied_stats.picked);
    assert!(
        copied == shaded,
        "picked and copied placements draw different pictures"
    );
    if std::env::var_os("SYLVA_BLESS").is_some() {
        write_png(GOLDEN, &shaded);
        eprintln!("wrote {GOLDEN} on {adapter}");
        return;
    }
    let golden =
        read_png(GOLDEN).expect("reference image missing: run with SYLVA_BLESS=1 to create it");
    assert_eq!(golden.len(), shaded.len());
    let diffs: Vec<u8> = golden
        .iter()
        .zip(&shaded)
        .map(|(a, b)| a.abs_diff(*b))
        .collect();
    let mean = diffs.iter().map(|&d| f64::from(d)).sum::<f64>() / diffs.len() as f64;
    let far = golden
        .chunks_exact(4)
        .zip(shaded.chunks_exact(4))
        .filter(|(a, b)| a.iter().zip(*b).any(|(x, y)| x.abs_diff(*y) > 24))
        .count();
    let far_fraction = far as f64 / total;
    eprintln!(
        "against the reference ({adapter}): mean difference {mean:.2}, {far_fraction:.4} of pixels far off"
    );
    assert!(
        mean < 3.0 && far_fraction < 0.02,
        "frame differs from {GOLDEN}: mean {mean:.2}, far {far_fraction:.4}"
    );
}

/// The wind moves the trees and nothing else: in a breeze, two moments of the cycle differ;
/// in still air they are the same picture.
#[test]
fn wind_sways_trees_and_still_air_does_not() {
    let birch = world::default_species().expect("bundled species")[1].clone();
    let mut scene = Scene::build(SceneOptions {
        seed: 3,
        side: 60.0,
        trees: None,
        species: vec![birch],
        budget: Some(4 << 20),
        paint: None,
        specimen: false,
        floor: true,
        year: None,
        constraints: Default::default(),
        terrain: None,
        ground: None,
        density: None,
    })
    .expect("birch stand builds");
    let size = (160, 90);
    let Some(mut offscreen) = offscreen(&scene, size) else {
        return;
    };
    let camera = Camera::parse("20,30,0,8,2").expect("camera");
    let mut frame_at = |wind: f32, time: f32| {
        offscreen.wind = wind;
        offscreen.time = time;
        offscreen
            .frame(&mut scene, &camera, Mode::Ids)
            .expect("id render")
            .0
    };
    let changed = |a: &[u8], b: &[u8]| {
        a.chunks_exact(4)
            .zip(b.chunks_exact(4))
            .filter(|(p, q)| p != q)
            .count() as f64
            / f64::from(size.0 * size.1)
    };
    let (breeze_0, breeze_1) = (frame_at(1.0, 0.0), frame_at(1.0, 0.7));
    let moved = changed(&breeze_0, &breeze_1);
    eprintln!(
        "a breeze moves {:.1}% of the pixels in 0.7 s",
        100.0 * moved
    );
    assert!(moved > 0.005, "{moved}");
    assert_eq!(changed(&frame_at(0.0, 0.0), &frame_at(0.0, 0.7)), 0.0);
}

/// Streaming changes nothing a frame shows: a view rendered, left for the far corner of a
/// world larger than the view distance (its cells dropped) and rendered again on coming back
/// is the same picture, pixel for pixel.
#[test]
fn a_view_streamed_again_is_the_same_picture() {
    let species = world::default_species().expect("bundled species");
    let mut scene = Scene::build(SceneOptions {
        seed: 4,
        side: 2400.0,
        trees: None,
        // Birch and oak: the spruce's needle sprays tripled the triangles this test draws on
        // the software driver without testing anything more.
        species: vec![species[1].clone(), species[0].clone()],
        budget: Some(12 << 20),
        paint: None,
        specimen: false,
        floor: true,
        year: None,
        constraints: Default::default(),
        terrain: None,
        ground: None,
        density: None,
    })
    .expect("world builds");
    let size = (160, 90);
    let Some(mut offscreen) = offscreen(&scene, size) else {
        return;
    };
    let here = Camera::parse("150,150,40,-5,30").expect("camera");
    let there = Camera::parse("2300,2300,40,-5,30").expect("camera");
    let (first, stats) = offscreen
        .frame(&mut scene, &here, Mode::Shaded)
        .expect("render");
    assert!(
        stats.streamed.generated > 0 && stats.streamed.coarse > 0,
        "{stats:?}"
    );
    let (_, away) = offscreen
        .frame(&mut scene, &there, Mode::Shaded)
        .expect("render");
    assert!(away.streamed.generated > 0, "{away:?}");
    let (back, again) = offscreen
        .frame(&mut scene, &here, Mode::Shaded)
        .expect("render");
    assert!(
        again.streamed.generated > 0,
        "the first view's cells were dropped"
    );
    assert!(
        first == back,
        "the view differs after streaming its cells again"
    );
}

/// A turntable shows its one tree whole from every side: the tree (bark and leaves) fills a
/// good part of each view, nothing of it is cut by the frame's top or sides, and no other
/// tree stands in the world.
#[test]
fn a_turntable_frames_its_tree_from_every_side() {
    let oak = world::default_species().expect("bundled species")[0].clone();
    let mut scene = Scene::build(SceneOptions {
        seed: 1,
        side: 0.0,
        trees: None,
        species: vec![oak],
        budget: Some(8 << 20),
        paint: None,
        specimen: true,
        floor: false,
        year: None,
        constraints: Default::default(),
        terrain: None,
        ground: None,
        density: None,
    })
    .expect("a turntable's world builds");
    let (builder, _) = scene.world.forest();
    let whole = sylva::forest::Rect::new(
        sylva::terrain::glam::Vec2::ZERO,
        sylva::terrain::glam::Vec2::splat(scene.side()),
    );
    assert_eq!(builder.trees(&scene.world.heightmap, whole).len(), 1);
    let size = (160, 160);
    let Some(mut offscreen) = offscreen(&scene, size) else {
        return;
    };
    let turntable = crate::turntable::Turntable { views: 4, size };
    let (views, tree) = turntable
        .render(&mut scene, &mut offscreen, Mode::Ids)
        .expect("turntable renders");
    assert_eq!(views.len(), 4);
    assert!(tree.height > 3.0 && tree.crown > 2.0, "{tree:?}");
    for crate::turntable::View { turn, pixels, .. } in &views {
        let coverage = Coverage::of_ids(pixels);
        assert!(
            coverage.leaves + coverage.bark > 0.08,
            "view from {turn}: {coverage}"
        );
        // The frame's outer rows and columns see sky or ground, never the tree.
        let is_sky_or_ground = |x: u32, y: u32| {
            let at = ((y * size.0 + x) * 4) as usize;
            let c = Coverage::of_ids(&pixels[at..at + 4]);
            c.sky + c.terrain > 0.99
        };
        let (w, h) = size;
        assert!(
            (0..w).all(|x| is_sky_or_ground(x, 0)),
            "view from {turn}: the tree touches the top"
        );
        assert!(
            (0..h).all(|y| is_sky_or_ground(0, y) && is_sky_or_ground(w - 1, y)),
            "view from {turn}: the tree touches a side"
        );
    }
}
