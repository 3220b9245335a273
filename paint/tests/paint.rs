//! Painting forests headless: scripted strokes, undo and redo, masks saved and loaded, the
//! painted forest streamed like a generated one, and bad input refused with the forest
//! unchanged.

use std::path::PathBuf;
use std::sync::Arc;

use proptest::prelude::*;
use sylva_forest::{ForestBuilder, ForestError, PlacementBlock, Rect};
use sylva_instancing::CompactTree;
use sylva_paint::{Brush, BrushAction, ForestPainter, PaintLayer, load_masks, save_masks};
use sylva_terrain::FlatPlane;
use sylva_terrain::glam::Vec2;

const SIDE: f32 = 120.0;

fn ground() -> FlatPlane {
    sylva_testkit::plane(SIDE)
}

fn bounds() -> Rect {
    Rect::new(Vec2::splat(-SIDE), Vec2::splat(SIDE))
}

fn painter(builder: ForestBuilder) -> ForestPainter<FlatPlane> {
    let layer = PaintLayer::new(bounds(), 1.0, 2).unwrap();
    ForestPainter::new(builder, ground(), layer).unwrap()
}

fn hard(action: BrushAction, radius: f32) -> Brush {
    let mut b = Brush::new(action, radius);
    b.hardness = 1.0;
    b
}

