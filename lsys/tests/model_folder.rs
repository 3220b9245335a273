//! vlab model folders: a `.l` file and the files beside it that it includes, read from the
//! folder only; errors in any of them name that file and its own line.

use std::path::{Path, PathBuf};

use sylva_lsys::{GrammarFileError, LSystem};

/// A fresh folder of this name holding `files` (name, text).
fn folder(name: &str, files: &[(&str, &str)]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("sylva-model-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for (file, text) in files {
        let path = dir.join(file);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, text).unwrap();
    }
    dir
}

fn error(dir: &Path) -> (PathBuf, usize, usize, String) {
    match LSystem::from_model_dir(dir).unwrap_err() {
        GrammarFileError::Parse { path, error } => (
            path,
            error.location.line,
            error.location.column,
            error.message,
        ),
        other => panic!("{other}"),
    }
}

const PLANT: &str = "Lsystem: 1\nderivation length: N\naxiom: A\nA --> F[+(ANGLE)A]A\nendlsystem\n";

#[test]
fn included_constants_and_nested_includes_are_read() {
    let dir = folder(
        "nested",
        &[
            ("plant.l", &format!("#include \"sizes.h\"\n{PLANT}")),
            ("sizes.h", "#define N 2\n#include \"angles.h\"\n"),
            ("angles.h", "/* degrees */\n#define ANGLE 25 // a comment\n"),
        ],
    );
    let plant = LSystem::from_model_dir(&dir).unwrap();
    assert_eq!(plant.derivation_length(), Some(2));
    // Worked by hand: A -> F[+(25)A]A, then each A again.
    assert_eq!(
        plant.derive(2, 0).unwrap().to_string(),
        "F[+(25)F[+(25)A]A]F[+(25)A]A"
    );
    // Printed, the model is one grammar with its includes in it: it parses alone, the same.
    let printed = LSystem::parse(&plant.to_string()).unwrap();
    assert_eq!(printed.derive(2, 0).unwrap(), plant.derive(2, 0).unwrap());
    // The .l file named, not its folder, reads the same.
    let same = LSystem::from_model_dir(dir.join("plant.l")).unwrap();
    assert_eq!(same.derive(2, 0).unwrap(), plant.derive(2, 0).unwrap());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn productions_may_come_from_an_included_file() {
    let dir = folder(
        "rules",
        &[
            (
                "plant.l",
                "#define N 1\nLsystem: 1\nderivation length: N\naxiom: A\n#include \"rules.inc\"\nendlsystem\n",
            ),
            ("rules.inc", "A --> FB\nB --> A\n"),
        ],
    );
    let plant = LSystem::from_model_dir(&dir).unwrap();
    // A -> FB -> FA -> FFB.
    assert_eq!(plant.derive(2, 0).unwrap().to_string(), "FA");
    assert_eq!(plant.derive(3, 0).unwrap().to_string(), "FFB");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn errors_name_the_file_and_line_they_are_in() {
    // A bad production on line 2 of the included file.
    let dir = folder(
        "bad_include",
        &[
            (
                "plant.l",
                "Lsystem: 1\nderivation length: 1\naxiom: A\n#include \"rules.inc\"\nendlsystem\n",
            ),
            ("rules.inc", "A --> F\nB --> F(\n"),
        ],
    );
    let (path, line, _, message) = error(&dir);
    assert_eq!(path, dir.join("rules.inc"), "{message}");
    assert_eq!(line, 2, "{message}");
    // After an include of three lines, the model's own lines keep their numbers.
    let dir = folder(
        "bad_after",
        &[
            (
                "plant.l",
                "#include \"three.h\"\nLsystem: 1\nderivation length: 1\naxiom: A\nA --> F(\nendlsystem\n",
            ),
            ("three.h", "#define X 1\n#define Y 2\n#define Z 3\n"),
        ],
    );
    let (path, line, _, message) = error(&dir);
    assert_eq!(path, dir.join("plant.l"), "{message}");
    assert_eq!(line, 5, "{message}");
}

#[test]
fn includes_stay_inside_the_folder_and_end() {
    let outside = folder("outside_secret", &[("secret.h", "#define N 1\n")]);
    let escape = format!(
        "#include \"../{}/secret.h\"\n{PLANT}",
        outside.file_name().unwrap().to_str().unwrap()
    );
    let dir = folder("escape", &[("plant.l", &escape)]);
    let (_, line, _, message) = error(&dir);
    assert_eq!(line, 1);
    assert!(message.contains("outside the model's folder"), "{message}");
    let dir = folder(
        "absolute",
        &[(
            "plant.l",
            "#include \"/etc/hostname\"\nLsystem: 1\naxiom: A\nendlsystem\n",
        )],
    );
    assert!(error(&dir).3.contains("absolute path"));
    let dir = folder(
        "missing",
        &[("plant.l", &format!("#include \"gone.h\"\n{PLANT}"))],
    );
    assert!(error(&dir).3.contains("no such file"));
    // A file that includes itself stops at the depth limit, with the chain in the message.
    let dir = folder(
        "loop",
        &[
            ("plant.l", &format!("#include \"self.h\"\n{PLANT}")),
            ("self.h", "#include \"self.h\"\n"),
        ],
    );
    let message = error(&dir).3;
    assert!(message.contains("nest more than 16 deep"), "{message}");
    let _ = std::fs::remove_dir_all(&outside);
}

#[test]
fn a_folder_needs_one_model() {
    let none = folder("none", &[("readme.txt", "no model here")]);
    let e = LSystem::from_model_dir(&none).unwrap_err().to_string();
    assert!(e.contains("no .l file"), "{e}");
    let two = folder("two", &[("a.l", PLANT), ("b.l", PLANT)]);
    let e = LSystem::from_model_dir(&two).unwrap_err().to_string();
    assert!(e.contains("a.l, b.l"), "{e}");
}

#[test]
fn without_a_folder_an_include_is_refused_at_its_place() {
    let e = LSystem::parse_dialect(
        &format!("#include \"x.h\"\n{PLANT}"),
        sylva_lsys::Dialect::Cpfg,
    )
    .unwrap_err();
    assert_eq!(e.location.line, 1);
    assert!(e.message.contains("unsupported: #include"), "{}", e.message);
}

/// A straight function from (0, 0) to (1, 1) in the `fver 1 1` format, named `name`.
fn ramp(name: &str) -> String {
    format!(
        "fver 1 1\nname: {name}\nsamples: 101\nflip: off\npoints: 4\n0 0\n0.333333 0.333333\n0.666667 0.666667\n1 1\n"
    )
}

#[test]
fn function_files_of_the_view_file_are_read_by_id_and_by_name() {
    // Old style: `function:` lines, ids in their order; the second function is the constant 2.
    let flat = "range: 0 1\npoints: 4\n0 2\n0.3 2\n0.6 2\n1 2\n";
    let dir = folder(
        "functions",
        &[
            (
                "plant.l",
                "Lsystem: 1\nderivation length: 1\naxiom: A(0.25)\nA(x) --> B(func(1, x)) C(func(2, x))\nendlsystem\n",
            ),
            (
                "plant.v",
                "scale factor: 0.9\nfunction: ramp.func 101\nfunction: flat.func 10\n",
            ),
            ("ramp.func", &ramp("ramp")),
            ("flat.func", flat),
        ],
    );
    let plant = LSystem::from_model_dir(&dir).unwrap();
    let word = plant.derive(1, 0).unwrap();
    let b = word.params(0)[0];
    assert!((b - 0.25).abs() < 2e-3, "{b}");
    assert_eq!(word.params(1), &[2.0]);
    // A function set: each name is defined as its id, as cpfg defines it.
    let set = format!(
        "funcgalleryver 1 1\nitems: 2\n{}{}",
        ramp("UP"),
        ramp("ALSO_UP")
    );
    let dir = folder(
        "function_set",
        &[
            (
                "plant.l",
                "Lsystem: 1\nderivation length: 1\naxiom: A(0.5)\nA(x) --> B(func(ALSO_UP, x), ALSO_UP)\nendlsystem\n",
            ),
            ("view.v", "function set: functions.fset\n"),
            ("functions.fset", &set),
        ],
    );
    let plant = LSystem::from_model_dir(&dir).unwrap();
    assert_eq!(plant.files().functions.len(), 2);
    let word = plant.derive(1, 0).unwrap();
    assert!((word.params(0)[0] - 0.5).abs() < 2e-3 && word.params(0)[1] == 2.0);
}

#[test]
fn func_without_its_files_or_past_them_is_refused_at_its_place() {
    let text = "Lsystem: 1\naxiom: A\nA --> B(func(1, 0.5))\nendlsystem\n";
    let e = LSystem::parse_dialect(text, sylva_lsys::Dialect::Cpfg).unwrap_err();
    assert_eq!((e.location.line, e.location.column), (3, 9));
    assert!(e.message.starts_with("unsupported: func"), "{}", e.message);
    let dir = folder(
        "past",
        &[
            (
                "plant.l",
                "Lsystem: 1\naxiom: A\nA --> B(func(3, 0.5))\nendlsystem\n",
            ),
            ("plant.v", "function: ramp.func\n"),
            ("ramp.func", &ramp("ramp")),
        ],
    );
    let (_, line, _, message) = error(&dir);
    assert_eq!(line, 3);
    assert!(message.contains("functions 1 to 1"), "{message}");
    // A view file naming a missing or broken function file says which line.
    let dir = folder(
        "broken_view",
        &[
            ("plant.l", "Lsystem: 1\naxiom: A\nendlsystem\n"),
            ("plant.v", "\nfunction: gone.func\n"),
        ],
    );
    let e = LSystem::from_model_dir(&dir).unwrap_err().to_string();
    assert!(e.contains("plant.v: line 2: gone.func"), "{e}");
}
