//! `sylva forest --project`: a project folder as the viewer's editor saves it makes the same
//! forest as the flags that say the same, and a folder missing its model says what it lacks.

mod common;

use std::path::Path;

use common::{scratch, stderr, sylva};
use sylva::world::Project;
use sylva::world::{SpeciesEntry, WorldDescription};

const SPECIES: &str = "name: shrub\ngrammar: shrub.lsys\ngenerations: 4\nangle: 25\n";
const GRAMMAR: &str = "axiom: A\nA -> F[+A][-A]FA\nF -> F\n";

fn path(p: &Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn a_project_makes_the_forest_its_flags_would() {
    let dir = scratch("project-same");
    let project = dir.join("project");
    let description = WorldDescription {
        species: vec![SpeciesEntry::Inline {
            file: SPECIES.into(),
            grammar: Some(GRAMMAR.into()),
        }],
        area: 120.0,
        seed: 4,
        density: Some(200.0),
        ..WorldDescription::default()
    };
    Project::write(&project, &description, None).unwrap();
    // The same world from flags: the species file beside its grammar.
    std::fs::write(dir.join("shrub.species"), SPECIES).unwrap();
    std::fs::write(dir.join("shrub.lsys"), GRAMMAR).unwrap();
    let (a, b) = (dir.join("a.glb"), dir.join("b.glb"));
    let out = sylva(&[
        "forest",
        "--project",
        path(&project),
        "--out",
        path(&a),
        "--quiet",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let out = sylva(&[
        "forest",
        "--species",
        path(&dir.join("shrub.species")),
        "--area",
        "120",
        "--seed",
        "4",
        "--density",
        "200",
        "--out",
        path(&b),
        "--quiet",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let (a, b) = (std::fs::read(a).unwrap(), std::fs::read(b).unwrap());
    assert!(a.len() > 1000);
    assert!(a == b, "the project's forest differs from the flags'");
    // A project names its world whole: the world's own flags are refused beside it.
    let out = sylva(&["forest", "--project", path(&project), "--seed", "2"]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_project_missing_its_model_says_which() {
    let dir = scratch("project-missing");
    let model = Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../terrain/tests/data/dems/west_bijou_escarpment.asc"
    ));
    Project::write(&dir, &WorldDescription::default(), Some(model)).unwrap();
    std::fs::remove_file(dir.join("heightmap.asc")).unwrap();
    let out = sylva(&[
        "forest",
        "--project",
        path(&dir),
        "--out",
        "/nonexistent/x.glb",
    ]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("no heightmap.* file"),
        "{}",
        stderr(&out)
    );
    let _ = std::fs::remove_dir_all(&dir);
}