fn at(t: &CompactTree) -> Vec2 {
    Vec2::new(t.position[0], t.position[2])
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("sylva-paint-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// Trees in a canonical order, to compare forests grown in different orders.
fn sorted(trees: impl Iterator<Item = CompactTree>) -> Vec<CompactTree> {
    let mut v: Vec<CompactTree> = trees.collect();
    v.sort_by(|a, b| {
        a.position
            .map(f32::to_bits)
            .cmp(&b.position.map(f32::to_bits))
            .then(a.variant.cmp(&b.variant))
    });
    v
}

#[test]
fn a_stroke_grows_the_generated_forest_inside_and_nothing_outside() {
    // One species grows, so the generated forest is what full paint of it should grow.
    let mut config = sylva_testkit::builder(3).config().clone();
    config.species[1].weight = 0.0;
    let builder = ForestBuilder::new(config).unwrap();
    let patch = builder.density().patch;
    let unpainted = builder.trees(&ground(), bounds());
    let mut painter = painter(builder);
    assert_eq!(painter.tree_count(), 0);
    let (centre, radius) = (Vec2::new(10.0, -5.0), 14.0 * patch);
    let report = painter
        .stroke(hard(BrushAction::Add { species: 0 }, radius), &[centre])
        .unwrap();
    assert_eq!(report.trees_after, painter.tree_count());
    assert!(report.tiles >= 4);
    // No tree beyond the brush (cells are 1 m: a cell centre within the radius holds trees
    // up to half a diagonal further out).
    let beyond = radius + 0.75;
    assert!(painter.trees().all(|t| at(t).distance(centre) < beyond));
    // Deep inside, where no decision reads an unpainted patch, exactly the generated forest's
    // trees stand, all of the painted species.
    let deep = radius - 5.0 * patch;
    let inside = |t: &&CompactTree| at(t).distance(centre) < deep;
    let variants = painter.forest().variants;
    let leafy = |t: &CompactTree| variants[usize::from(t.variant)].species == 0;
    let painted: Vec<&CompactTree> = painter.trees().filter(inside).collect();
    let generated: Vec<&CompactTree> = unpainted.iter().filter(inside).collect();
    assert!(painted.len() > 100, "{}", painted.len());
    let positions = |v: &[&CompactTree]| {
        sorted(v.iter().map(|t| **t))
            .iter()
            .map(at)
            .collect::<Vec<_>>()
    };
    assert!(
        positions(&painted) == positions(&generated),
        "{} painted trees, {} generated",
        painted.len(),
        generated.len()
    );
    assert!(painted.iter().all(|t| leafy(t)));
    // Over the whole disc, the count is the generated forest's within a few percent (the rim
    // has fewer neighbours to clash with).
    let disc = |t: &&CompactTree| at(t).distance(centre) < radius;
    let (p, g) = (
        painter.trees().filter(disc).count(),
        unpainted.iter().filter(disc).count(),
    );
    assert!(
        (p as f32) > 0.95 * g as f32 && (p as f32) < 1.25 * g as f32,
        "{p} vs {g}"
    );
}

#[test]
fn erase_removes_trees_and_undo_restores_the_exact_forest() {
    let mut painter = painter(sylva_testkit::builder(5));
    let add = hard(BrushAction::Add { species: 1 }, 30.0);
    painter
        .stroke(add, &[Vec2::new(-40.0, 0.0), Vec2::new(40.0, 0.0)])
        .unwrap();
    let added: Vec<CompactTree> = painter.trees().copied().collect();
    assert!(added.len() > 200);
    let erase = hard(BrushAction::Erase, 12.0);
    let centre = Vec2::new(5.0, 3.0);
    let report = painter.stroke(erase, &[centre]).unwrap();
    assert!(report.trees_after < report.trees_before);
    assert!(
        painter
            .trees()
            .all(|t| at(t).distance(centre) >= 12.0 - 0.75)
    );
    // Trees out of the erased patches' reach are the same trees.
    let reach = painter.reach(report.change.unwrap().region);
    let far = |t: &&CompactTree| !reach.contains(at(t));
    assert_eq!(
        painter.trees().filter(far).copied().collect::<Vec<_>>(),
        added.iter().filter(far).copied().collect::<Vec<_>>()
    );
    let erased: Vec<CompactTree> = painter.trees().copied().collect();
    painter.undo().unwrap();
    assert_eq!(painter.trees().copied().collect::<Vec<_>>(), added);
    painter.undo().unwrap();
    assert_eq!(painter.tree_count(), 0);
    assert!(painter.undo().is_none());
    painter.redo().unwrap();
    painter.redo().unwrap();
    assert_eq!(painter.trees().copied().collect::<Vec<_>>(), erased);
}

#[test]
fn the_species_brush_turns_trees_and_keeps_their_places() {
    let mut painter = painter(sylva_testkit::builder(9));
    painter
        .stroke(hard(BrushAction::Add { species: 0 }, 40.0), &[Vec2::ZERO])
        .unwrap();
    painter
        .stroke(
            hard(BrushAction::Species { species: 1 }, 15.0),
            &[Vec2::ZERO],
        )
        .unwrap();
    let forest = painter.forest();
    let species = |t: &CompactTree| forest.variants[usize::from(t.variant)].species;
    let (core, rim): (Vec<&CompactTree>, Vec<&CompactTree>) = painter
        .trees()
        .filter(|t| at(t).length() < 15.0 - 0.75 || at(t).length() > 15.0 + 0.75)
        .partition(|t| at(t).length() < 15.0);
    assert!(core.len() > 20 && rim.len() > 20);
    assert!(core.iter().all(|t| species(t) == 1));
    assert!(rim.iter().all(|t| species(t) == 0));
}

#[test]
fn saved_masks_load_and_stream_the_same_trees() {
    let mut painter = painter(sylva_testkit::builder(4));
    let mut brush = Brush::new(BrushAction::Add { species: 0 }, 25.0);
    brush.strength = 0.8;
    painter
        .stroke(brush, &[Vec2::new(-60.0, -60.0), Vec2::new(50.0, 40.0)])
        .unwrap();
    let mut species = Brush::new(BrushAction::Species { species: 1 }, 20.0);
    species.strength = 0.6;
    painter.stroke(species, &[Vec2::new(0.0, 0.0)]).unwrap();
    let dir = scratch("round-trip");
    save_masks(painter.layer(), &["leafy", "plant"], &dir).unwrap();
    let loaded = load_masks(&dir, &["leafy", "plant"], bounds()).unwrap();
    assert_eq!(&loaded, painter.layer());
    let mut config = painter.painted_builder().unwrap().config().clone();
    config.composition = Some(Arc::new(loaded));
    let builder = ForestBuilder::new(config).unwrap();
    let grown = builder.trees(&ground(), bounds());
    assert_eq!(sorted(grown.into_iter()), sorted(painter.trees().copied()));
    // Streamed (as the exporters take it): the same trees, block by block.
    let mut streamed = Vec::new();
    let stats = builder
        .stream(&ground(), bounds(), &mut |b: &PlacementBlock| {
            streamed.extend_from_slice(&b.trees);
            Ok(())
        })
        .unwrap();
    assert_eq!(stats.trees, painter.tree_count());
    assert_eq!(
        sorted(streamed.into_iter()),
        sorted(painter.trees().copied())
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_strokes_and_masks_are_refused_and_change_nothing() {
    let mut config = sylva_testkit::builder(2).config().clone();
    config.species[1].weight = 0.0;
    let mut painter = painter(ForestBuilder::new(config).unwrap());
    painter
        .stroke(
            Brush::new(BrushAction::Add { species: 0 }, 20.0),
            &[Vec2::ZERO],
        )
        .unwrap();
    let (trees, layer) = (painter.tree_count(), painter.layer().clone());
    let unloaded = painter
        .stroke(
            Brush::new(BrushAction::Add { species: 1 }, 20.0),
            &[Vec2::ZERO],
        )
        .unwrap_err();
    assert!(
        unloaded.to_string().contains("no trees to paint"),
        "{unloaded}"
    );
    let missing = painter
        .stroke(
            Brush::new(BrushAction::Species { species: 7 }, 20.0),
            &[Vec2::ZERO],
        )
        .unwrap_err();
    assert!(missing.to_string().contains("no species 7"), "{missing}");
    let outside = painter
        .stroke(
            Brush::new(BrushAction::Erase, 5.0),
            &[Vec2::new(500.0, 0.0)],
        )
        .unwrap_err();
    assert!(
        outside.to_string().contains("misses the terrain"),
        "{outside}"
    );
    assert!(
        painter
            .stroke(Brush::new(BrushAction::Erase, -1.0), &[Vec2::ZERO])
            .is_err()
    );
    assert_eq!((painter.tree_count(), painter.layer()), (trees, &layer));

    // Masks: wrong bit depth, wrong size, another terrain's, a stranger's file, none.
    let dir = scratch("bad-masks");
    save_masks(&layer, &["leafy", "plant"], &dir).unwrap();
    let names = ["leafy", "plant"];
    let other = Rect::new(Vec2::ZERO, Vec2::splat(50.0));
    let e = load_masks(&dir, &names, other).unwrap_err().to_string();
    assert!(
        e.contains("the mask covers") && e.contains("leafy.png"),
        "{e}"
    );
    // A mask of another layer's size beside this layer's (saving replaces a set whole, so
    // the odd one is copied in).
    let small = PaintLayer::new(bounds(), 2.0, 2).unwrap();
    let other_set = scratch("other-size");
    save_masks(&small, &names, &other_set).unwrap();
    std::fs::copy(other_set.join("plant.png"), dir.join("plant.png")).unwrap();
    let e = load_masks(&dir, &names, bounds()).unwrap_err().to_string();
    assert!(e.contains("share one size"), "{e}");
    let eight = {
        let mut bytes = Vec::new();
        let mut enc = png::Encoder::new(&mut bytes, 4, 4);
        enc.set_color(png::ColorType::Grayscale);
        enc.set_depth(png::BitDepth::Eight);
        enc.write_header()
            .unwrap()
            .write_image_data(&[0; 16])
            .unwrap();
        bytes
    };
    std::fs::write(dir.join("plant.png"), eight).unwrap();
    let e = load_masks(&dir, &names, bounds()).unwrap_err().to_string();
    assert!(
        e.contains("16-bit grayscale") && e.contains("plant.png"),
        "{e}"
    );
    // A header claiming a vast image is refused before anything is allocated for it.
    for side in [70_000u32, u32::MAX >> 1] {
        let mut bytes = Vec::new();
        let mut enc = png::Encoder::new(&mut bytes, side, side);
        enc.set_color(png::ColorType::Grayscale);
        enc.set_depth(png::BitDepth::Sixteen);
        let mut writer = enc.write_header().unwrap();
        // One row's worth of image data at most follows: the header lies.
        writer
            .write_chunk(png::chunk::IDAT, &[0x78, 0x9c, 0x03, 0x00])
            .unwrap();
        drop(writer);
        std::fs::write(dir.join("plant.png"), &bytes).unwrap();
        let e = load_masks(&dir, &names, bounds()).unwrap_err().to_string();
        // Refused by the layer's bound or the PNG decoder's own memory limit, naming the file.
        let bounded = e.contains("too large") || e.contains("limits are exceeded");
        assert!(bounded && e.contains("plant.png"), "{e}");
    }
    std::fs::write(dir.join("pine.png"), b"not a png").unwrap();
    let e = load_masks(&dir, &names, bounds()).unwrap_err().to_string();
    assert!(e.contains("names no species"), "{e}");
    let empty = scratch("no-masks");
    std::fs::create_dir_all(&empty).unwrap();
    let e = load_masks(&empty, &names, bounds())
        .unwrap_err()
        .to_string();
    assert!(e.contains("no masks"), "{e}");
    let mut config = sylva_testkit::builder(2).config().clone();
    config.composition = Some(Arc::new(PaintLayer::new(bounds(), 4.0, 3).unwrap()));
    let e = ForestBuilder::new(config).unwrap_err();
    assert_eq!(
        e,
        ForestError::CompositionSpecies {
            composition: 3,
            forest: 2
        }
    );
    let _ = std::fs::remove_dir_all(&dir);
    let _ = std::fs::remove_dir_all(&empty);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 12, ..ProptestConfig::default() })]

    /// Regenerating only the patches near each stroke gives exactly the forest grown afresh
    /// from the final layer.
    #[test]
    fn local_regeneration_equals_growing_afresh(
        strokes in prop::collection::vec(
            (0usize..3, -130.0f32..130.0, -130.0f32..130.0, 2.0f32..30.0, 0.1f32..1.0, 0.0f32..1.0),
            1..5,
        )
    ) {
        let builder = sylva_testkit::builder(6);
        let mut painter = painter(builder.clone());
        for (action, x, z, radius, strength, hardness) in strokes {
            let action = match action {
                0 => BrushAction::Add { species: 0 },
                1 => BrushAction::Species { species: 1 },
                _ => BrushAction::Erase,
            };
            let brush = Brush { action, radius, strength, hardness };
            // Strokes entirely off the terrain are refused; the rest paint.
            let _ = painter.stroke(brush, &[Vec2::new(x, z), Vec2::new(z, x)]);
        }
        let afresh = ForestPainter::new(builder, ground(), painter.layer().clone()).unwrap();
        prop_assert_eq!(
            painter.trees().copied().collect::<Vec<_>>(),
            afresh.trees().copied().collect::<Vec<_>>()
        );
    }
}

#[test]
fn a_full_layer_in_the_species_proportions_grows_the_generated_forest() {
    let builder = sylva_testkit::builder(12);
    let weights: Vec<f32> = builder.config().species.iter().map(|s| s.weight).collect();
    let layer = PaintLayer::filled(bounds(), 1.0, &weights).unwrap();
    let unpainted = builder.trees(&ground(), bounds());
    let painted = ForestPainter::new(builder, ground(), layer).unwrap();
    let painted = sorted(painted.trees().copied());
    let unpainted = sorted(unpainted.into_iter());
    // Only a tree whose draw falls within a rounding step of a share's boundary may differ.
    let same = painted
        .iter()
        .zip(&unpainted)
        .filter(|(a, b)| a == b)
        .count();
    println!("{same} of {} trees the same", unpainted.len());
    assert_eq!(painted.len(), unpainted.len());
    assert!(same + 2 >= unpainted.len(), "{same} of {}", unpainted.len());
    // Past the layer's edge trees grow as unpainted; an empty layer over half the terrain
    // keeps nothing on that half.
    let half = Rect::new(Vec2::splat(-SIDE), Vec2::new(0.0, SIDE));
    let builder = sylva_testkit::builder(12);
    let empty =
        ForestPainter::new(builder, ground(), PaintLayer::new(half, 1.0, 2).unwrap()).unwrap();
    assert!(empty.trees().all(|t| t.position[0] >= 0.0));
    let far = |t: &&CompactTree| t.position[0] > 20.0;
    assert_eq!(
        empty.trees().filter(far).count(),
        unpainted.iter().filter(far).count()
    );
}
