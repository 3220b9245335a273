//! Derives an L-system and prints the word, in grammar notation, to stdout.
//!
//! ```text
//! cargo run --release --example derive -- [GRAMMAR_FILE | --preset NAME] [--generations N] [--seed S]
//! ```
//!
//! Without a grammar it derives the bundled preset `abop-1.24a`. Errors go to stderr with a
//! non-zero exit status.

mod common;

use std::process::ExitCode;

use sylva::lsys::{LSystem, PRESETS, preset};

struct Args {
    file: Option<String>,
    preset: Option<String>,
    generations: Option<u32>,
    seed: u64,
}

const USAGE: &str = "usage: derive [GRAMMAR_FILE | --preset NAME] [--generations N] [--seed S]";

fn parse_args() -> Result<Args, String> {
    let mut args = Args {
        file: None,
        preset: None,
        generations: None,
        seed: 0,
    };
    let mut it = std::env::args().skip(1);
    while let Some(a) = it.next() {
        match a.as_str() {
            "--generations" => {
                args.generations = Some(common::parse_value("--generations", it.next())?)
            }
            "--seed" => args.seed = common::parse_value("--seed", it.next())?,
            "--preset" => args.preset = Some(common::parse_value::<String>("--preset", it.next())?),
            "--help" | "-h" => {
                let names: Vec<&str> = PRESETS.iter().map(|p| p.name).collect();
                common::print_help(&format!("{USAGE}\npresets: {}", names.join(", ")));
            }
            s if s.starts_with("--") => return Err(format!("unknown option {s}\n{USAGE}")),
            s => args.file = Some(s.to_string()),
        }
    }
    Ok(args)
}

fn run() -> Result<String, String> {
    let args = parse_args()?;
    let (grammar, default_generations) = match (&args.file, &args.preset) {
        (Some(_), Some(_)) => {
            return Err(format!(
                "give a grammar file or --preset, not both\n{USAGE}"
            ));
        }
        (Some(path), None) => (LSystem::from_file(path).map_err(|e| e.to_string())?, 4),
        (None, name) => {
            let name = name.as_deref().unwrap_or("abop-1.24a");
            let p =
                preset(name).ok_or_else(|| format!("no preset called '{name}' (see --help)"))?;
            (
                p.lsystem().map_err(|e| format!("{name}: {e}"))?,
                p.generations,
            )
        }
    };
    let word = grammar
        .derive(args.generations.unwrap_or(default_generations), args.seed)
        .map_err(|e| e.to_string())?;
    Ok(word.to_string())
}

fn main() -> ExitCode {
    common::finish(run().map(|word| println!("{word}")))
}
