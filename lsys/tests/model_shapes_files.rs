//! A vlab model's curve, contour and surface files, read from its folder by the names its
//! view file gives: known answers for cpfg's curve functions, and errors at their place.

use std::path::PathBuf;

use sylva_lsys::{Dialect, LSystem};

/// A fresh folder of this name holding `files` (name, text).
fn folder(name: &str, files: &[(&str, &str)]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("sylva-shapes-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for (file, text) in files {
        std::fs::write(dir.join(file), text).unwrap();
    }
    dir
}

/// vlab's Ridley profile (its model's `profile.con`).
const PROFILE: &str = "version: 1.4\ncontact: 0 0 0\nend: 0 0 0\nheading: 0 1 0\nup: 0 0 -1\n\
    size: 1\npoints: 4\nrange: 0.0 1.0\ndimension: 4\ntype: bspline\n0.269398 -0.447751 0 3\n\
    0.274471 -0.109864 0 1\n0.165305 0.175183 0 1\n-0.001478 0.202475 0 3\n";

/// A flat unit patch: one Bézier patch over [0, 1] x [0, 1] in x and y, heading +y, up +z,
/// contact at the origin (a `.s` file as vlab's surface editor writes it).
fn patch() -> String {
    include_str!("data/flat_patch.s").to_string()
}

#[test]
fn curve_functions_read_the_views_curves() {
    // Comment-only lines inside a production's block are part of it, as in Ridley's model.
    let plant = "Lsystem: 1\nStart: {L=curveGAL(1);}\nderivation length: 1\nAxiom: A(0.5)\n\
        A(t) : t < L {   // the block opens here\n\
        \t\t\t// a comment alone on its line\n\
        x = curveX(1, t); y = curveY(1, t); z = curveZ(1, t);\n\
        } --> B(x, y, z, L)\nendlsystem\n";
    let dir = folder(
        "curves",
        &[
            ("spiral.l", plant),
            ("spiral.v", "curve: profile.con\ncontour sides: 12\n"),
            ("profile.con", PROFILE),
        ],
    );
    let model = LSystem::from_model_dir(&dir).unwrap();
    assert_eq!(model.files().curves.len(), 1);
    assert_eq!(model.files().contour_sides, Some(12));
    let word = model.derive(1, 0).unwrap();
    let p = word.params(0);
    // cpfg's own values for this curve at 100 samples.
    assert!((p[0] - 0.243388).abs() < 1e-5, "{p:?}");
    assert!((p[1] + 0.060038).abs() < 1e-5, "{p:?}");
    assert_eq!(p[2], 0.0);
    assert!((p[3] - 0.779429).abs() < 1e-6, "{p:?}");
    // Printed in sylva's notation, it reads back with its files and derives the same.
    let again =
        LSystem::parse_with_files(&model.to_string(), Dialect::Sylva, model.files().clone())
            .unwrap();
    assert_eq!(again.derive(1, 0).unwrap(), word);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn curves_without_their_files_or_past_them_are_refused_at_their_place() {
    let text = "Lsystem: 1\naxiom: A\nA --> B(curveGAL(1))\nendlsystem\n";
    let e = LSystem::parse_dialect(text, Dialect::Cpfg).unwrap_err();
    assert_eq!((e.location.line, e.location.column), (3, 9));
    assert!(
        e.message
            .starts_with("unsupported: curveGAL(id, ...) reads the model's curve files"),
        "{}",
        e.message
    );
    let dir = folder(
        "past_curves",
        &[
            (
                "plant.l",
                "Lsystem: 1\naxiom: A\nA --> B(curveY(2, 0.5))\nendlsystem\n",
            ),
            ("plant.v", "curve: profile.con 50\n"),
            ("profile.con", PROFILE),
        ],
    );
    let e = LSystem::from_model_dir(&dir).unwrap_err().to_string();
    assert!(
        e.contains("curveY(2, ...): the model has curves 1 to 1"),
        "{e}"
    );
    // A broken curve file names the view file's line and the curve file's own.
    std::fs::write(
        dir.join("profile.con"),
        "cver 1 3\nname: x\npoints: 4 4\ntype: zz\n",
    )
    .unwrap();
    let e = LSystem::from_model_dir(&dir).unwrap_err().to_string();
    assert!(
        e.contains("line 1: profile.con: line 4: unsupported: curve type 'zz'"),
        "{e}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn surfaces_and_contours_are_read_with_their_settings() {
    let contour = "cver 1 3\nname: blade\npoints: 2 6\ntype: or\nsamples: 8\n-1 0 0 3\n1 0 0 3\n";
    let dir = folder(
        "surfaces",
        &[
            // A control panel beside the model is not the model.
            ("panel.l", "target: Lsystem\npanel name: L-system\n"),
            (
                "plant.l",
                "Lsystem: 1\nderivation length: 1\nAxiom: @#(2)~l(3)~q\nendlsystem\n",
            ),
            (
                "plant.v",
                "surface: l leaf.s 2.5 4 6\nsurface: qleaf.s\ncontour: 2 blade.con\n",
            ),
            ("leaf.s", &patch()),
            ("qleaf.s", &patch()),
            ("blade.con", contour),
        ],
    );
    let model = LSystem::from_model_dir(&dir).unwrap();
    let files = model.files();
    let letters: Vec<char> = files.surfaces.iter().map(|s| s.letter).collect();
    // The second surface names no letter: its file's first.
    assert_eq!(letters, ['l', 'q']);
    assert_eq!(
        (files.surfaces[0].scale, files.surfaces[0].divisions),
        (2.5, [4, 6])
    );
    assert_eq!(
        (files.surfaces[1].scale, files.surfaces[1].divisions),
        (1.0, [8, 8])
    );
    assert_eq!(files.contours.len(), 1);
    assert!(files.contour(2).is_some() && files.contour(1).is_none());
    // `~l(3)` is one module, the surface's, with its parameter.
    let word = model.derive(1, 0).unwrap();
    assert_eq!(word.len(), 3);
    assert_eq!(word.to_string(), "@#(2) ~l(3) ~q");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn surfaces_cut_too_finely_are_refused() {
    let mut many = patch();
    // 300 patches cut 64 by 64: 1.2 M quads, past the bound.
    let rows: String = many.lines().skip(11).map(|l| format!("{l}\n")).collect();
    for _ in 0..299 {
        many += "p\n";
        many += &rows;
    }
    let dir = folder(
        "fine",
        &[
            (
                "plant.l",
                "Lsystem: 1\nderivation length: 1\nAxiom: ~l\nendlsystem\n",
            ),
            ("plant.v", "surface: l leaf.s 1 64 64\n"),
            ("leaf.s", &many),
        ],
    );
    let e = LSystem::from_model_dir(&dir).unwrap_err().to_string();
    assert!(
        e.contains("the surfaces come to 1228800 quads: at most 1048576"),
        "{e}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
