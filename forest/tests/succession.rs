//! Forests over time: determinism, ecology (succession, self-thinning, gaps), events, tiles
//! with halos, bounds, and snapshots drawn by a builder.

use std::collections::HashMap;
use std::sync::Arc;

use proptest::prelude::*;
use sylva_forest::succession::{
    Event, Snapshot, State, Stem, Succession, SuccessionOptions, YearStats, thinning_slope,
};
use sylva_forest::{ForestBuilder, ForestConfig, ForestError, Rect, TreeForm};
use sylva_terrain::glam::Vec2;
use sylva_testkit::{plane, succession_species};

fn square(min: f32, side: f32) -> Rect {
    Rect::new(Vec2::splat(min), Vec2::splat(min + side))
}

fn grown(region: Rect, years: u32, options: SuccessionOptions) -> Succession {
    let mut forest = Succession::new(succession_species(), region, options).unwrap();
    forest.run(years, |_| Ok(())).unwrap();
    forest
}

/// Basal-area share of species `k` in a year.
fn share(year: &YearStats, k: usize) -> f32 {
    if year.basal_area > 0.0 {
        year.species[k].basal_area / year.basal_area
    } else {
        0.0
    }
}

#[test]
fn the_same_forest_at_any_thread_count() {
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| grown(square(0.0, 120.0), 60, SuccessionOptions::default()))
    };
    let (one, two) = (run(1), run(2));
    assert_eq!(one.stems(), two.stems());
    assert_eq!(one.stats(), two.stats());
    assert!(one.stems().len() > 100, "{} trees", one.stems().len());
}

#[test]
fn pioneers_come_first_and_shade_tolerant_trees_take_over() {
    let forest = grown(square(0.0, 200.0), 250, SuccessionOptions::default());
    let years = forest.stats();
    let (early, late) = (&years[40], &years[250]);
    assert!(
        share(early, 0) > 0.7,
        "the pioneer holds {:.2} at 40",
        share(early, 0)
    );
    assert!(
        share(late, 1) > 0.5,
        "the tolerant tree holds {:.2} at 250",
        share(late, 1)
    );
    assert!(share(late, 1) > 3.0 * share(early, 1));
}

#[test]
fn dense_stands_thin_themselves() {
    let forest = grown(
        square(0.0, 200.0),
        150,
        SuccessionOptions::default().with_storm_rate(0.0),
    );
    let years = forest.stats();
    let densest = (0..years.len())
        .max_by(|&a, &b| years[a].stems_per_ha.total_cmp(&years[b].stems_per_ha))
        .unwrap();
    let later = &years[densest + 30];
    assert!(later.stems_per_ha < 0.8 * years[densest].stems_per_ha);
    assert!(later.mean_diameter > 1.3 * years[densest].mean_diameter);
    let slope = thinning_slope(&years[densest..densest + 30]).unwrap();
    assert!((-2.6..-0.9).contains(&slope), "slope {slope}");
}

#[test]
fn storms_throw_tall_trees_along_the_wind_and_open_the_canopy() {
    let options = SuccessionOptions::default().with_storm_rate(0.0);
    let forest = grown(square(0.0, 200.0), 90, options);
    let before = forest.stats().last().unwrap().canopy_cover;
    // The same region grown with a storm every year.
    let mut stormy = Succession::new(
        forest.species().to_vec(),
        forest.region(),
        options.with_storm_rate(1.0),
    )
    .unwrap();
    stormy.run(90, |_| Ok(())).unwrap();
    let thrown: Vec<&Stem> = stormy
        .stems()
        .iter()
        .filter(|s| s.state == State::Fallen)
        .collect();
    assert!(!thrown.is_empty());
    let storms: Vec<(u32, f32)> = stormy
        .stats()
        .iter()
        .flat_map(|y| {
            y.events.iter().filter_map(move |e| match e {
                Event::Storm { direction, .. } => Some((y.year, *direction)),
                _ => None,
            })
        })
        .collect();
    assert_eq!(storms.len(), 90, "a storm a year");
    // Each fallen tree lies along one of the storms' directions.
    for s in &thrown {
        let along = f32::from(s.fall) / 256.0 * 360.0;
        assert!(
            storms.iter().any(|(_, d)| (d - along).abs() < 1.5),
            "a tree fell towards {along} degrees"
        );
    }
    // Storms every year keep the canopy more open than calm years did.
    let after = stormy.stats().last().unwrap().canopy_cover;
    assert!(
        after < before,
        "cover {after} with storms, {before} without"
    );
}

