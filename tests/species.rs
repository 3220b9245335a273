//! The bundled species as a user meets them: every form of every species is a tree with bark
//! and leaves, within the triangle budget docs/species.md states for it.

use sylva::turtle::Mesh;

/// Most triangles of one hero tree of each bundled species (docs/species.md), canopy form and
/// young form: what a user's scene pays for a tree up close.
const BUDGETS: [(&str, usize, usize); 5] = [
    ("oak", 40_000, 5_000),
    ("birch", 28_000, 5_000),
    ("spruce", 26_000, 5_000),
    ("pine", 16_000, 5_000),
    ("hazel", 16_000, 5_000),
];

/// Most triangles of a hero tree, canopy and young form, for the bundled species beyond the
/// default forest's five (`world/species/`): a conifer's budget with room to spare.
const OTHER_BUDGET: (usize, usize) = (30_000, 5_000);

fn bark_and_leaf_triangles(mesh: &Mesh) -> (usize, usize) {
    (mesh.bark.len() / 3, mesh.leaves.len() / 3)
}

#[test]
fn every_form_of_every_species_has_bark_and_leaves_within_its_budget() {
    let species = sylva::presets::species().expect("bundled species");
    assert_eq!(species.len(), BUDGETS.len());
    for (s, (name, canopy_budget, young_budget)) in species.iter().zip(BUDGETS) {
        assert_eq!(s.name, name);
        for (form, generations, budget) in [
            ("canopy", s.generations, canopy_budget),
            ("young", s.seedling_generations, young_budget),
        ] {
            for seed in 1..=4 {
                let mesh = s.mesh(generations, seed).expect("the species derives");
                let (bark, leaves) = bark_and_leaf_triangles(&mesh);
                assert!(
                    bark > 100 && leaves >= 50,
                    "{name} {form} (seed {seed}): {bark} bark and {leaves} leaf triangles"
                );
                assert!(
                    bark + leaves <= budget,
                    "{name} {form} (seed {seed}): {} triangles, budget {budget}",
                    bark + leaves
                );
            }
        }
    }
}

#[test]
fn every_other_bundled_species_has_bark_and_leaves_within_the_shared_budget() {
    let others = &sylva::presets::BUNDLED[sylva::presets::DEFAULT_SPECIES..];
    assert!(others.len() >= 2, "fir and larch at least");
    for bundled in others {
        let s = bundled.species().expect("a bundled species parses");
        for (generations, budget) in [
            (s.generations, OTHER_BUDGET.0),
            (s.seedling_generations, OTHER_BUDGET.1),
        ] {
            for seed in 1..=2 {
                let mesh = s.mesh(generations, seed).expect("the species derives");
                let (bark, leaves) = bark_and_leaf_triangles(&mesh);
                assert!(
                    bark > 100 && leaves >= 50 && bark + leaves <= budget,
                    "{} ({generations} generations, seed {seed}): {bark} bark and {leaves} leaf triangles, budget {budget}",
                    bundled.name
                );
            }
        }
    }
}
