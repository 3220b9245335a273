//! Derives a bundled grammar and prints the word: `LSystem::derive` in a few lines.
//!
//! ```text
//! cargo run --example derive [PRESET] [GENERATIONS]
//! ```
//!
//! The `sylva derive` command does the same for any grammar file, with flags.

use sylva::lsys::preset;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let name = args.next().unwrap_or_else(|| "abop-1.24a".into());
    let generations: u32 = args.next().map_or(Ok(3), |g| g.parse())?;
    let grammar = preset(&name)
        .ok_or_else(|| format!("no preset called '{name}'"))?
        .lsystem()?;
    let word = grammar.derive(generations, 7)?;
    let text = word.to_string();
    // Every branch opened is closed: the turtle can draw it.
    assert_eq!(text.matches('[').count(), text.matches(']').count());
    println!("{text}");
    eprintln!(
        "{name}: {} modules after {generations} generations",
        word.len()
    );
    Ok(())
}
