//! `sylva` on real elevation models: a window of one too large for a world, the note that
//! says why a forest is thin, and a stand grown on real ground.

mod common;

use common::{scratch, stderr, sylva};

/// A bundled real model's path.
fn dem(name: &str) -> String {
    format!(
        "{}/../terrain/tests/data/dems/{name}",
        env!("CARGO_MANIFEST_DIR")
    )
}

/// An SRTM tile, 80 x 111 km, makes a forest on the first try: its middle 1000 m, with a
/// note naming the window as a crop; a crop outside the model is a usage mistake.
#[test]
fn a_tile_of_any_size_gives_its_middle_and_names_its_crop() {
    let dir = scratch("land-middle");
    let (glb, png) = (dir.join("f.glb"), dir.join("f.png"));
    let hgt = dem("N44W072.hgt");
    let birch = format!(
        "{}/../world/species/birch/birch.species",
        env!("CARGO_MANIFEST_DIR")
    );
    let out = sylva(&[
        "forest",
        "--terrain",
        &hgt,
        "--species",
        &birch,
        "--density",
        "20",
        "--budget-mb",
        "4",
        "--out",
        glb.to_str().unwrap(),
        "--heightmap",
        png.to_str().unwrap(),
        "--stats",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let message = stderr(&out);
    // The middle window: 16 x 11 samples of 66 x 93 m.
    assert!(
        message.contains("the model covers 79530 x 111122 m (1201 x 1201 samples); took the middle 994 x 926 m (columns 592..607, rows 595..605); --crop 592,595,16,11 names this window, --whole writes the whole model as 3D Tiles"),
        "{message}"
    );
    let stats: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(stats["area_m"].as_f64().unwrap() <= 1000.0, "{stats}");
    let _ = std::fs::remove_dir_all(&dir);
    let out = sylva(&["forest", "--terrain", &hgt, "--crop", "1200,0,10,10"]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("does not lie inside"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn a_thin_forest_says_which_constraint_thinned_it() {
    let dir = scratch("land-thin");
    let (glb, png) = (dir.join("f.glb"), dir.join("f.png"));
    let out = sylva(&[
        "forest",
        "--terrain",
        &dem("west_bijou_escarpment.asc"),
        "--crop",
        "40,10,30,30",
        "--max-slope",
        "3",
        "--out",
        glb.to_str().unwrap(),
        "--heightmap",
        png.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let message = stderr(&out);
    assert!(
        message.contains("candidate tree spots were refused"),
        "{message}"
    );
    assert!(
        message.contains("steeper than 3 degrees (--max-slope)"),
        "{message}"
    );
    let summary = String::from_utf8_lossy(&out.stdout);
    assert!(summary.contains("terrain: placed"), "{summary}");
    assert!(std::fs::metadata(&glb).unwrap().len() > 0);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_stand_grows_on_real_ground() {
    let dir = scratch("land-stand");
    let glb = dir.join("stand.glb");
    let asc = dem("west_bijou_escarpment.asc");
    let out = sylva(&[
        "grow",
        "--terrain",
        &asc,
        "--trees",
        "4",
        "--generations",
        "4",
        "--out",
        glb.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(std::fs::metadata(&glb).unwrap().len() > 0);
    // Off the model is an error, not a stand in the air.
    let out = sylva(&[
        "grow",
        "--terrain",
        &asc,
        "--at",
        "10,10",
        "--out",
        glb.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("must lie inside"), "{}", stderr(&out));
    let _ = std::fs::remove_dir_all(&dir);
}