/// The trees within 20 m of the inner borders of a 240 m square's four 120 m tiles, each tile
/// simulated alone with `halo`, and the whole square's trees there: the share of the tiles'
/// trees the whole run holds too (same tree, state and height within 1%), and the basal area
/// of the border strip in the tiles over the whole run's.
fn border_agreement(years: u32, halo: f32) -> (f32, f32) {
    let whole = grown(
        square(0.0, 240.0),
        years,
        SuccessionOptions::default().with_halo(halo),
    );
    let key = |s: &Stem| (s.key, s.species);
    let index: HashMap<(u64, u8), &Stem> = whole.stems().iter().map(|s| (key(s), s)).collect();
    let near = |s: &&Stem| {
        let p = Vec2::from(s.position);
        square(0.0, 240.0).contains(p)
            && (p.x - 120.0).abs().min((p.y - 120.0).abs()) < 20.0
            && s.height > 1.3
            && s.state.is_alive()
    };
    let basal = |s: &Stem| {
        whole.species()[usize::from(s.species)]
            .life
            .diameter(s.height)
            .powi(2)
    };
    let whole_basal: f32 = whole.stems().iter().filter(near).map(basal).sum();
    let (mut count, mut same, mut tiles_basal) = (0usize, 0usize, 0.0f32);
    for (i, j) in [(0.0, 0.0), (120.0, 0.0), (0.0, 120.0), (120.0, 120.0)] {
        let tile = Rect::new(Vec2::new(i, j), Vec2::new(i + 120.0, j + 120.0));
        let forest = grown(tile, years, SuccessionOptions::default().with_halo(halo));
        for s in forest
            .stems()
            .iter()
            .filter(near)
            .filter(|s| tile.contains(s.position.into()))
        {
            count += 1;
            tiles_basal += basal(s);
            same += usize::from(index.get(&key(s)).is_some_and(|w| {
                w.state == s.state && (w.height - s.height).abs() < 0.01 * s.height
            }));
        }
    }
    (same as f32 / count.max(1) as f32, tiles_basal / whole_basal)
}

#[test]
fn tiles_with_a_halo_agree_near_their_borders() {
    let (bare, bare_basal) = border_agreement(80, 0.0);
    let (haloed, haloed_basal) = border_agreement(80, 60.0);
    eprintln!(
        "80 years: halo 0 m {bare:.2} of border trees ({bare_basal:.2} of basal area), 60 m {haloed:.2} ({haloed_basal:.2})"
    );
    assert!(
        haloed > bare + 0.15,
        "a halo keeps more trees the same: {bare:.2} -> {haloed:.2}"
    );
    assert!(
        (haloed_basal - 1.0).abs() < 0.1,
        "the border strip's basal area: {haloed_basal:.2} of the whole run's"
    );
}

#[test]
fn bounds_are_errors_not_aborts() {
    let huge = Rect::new(Vec2::ZERO, Vec2::splat(30_000.0));
    assert!(matches!(
        Succession::new(succession_species(), huge, SuccessionOptions::default()),
        Err(ForestError::SuccessionArea { .. })
    ));
    let mut small = Succession::new(
        succession_species(),
        square(0.0, 100.0),
        SuccessionOptions::default().with_max_stems(50),
    )
    .unwrap();
    assert!(matches!(
        small.run(50, |_| Ok(())),
        Err(ForestError::TooManyStems { limit: 50, .. })
    ));
    for bad in [
        SuccessionOptions::default().with_halo(f32::NAN),
        SuccessionOptions::default().with_storm_rate(2.0),
        SuccessionOptions::default().with_max_stems(0),
    ] {
        assert!(matches!(
            Succession::new(succession_species(), square(0.0, 10.0), bad),
            Err(ForestError::OutOfRange(_))
        ));
    }
    let mut species = succession_species();
    species[0].life.max_height = -1.0;
    assert!(Succession::new(species, square(0.0, 10.0), SuccessionOptions::default()).is_err());
}

