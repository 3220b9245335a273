//! `sylva tree`: derives a tree, meshes it with the turtle and writes a Wavefront OBJ file.

use std::path::PathBuf;

use clap::{Args, ValueEnum};
use sylva::lsys::preset;
use sylva::turtle::{BranchShape, MeshBuilder, SymbolTable, TurtleOptions, interpret, write_obj};

use crate::Failure;
use crate::derive::{grammar, presets_help};

/// Branch shapes on the command line.
#[derive(Debug, Clone, Copy, ValueEnum)]
enum Shape {
    /// A cylinder per segment.
    Cylinder,
    /// Frustums sharing rings, tapering along the branch.
    Frustum,
}

/// `sylva tree`'s flags.
#[derive(Debug, Args)]
#[command(after_help = presets_help())]
pub(crate) struct TreeArgs {
    /// A grammar file (sylva's notation, cpfg's .l or L-Py's .lpy).
    #[arg(conflicts_with = "preset")]
    file: Option<PathBuf>,
    /// A bundled grammar (default abop-ternary).
    #[arg(long, value_name = "NAME")]
    preset: Option<String>,
    /// Generations to derive (default: the grammar's own).
    #[arg(long, value_name = "N")]
    generations: Option<u32>,
    /// Seed of stochastic productions.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Turning angle in degrees (default: the grammar's).
    #[arg(long, value_name = "DEG")]
    angle: Option<f32>,
    /// Branch shape.
    #[arg(long, value_enum, default_value_t = Shape::Frustum)]
    shape: Shape,
    /// Sides of each branch's rings.
    #[arg(long, value_name = "K", default_value_t = 8)]
    sides: u32,
    /// Close branch ends with caps.
    #[arg(long)]
    caps: bool,
    /// The OBJ file to write.
    #[arg(long, value_name = "FILE", default_value = "tree.obj")]
    out: PathBuf,
    /// Print nothing but errors.
    #[arg(long, short)]
    quiet: bool,
}

pub(crate) fn run(args: TreeArgs) -> Result<(), Failure> {
    let (grammar, default_generations) =
        grammar(args.file.as_ref(), args.preset.as_deref(), "abop-ternary")?;
    let mut options = match &args.file {
        // cpfg models draw with cpfg's turtle.
        Some(_) => {
            TurtleOptions::default().with_symbols(SymbolTable::for_dialect(grammar.dialect()))
        }
        None => preset(args.preset.as_deref().unwrap_or("abop-ternary"))
            .map(TurtleOptions::for_preset)
            .unwrap_or_default(),
    };
    if let Some(a) = args.angle {
        options.angle = a;
    }
    let shape = match args.shape {
        Shape::Cylinder => BranchShape::Cylinder,
        Shape::Frustum => BranchShape::Frustum,
    };
    options = options
        .with_shape(shape)
        .with_radial_segments(args.sides)
        .with_caps(args.caps);
    let word = grammar
        .derive(args.generations.unwrap_or(default_generations), args.seed)
        .and_then(|w| grammar.interpretation(&w, args.seed))?;
    let mut builder = MeshBuilder::new(&options);
    let stats = interpret(&word, &options, &mut builder)?;
    let mesh = builder.finish();
    sylva::base::file::write(&args.out, |w| write_obj(&mesh, w))?;
    if !args.quiet {
        println!(
            "wrote {}: {} vertices, {} triangles, {} segments, {} polygons, {} leaves ({} modules)",
            args.out.display(),
            mesh.vertices.len(),
            mesh.triangle_count(),
            stats.segments,
            stats.polygons,
            stats.leaves,
            word.len()
        );
    }
    Ok(())
}
