//! Derives a tree, meshes it with the turtle and writes a Wavefront OBJ file.
//!
//! ```text
//! cargo run --release --example tree -- [GRAMMAR_FILE | --preset NAME] [--generations N] [--seed S]
//!     [--angle DEG] [--shape cylinder|frustum] [--sides K] [--caps] [--out tree.obj]
//! ```
//!
//! Without arguments it writes the bundled ternary tree to `tree.obj`.

mod common;

use std::process::ExitCode;

use sylva::lsys::{LSystem, preset};
use sylva::turtle::{BranchShape, MeshBuilder, SymbolTable, TurtleOptions, interpret, write_obj};

const USAGE: &str = "usage: tree [GRAMMAR_FILE | --preset NAME] [--generations N] [--seed S] [--angle DEG] \
                     [--shape cylinder|frustum] [--sides K] [--caps] [--out tree.obj]";

fn run() -> Result<(), String> {
    let mut file = None;
    let mut preset_name = None;
    let (mut generations, mut seed, mut angle, mut shape, mut sides, mut caps) =
        (None, 0u64, None, BranchShape::Frustum, 8u32, false);
    let mut out = String::from("tree.obj");
    let mut it = std::env::args().skip(1);
    while let Some(a) = it.next() {
        match a.as_str() {
            "--preset" => preset_name = Some(common::parse_value::<String>("--preset", it.next())?),
            "--generations" => {
                generations = Some(common::parse_value::<u32>("--generations", it.next())?)
            }
            "--seed" => seed = common::parse_value("--seed", it.next())?,
            "--sides" => sides = common::parse_value("--sides", it.next())?,
            "--angle" => angle = Some(common::parse_value::<f32>("--angle", it.next())?),
            "--shape" => {
                shape = match common::parse_value::<String>("--shape", it.next())?.as_str() {
                    "cylinder" => BranchShape::Cylinder,
                    "frustum" => BranchShape::Frustum,
                    s => return Err(format!("--shape must be cylinder or frustum, not {s}")),
                }
            }
            "--caps" => caps = true,
            "--out" => out = common::parse_value::<String>("--out", it.next())?,
            "--help" | "-h" => common::print_help(USAGE),
            s if s.starts_with("--") => return Err(format!("unknown option {s}\n{USAGE}")),
            s => file = Some(s.to_string()),
        }
    }
    let (grammar, mut options, default_generations) = match (file, preset_name) {
        (Some(_), Some(_)) => {
            return Err(format!(
                "give a grammar file or --preset, not both\n{USAGE}"
            ));
        }
        (Some(path), None) => {
            let grammar = LSystem::from_file(&path).map_err(|e| e.to_string())?;
            // cpfg models say how long to derive them, and draw with cpfg's turtle.
            let steps = grammar.derivation_length().unwrap_or(4);
            let symbols = SymbolTable::for_dialect(grammar.dialect());
            (
                grammar,
                TurtleOptions::default().with_symbols(symbols),
                steps,
            )
        }
        (None, name) => {
            let name = name.unwrap_or_else(|| "abop-ternary".to_string());
            let p = preset(&name).ok_or_else(|| format!("no preset called '{name}'"))?;
            (
                p.lsystem().map_err(|e| e.to_string())?,
                TurtleOptions::for_preset(p),
                p.generations,
            )
        }
    };
    if let Some(a) = angle {
        options.angle = a;
    }
    options = options
        .with_shape(shape)
        .with_radial_segments(sides)
        .with_caps(caps);
    let word = grammar
        .derive(generations.unwrap_or(default_generations), seed)
        .and_then(|w| grammar.interpretation(&w, seed))
        .map_err(|e| e.to_string())?;
    let mut builder = MeshBuilder::new(&options);
    let stats = interpret(&word, &options, &mut builder).map_err(|e| e.to_string())?;
    let mesh = builder.finish();
    let f = std::fs::File::create(&out).map_err(|e| format!("{out}: {e}"))?;
    write_obj(&mesh, f).map_err(|e| format!("{out}: {e}"))?;
    println!(
        "wrote {out}: {} vertices, {} triangles, {} segments, {} polygons, {} leaves ({} modules)",
        mesh.vertices.len(),
        mesh.triangle_count(),
        stats.segments,
        stats.polygons,
        stats.leaves,
        word.len()
    );
    Ok(())
}

fn main() -> ExitCode {
    common::finish(run())
}
