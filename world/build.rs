//! Bundles every species folder under `species/`: a folder `species/NAME/` holds
//! `NAME.species` and, when its grammar is not a preset, one `.lsys` grammar file. Adding a
//! species is adding a folder; this script writes the list the crate includes.

use std::fmt::Write as _;
use std::path::Path;

/// The species that come first, in this order: the default forest's five. Any other folder
/// follows in name order.
const FIRST: [&str; 5] = ["oak", "birch", "spruce", "pine", "hazel"];

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("species");
    println!("cargo::rerun-if-changed={}", root.display());
    let mut names: Vec<String> = std::fs::read_dir(&root)
        .expect("the species folder")
        .filter_map(Result::ok)
        .filter(|e| e.path().is_dir())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    names.sort_by_key(|n| {
        (
            FIRST.iter().position(|f| f == n).unwrap_or(FIRST.len()),
            n.clone(),
        )
    });
    let mut out = String::from("&[\n");
    for name in &names {
        let folder = root.join(name);
        println!("cargo::rerun-if-changed={}", folder.display());
        let species = folder.join(format!("{name}.species"));
        assert!(
            species.is_file(),
            "{}: missing {name}.species",
            folder.display()
        );
        let grammars: Vec<_> = std::fs::read_dir(&folder)
            .expect("a species folder")
            .filter_map(Result::ok)
            .map(|e| e.path())
            .filter(|p| p.extension().is_some_and(|x| x == "lsys"))
            .collect();
        assert!(
            grammars.len() <= 1,
            "{}: more than one .lsys grammar",
            folder.display()
        );
        let grammar = match grammars.first() {
            Some(g) => format!("Some(include_str!({:?}))", g.display().to_string()),
            None => "None".to_owned(),
        };
        writeln!(
            out,
            "    BundledSpecies {{ name: {name:?}, path: \"world/species/{name}/{name}.species\", text: include_str!({:?}), grammar: {grammar} }},",
            species.display().to_string()
        )
        .expect("writing to a string");
    }
    out.push_str("]\n");
    let dest = Path::new(&std::env::var("OUT_DIR").expect("OUT_DIR")).join("species.rs");
    std::fs::write(dest, out).expect("writing the species list");
}
