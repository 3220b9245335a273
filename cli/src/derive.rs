//! `sylva derive`: derives an L-system and prints the word, in grammar notation, to stdout.

use clap::Args;

use crate::Failure;
use crate::grammar::{GrammarArgs, presets_help};

/// `sylva derive`'s flags.
#[derive(Debug, Args)]
#[command(after_help = presets_help())]
pub(crate) struct DeriveArgs {
    #[command(flatten)]
    grammar: GrammarArgs,
}

pub(crate) fn run(args: DeriveArgs) -> Result<(), Failure> {
    let grammar = args.grammar.load("abop-1.24a")?;
    let word = grammar
        .lsystem
        .derive(grammar.generations, args.grammar.seed)?;
    println!("{word}");
    Ok(())
}
