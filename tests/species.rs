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
