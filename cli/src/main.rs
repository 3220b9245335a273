//! `sylva`: procedural forests on the command line.
//!
//! ```text
//! sylva forest                 # the default forest: forest.glb and forest_height.png
//! sylva forest --project DIR   # the forest of a project the viewer's editor saved
//! sylva tiles --out world      # the same world as a 3D Tiles 1.1 tileset
//! sylva grow                   # 25 oaks grown together around a boulder: stand.glb
//! sylva pack --out pack        # levels of detail, impostors and placements for engines
//! sylva paint                  # a scripted painting session: paint_masks/
//! sylva derive --preset abop-honda --generations 6
//! sylva tree --preset abop-ternary --out tree.obj
//! sylva terrain --size 1025 --out height.png
//! sylva corpus path/to/vlab/oofs
//! sylva succession --years 300  # a forest over time: succession/ with statistics and plots
//! sylva serve --port 8080       # worlds on demand over HTTP, and a page to walk them
//! ```
//!
//! Every subcommand has `--help`. Exit status: 0 on success, 1 when the job failed (bad input
//! or a file that could not be read or written; one line on stderr says which and why), 2 for
//! a command line that does not parse.

mod corpus;
mod derive;
mod failure;
mod forest;
mod grammar;
mod grow;
mod outputs;
mod pack;
mod paint;
// Plots and the server are features (off in the quick start's build, on in CI's and with
// `cargo install --path cli --features serve,plots`): each stands in for the other when off.
#[cfg(feature = "plots")]
mod plots;
#[cfg(not(feature = "plots"))]
#[path = "plots_absent.rs"]
mod plots;
mod progress;
#[cfg(feature = "serve")]
mod serve;
#[cfg(not(feature = "serve"))]
#[path = "serve_absent.rs"]
mod serve;
mod succession;
mod terrain;
mod tiles;
mod tree;
mod world;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

pub(crate) use failure::Failure;

/// Procedural forests: L-system grammars, turtle geometry, fractal terrain, branch-level
/// instancing, growth in the environment, painting and export.
#[derive(Debug, Parser)]
#[command(name = "sylva", version, propagate_version = true)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Grows a forest on a terrain and writes it as one binary glTF, with the heightmap.
    Forest(forest::ForestArgs),
    /// Writes a world as an OGC 3D Tiles 1.1 tileset: every tile, one tile, or the root.
    Tiles(tiles::TilesArgs),
    /// Grows a stand of trees together with light and collision and writes it as glTF.
    Grow(grow::GrowArgs),
    /// Writes the species as an asset pack for engines: levels of detail, impostors and the
    /// world's placements.
    Pack(pack::PackArgs),
    /// Runs a timed, scripted painting session and saves its masks.
    Paint(paint::PaintArgs),
    /// Derives an L-system and prints the word.
    Derive(derive::DeriveArgs),
    /// Derives a tree (a grammar, or a species with --species), meshes it with the turtle and
    /// writes a Wavefront OBJ, or binary glTF with its textures.
    Tree(tree::TreeArgs),
    /// Generates a diamond-square heightmap and writes it as a 16-bit PNG.
    Terrain(terrain::TerrainArgs),
    /// Loads, derives and meshes every cpfg and L-Py model under a folder; prints a table.
    Corpus(corpus::CorpusArgs),
    /// Grows a forest over time from bare ground, year by year (seeding, light, suppression,
    /// age, storms, lightning, disease); writes its statistics per year, plots and snapshots.
    Succession(succession::SuccessionArgs),
    /// Serves worlds on demand over HTTP: 3D Tiles generated on first request and kept in a
    /// cache folder, single trees, and a page that walks a world in the browser.
    Serve(serve::ServeArgs),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Forest(a) => forest::run(a),
        Command::Tiles(a) => tiles::run(a),
        Command::Grow(a) => grow::run(a),
        Command::Pack(a) => pack::run(a),
        Command::Paint(a) => paint::run(a),
        Command::Derive(a) => derive::run(a),
        Command::Tree(a) => tree::run(a),
        Command::Terrain(a) => terrain::run(a),
        Command::Corpus(a) => corpus::run(a),
        Command::Succession(a) => succession::run(a),
        Command::Serve(a) => serve::run(a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(failure) => {
            eprintln!("error: {failure}");
            ExitCode::from(failure.code())
        }
    }
}
