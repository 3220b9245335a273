//! `sylva derive`: derives an L-system and prints the word, in grammar notation, to stdout.

use std::path::PathBuf;

use clap::Args;
use sylva::lsys::{LSystem, PRESETS, preset};

use crate::Failure;

/// `sylva derive`'s flags.
#[derive(Debug, Args)]
#[command(after_help = presets_help())]
pub(crate) struct DeriveArgs {
    /// A grammar file (sylva's notation, cpfg's .l or L-Py's .lpy).
    #[arg(conflicts_with = "preset")]
    file: Option<PathBuf>,
    /// A bundled grammar (default abop-1.24a).
    #[arg(long, value_name = "NAME")]
    preset: Option<String>,
    /// Generations to derive (default: the grammar's own, or 4).
    #[arg(long, value_name = "N")]
    generations: Option<u32>,
    /// Seed of stochastic productions.
    #[arg(long, default_value_t = 0)]
    seed: u64,
}

/// The presets' names, for `--help`.
pub(crate) fn presets_help() -> String {
    let names: Vec<&str> = PRESETS.iter().map(|p| p.name).collect();
    format!("Presets: {}", names.join(", "))
}

/// The grammar a file or a preset names, with its default generations.
pub(crate) fn grammar(
    file: Option<&PathBuf>,
    preset_name: Option<&str>,
    fallback: &str,
) -> Result<(LSystem, u32), Failure> {
    if let Some(path) = file {
        let grammar = LSystem::from_file(path)?;
        // cpfg models say how long to derive them.
        let steps = grammar.derivation_length().unwrap_or(4);
        return Ok((grammar, steps));
    }
    let name = preset_name.unwrap_or(fallback);
    let p = preset(name).ok_or_else(|| {
        Failure::usage(format!(
            "no preset called '{name}' (see --help for the list)"
        ))
    })?;
    Ok((p.lsystem()?, p.generations))
}

pub(crate) fn run(args: DeriveArgs) -> Result<(), Failure> {
    let (grammar, generations) = grammar(args.file.as_ref(), args.preset.as_deref(), "abop-1.24a")?;
    let word = grammar.derive(args.generations.unwrap_or(generations), args.seed)?;
    println!("{word}");
    Ok(())
}
