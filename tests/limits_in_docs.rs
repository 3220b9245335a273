//! The limits the docs quote are the ones the code checks: each figure a page gives is
//! written here from the constant it names, so changing a limit without its page (or a
//! page without its limit) fails here (issue 60: the docs listed a description field the
//! server refused, and front ends each had their own numbers).

use sylva::export::limits::MAX_TILES;
use sylva::forest::limits::{MAX_SPECIES_NAME_CHARS, MAX_TREE_PIECES};
use sylva::world::limits::{
    MAX_BUDGET_MB, MAX_DESCRIPTION_BYTES, MAX_MODEL_BYTES, MAX_MODEL_SIDE, MAX_SIDE, MAX_SPECIES,
    MAX_YEARS, TILE_SIZE_RANGE,
};

/// A page of `docs/`, its whitespace runs (line breaks among them) made single spaces.
fn page(name: &str) -> String {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("docs")
        .join(name);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// `n` with commas between thousands, as the pages write numbers.
fn grouped(n: u64) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (k, c) in digits.chars().enumerate() {
        if k > 0 && (digits.len() - k).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

#[track_caller]
fn quotes(name: &str, text: &str, figure: &str) {
    assert!(
        text.contains(figure),
        "docs/{name} should say \"{figure}\" (the limit in the code)"
    );
}

#[test]
fn the_cli_page_quotes_the_limits_it_names() {
    let cli = page("cli.md");
    let say = |figure: &str| quotes("cli.md", &cli, figure);
    say(&format!("at most {} fine tiles", grouped(MAX_TILES)));
    say(&format!("at most {MAX_SPECIES_NAME_CHARS} characters"));
    assert_eq!(MAX_TREE_PIECES, 1_000_000, "the page says a million");
    say("at most a million pieces of geometry");
    say(&format!("at most {} km a side", MAX_SIDE / 1000.0));
    say(&format!("`--budget-mb` is 1 to {MAX_BUDGET_MB}"));
    say(&format!("at most {MAX_SPECIES} species"));
}

#[test]
fn the_serving_page_quotes_the_limits_it_names() {
    let serving = page("serving.md");
    let say = |figure: &str| quotes("serving.md", &serving, figure);
    say(&format!(
        "{} km a side, a tile at least {} m",
        MAX_SIDE / 1000.0,
        TILE_SIZE_RANGE.0
    ));
    say(&format!(
        "A description is at most {} KiB, a heightmap {} MiB and {MAX_MODEL_SIDE} samples a side",
        MAX_DESCRIPTION_BYTES >> 10,
        MAX_MODEL_BYTES >> 20
    ));
    say(&format!("at most {}", grouped(u64::from(MAX_YEARS))));
    say(&format!("more than {}", grouped(MAX_TILES)));
}

#[test]
fn numbers_are_grouped_as_the_pages_write_them() {
    assert_eq!(grouped(65_536), "65,536");
    assert_eq!(grouped(100), "100");
    assert_eq!(grouped(1_000_000), "1,000,000");
}
