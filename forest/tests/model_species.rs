//! A species whose grammar is a vlab model folder draws as cpfg draws it: with cpfg's turtle
//! and the model's own surfaces.

use sylva_forest::Species;

/// A flat unit Bézier patch, heading +y, up +z (lsys's test data).
fn patch() -> String {
    include_str!(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../lsys/tests/data/flat_patch.s"
    ))
    .to_string()
}

#[test]
fn a_model_species_draws_its_surfaces() {
    let dir = std::env::temp_dir().join("sylva-model-species");
    let model = dir.join("herb");
    std::fs::create_dir_all(&model).unwrap();
    std::fs::write(
        model.join("plant.l"),
        "Lsystem: 1\nderivation length: 2\nAxiom: A\nA --> F[+~l(0.5)]A\nendlsystem\n",
    )
    .unwrap();
    std::fs::write(model.join("plant.v"), "surface: l leaf.s 1 2 2\n").unwrap();
    std::fs::write(model.join("leaf.s"), patch()).unwrap();
    std::fs::write(
        dir.join("herb.species"),
        "name: herb\ngrammar: herb\ngenerations: 2\n",
    )
    .unwrap();
    let herb = Species::from_file(dir.join("herb.species")).unwrap();
    // Two leaves of one patch cut 2 by 2: 4 quads each, 8 triangles each, beside the stem's tube.
    let mesh = herb.mesh(2, 0).unwrap();
    let stem_only = {
        let mut bare = herb.clone();
        bare.turtle.symbols.remove("~l");
        bare.mesh(2, 0).unwrap()
    };
    assert_eq!(mesh.triangle_count() - stem_only.triangle_count(), 16);
    let _ = std::fs::remove_dir_all(&dir);
}