#[test]
fn a_snapshot_is_drawn_in_every_form_at_its_heights() {
    let forest = grown(
        square(0.0, 150.0),
        120,
        SuccessionOptions::default().with_storm_rate(0.3),
    );
    let snapshot: Snapshot = forest.snapshot();
    assert!(snapshot.len() > 100);
    assert!(
        snapshot
            .trees()
            .all(|t| forest.region().contains(t.position.into()))
    );
    let config = ForestConfig::new(succession_species())
        .with_budget(4 << 20)
        .with_all_ages(true);
    let builder = ForestBuilder::new(config).unwrap();
    let drawing = builder
        .with_snapshot(Some(Arc::new(snapshot.clone())))
        .unwrap();
    let ground = plane(1000.0);
    let trees = drawing.trees(&ground, forest.region());
    assert_eq!(trees.len(), snapshot.len(), "flat ground keeps every tree");
    let forms: Vec<TreeForm> = trees
        .iter()
        .map(|t| builder.variants()[usize::from(t.variant)].form)
        .collect();
    assert!(
        forms.contains(&TreeForm::Fallen) && forms.iter().any(|f| matches!(f, TreeForm::Live(_)))
    );
    // Each living tree is drawn as tall as it stands.
    for (tree, t) in trees.iter().zip(snapshot.trees_in(forest.region())) {
        let variant = &builder.variants()[usize::from(tree.variant)];
        if let TreeForm::Live(g) = variant.form {
            let drawn = builder
                .form_heights(variant.species)
                .iter()
                .find(|(k, _)| *k == g)
                .unwrap()
                .1;
            assert!((drawn * tree.scale - t.height).abs() < 1e-3 * t.height);
        }
        assert_eq!(t.state == State::Fallen, variant.form == TreeForm::Fallen);
    }
    // A builder without every age refuses a snapshot.
    let plain =
        ForestBuilder::new(ForestConfig::new(succession_species()).with_budget(2 << 20)).unwrap();
    assert!(matches!(
        plain.with_snapshot(Some(Arc::new(snapshot))),
        Err(ForestError::NotAllAges)
    ));
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 8, ..ProptestConfig::default() })]

    /// Whatever the seed and region: trees stay in the simulated area, no taller than their
    /// species allows and no older than the years run; the statistics hold a year each.
    #[test]
    fn trees_stay_within_their_bounds(seed in 0u64..1000, x in -500.0f32..500.0, side in 20.0f32..80.0) {
        let region = Rect::new(Vec2::new(x, -x), Vec2::new(x + side, -x + side));
        let options = SuccessionOptions::default().with_seed(seed).with_halo(10.0);
        let forest = {
            let mut f = Succession::new(succession_species(), region, options).unwrap();
            f.run(40, |_| Ok(())).unwrap();
            f
        };
        let area = region.expanded(10.0);
        let lives: Vec<_> = forest.species().iter().map(|s| s.life).collect();
        for s in forest.stems() {
            prop_assert!(area.contains(s.position.into()));
            prop_assert!(s.height <= 1.2 * lives[usize::from(s.species)].max_height + 1e-3);
            prop_assert!(s.age <= 40);
        }
        prop_assert_eq!(forest.stats().len(), 41);
    }
}

/// The table of the crate README: how closely tiles agree with one run, by halo and years.
/// `cargo test --release -p sylva-forest --test succession -- --ignored --nocapture`
#[test]
#[ignore = "a table for docs/growth-and-succession.md, about a minute in release"]
fn tile_agreement_table() {
    for years in [80, 300] {
        for halo in [0.0, 30.0, 60.0, 120.0, 240.0] {
            let (trees, basal) = border_agreement(years, halo);
            eprintln!(
                "| {years} | {halo} | {:.0}% | {:.2} |",
                100.0 * trees,
                basal
            );
        }
    }
}
