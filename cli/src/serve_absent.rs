//! `sylva serve` when this `sylva` is built without the `serve` feature: the command is
//! listed, and says how to get a `sylva` that serves. The HTTP stack (tokio, axum) stays out
//! of the quick start's build.

use clap::Args;

use crate::Failure;

/// `sylva serve`'s flags: any, since nothing is served.
#[derive(Debug, Args)]
pub(crate) struct ServeArgs {
    /// The flags a serving build takes (see its --help).
    #[arg(trailing_var_arg = true, allow_hyphen_values = true, hide = true)]
    rest: Vec<String>,
}

pub(crate) fn run(_: ServeArgs) -> Result<(), Failure> {
    Err(Failure::usage(
        "this sylva was built without serve: build it with `cargo install --path cli --features serve` (or `cargo run --release -p sylva-cli --features serve -- serve`)",
    ))
}
