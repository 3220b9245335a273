//! `sylva corpus` over a small folder of models: what each read, whether it meshes, and the
//! bar on the share that does.

use std::path::PathBuf;
use std::process::Command;

const SYLVA: &str = env!("CARGO_BIN_EXE_sylva");

/// A flat unit Bézier patch, heading +y, up +z (lsys's test data).
fn patch() -> String {
    include_str!(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../lsys/tests/data/flat_patch.s"
    ))
    .to_string()
}

fn write(dir: &PathBuf, name: &str, text: &str) {
    std::fs::create_dir_all(dir).unwrap();
    std::fs::write(dir.join(name), text).unwrap();
}

#[test]
fn the_table_says_what_each_model_read_and_the_bar_holds() {
    let root = std::env::temp_dir().join(format!("sylva-corpus-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&root);
    // Leaves drawn by a surface file (two steps: F [ + ~l ] F [ + ~l ] A, 11 modules), and a
    // model that fails (its word draws nothing).
    let leafy = root.join("leafy");
    write(
        &leafy,
        "plant.l",
        "Lsystem: 1\nderivation length: 2\nAxiom: A\nA --> F[+~l(0.5)]A\nendlsystem\n",
    );
    write(&leafy, "plant.v", "surface: l leaf.s 1 4 4\n");
    write(&leafy, "leaf.s", &patch());
    write(
        &root.join("bare"),
        "plant.l",
        "Lsystem: 1\nderivation length: 1\nAxiom: A\nA --> B\nendlsystem\n",
    );
    let out = root.join("table.md");
    let run = |min: &str| {
        Command::new(SYLVA)
            .args([
                "corpus",
                root.to_str().unwrap(),
                "--out",
                out.to_str().unwrap(),
                "--min-percent",
                min,
            ])
            .output()
            .unwrap()
    };
    let passed = run("50");
    assert!(
        passed.status.success(),
        "{}",
        String::from_utf8_lossy(&passed.stderr)
    );
    let table = std::fs::read_to_string(&out).unwrap();
    assert!(
        table.starts_with(
            "2 models: 1 load, derive and mesh (50%); 0 refused as unsupported; 1 fail."
        ),
        "{table}"
    );
    assert!(
        table.contains("| leafy/plant.l | 1 surface | meshes | 2 steps, 11 modules,"),
        "{table}"
    );
    assert!(
        table.contains("| bare/plant.l |  | fails | meshed to no triangles"),
        "{table}"
    );
    // Above the share that meshes, the run fails and says why.
    let failed = run("60");
    assert!(!failed.status.success());
    assert!(
        String::from_utf8_lossy(&failed.stderr)
            .contains("50% of the models mesh, fewer than the 60% required")
    );
    let _ = std::fs::remove_dir_all(&root);
}
