//! `sylva tree`: derives a tree, meshes it with the turtle and writes a Wavefront OBJ file, or
//! a species' tree with its textures as binary glTF.

use std::path::{Path, PathBuf};

use clap::{Args, ValueEnum};
use sylva::forest::Species;
use sylva::turtle::{BranchShape, Mesh, MeshBuilder, interpret, write_obj};

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
    /// A species instead of a grammar: a species file, or a bundled species by name (oak,
    /// birch, spruce, pine, hazel, fir, larch, beech, sycamore, aspen, alder), drawn with its
    /// own turtle settings, colours and textures.
    #[arg(long, value_name = "FILE|NAME", conflicts_with_all = ["file", "preset", "angle", "shape", "sides", "caps"])]
    species: Option<String>,
    /// With --species: the day of the year to draw the tree on, 1 to 365, or spring,
    /// summer, autumn or winter (its leaves, autumn colour or bare crown, and snow).
    #[arg(long, value_name = "DAY", requires = "species", value_parser = crate::world::season_day)]
    season: Option<f32>,
    /// The file to write: Wavefront OBJ, or binary glTF with textures when it ends in .glb.
    #[arg(long, value_name = "FILE", default_value = "tree.obj")]
    out: PathBuf,
    /// Print nothing but errors.
    #[arg(long, short)]
    quiet: bool,
}

pub(crate) fn run(args: TreeArgs) -> Result<(), Failure> {
    if let Some(name) = &args.species {
        return species_tree(&args, name);
    }
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
    let mut species = Species::new("tree", lsystem.clone(), grammar.generations);
    species.turtle = options;
    write_tree(&args.out, &species, &mesh)?;
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

/// Writes `mesh` at `out`: binary glTF with `species`' materials and textures when the name
/// ends in .glb, else a Wavefront OBJ.
fn write_tree(out: &Path, species: &Species, mesh: &Mesh) -> Result<(), Failure> {
    let glb = out
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("glb"));
    if glb {
        sylva::export::write_tree_glb(species, mesh, out)?;
    } else {
        sylva::base::file::write(out, |w| write_obj(mesh, w))?;
    }
    Ok(())
}

/// One tree of a species file or bundled species, at the species' generations (or
/// `--generations`) from `--seed`.
fn species_tree(args: &TreeArgs, name: &str) -> Result<(), Failure> {
    let mut species = sylva::presets::named_or_file(name)?;
    if let Some(day) = args.season {
        species = species.in_season(day);
    }
    let generations = args.grammar.generations.unwrap_or(species.generations);
    let mesh = species.mesh(generations, args.grammar.seed)?;
    write_tree(&args.out, &species, &mesh)?;
    if !args.quiet {
        println!(
            "wrote {}: {} {} of {generations} generations (seed {}), {} vertices, {} triangles ({} of bark, {} of leaves)",
            args.out.display(),
            species.name,
            if generations < species.generations {
                "sapling"
            } else {
                "tree"
            },
            args.grammar.seed,
            mesh.vertices.len(),
            mesh.triangle_count(),
            mesh.bark.len() / 3,
            mesh.leaves.len() / 3,
        );
    }
    Ok(())
}
