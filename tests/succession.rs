//! The bundled species over time, against ecology: pioneers (birch, pine) first on bare
//! ground, shade-tolerant spruce taking over the closed stand, the stand thinning itself as
//! its trees grow, and the canopy closing again over the gaps storms open.

use sylva::forest::Rect;
use sylva::forest::succession::{Event, Succession, SuccessionOptions, YearStats};
use sylva::terrain::glam::Vec2;

/// The bundled species' order: oak, birch, spruce, pine, hazel.
const BIRCH: usize = 1;
const SPRUCE: usize = 2;
const PINE: usize = 3;

fn stand(side: f32, years: u32, seed: u64) -> Vec<YearStats> {
    let region = Rect::new(Vec2::ZERO, Vec2::splat(side));
    let options = SuccessionOptions::default().with_seed(seed);
    let mut forest = Succession::new(sylva::presets::species().unwrap(), region, options).unwrap();
    forest.run(years, |_| Ok(())).unwrap();
    forest.stats().to_vec()
}

fn share(year: &YearStats, species: &[usize]) -> f32 {
    species
        .iter()
        .map(|&k| year.species[k].basal_area)
        .sum::<f32>()
        / year.basal_area.max(1e-6)
}

#[test]
fn pioneers_first_then_spruce_then_gaps_refilled() {
    let years = stand(300.0, 300, 1);
    let pioneers = [BIRCH, PINE];
    assert!(
        share(&years[40], &pioneers) > 0.8,
        "pioneers at 40: {:.2}",
        share(&years[40], &pioneers)
    );
    assert!(
        share(&years[300], &[SPRUCE]) > 0.5,
        "spruce at 300: {:.2}",
        share(&years[300], &[SPRUCE])
    );
    // Self-thinning: from the densest year, fewer and thicker stems.
    let densest = (0..years.len())
        .max_by(|&a, &b| years[a].stems_per_ha.total_cmp(&years[b].stems_per_ha))
        .unwrap();
    assert!(densest < 100, "the stand is densest young, at {densest}");
    let later = &years[densest + 40];
    assert!(later.stems_per_ha < 0.8 * years[densest].stems_per_ha);
    assert!(later.mean_diameter > 1.3 * years[densest].mean_diameter);
    // The strongest storm after the canopy closed opened it, and it closed again.
    let (year, _) = years
        .iter()
        .flat_map(|y| y.events.iter().map(move |e| (y.year as usize, e)))
        .filter_map(|(year, e)| match e {
            Event::Storm { thrown, .. } => Some((year, *thrown)),
            _ => None,
        })
        .filter(|(year, _)| *year > 60 && *year + 30 < years.len())
        .max_by_key(|(_, thrown)| *thrown)
        .expect("a storm after the canopy closed");
    let before = years[year - 1].canopy_cover;
    let gap = years[year..year + 5]
        .iter()
        .map(|y| y.canopy_cover)
        .fold(1.0, f32::min);
    let healed = years[year + 5..year + 30]
        .iter()
        .map(|y| y.canopy_cover)
        .fold(0.0, f32::max);
    assert!(
        gap < before,
        "the storm of {year} opened the canopy: {before} -> {gap}"
    );
    assert!(
        healed > gap + 0.5 * (before - gap),
        "refilled: {gap} -> {healed} (was {before})"
    );
}
