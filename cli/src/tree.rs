//! `sylva tree`: derives a tree, meshes it with the turtle and writes a Wavefront OBJ file.

use std::path::PathBuf;

use clap::{Args, ValueEnum};
use sylva::turtle::{BranchShape, MeshBuilder, interpret, write_obj};

use crate::Failure;
use crate::grammar::{GrammarArgs, presets_help};

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
    #[command(flatten)]
    grammar: GrammarArgs,
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
    let grammar = args.grammar.load("abop-ternary")?;
    let mut options = grammar.turtle();
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
    let (lsystem, seed) = (&grammar.lsystem, args.grammar.seed);
    let word = lsystem
        .derive(grammar.generations, seed)
        .and_then(|w| lsystem.interpretation(&w, seed))?;
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
