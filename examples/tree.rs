//! Derives a tree, meshes it with the turtle and writes a Wavefront OBJ: the path from a
//! grammar to geometry (`interpret` into a `MeshBuilder`).
//!
//! ```text
//! cargo run --example tree [PRESET] [OUT.obj]
//! ```
//!
//! `sylva tree` does the same for any grammar file, with flags for shape, sides and caps.

use sylva::lsys::preset;
use sylva::turtle::{MeshBuilder, TurtleOptions, interpret, write_obj};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let name = args.next().unwrap_or_else(|| "abop-ternary".into());
    let out = args.next().unwrap_or_else(|| "tree.obj".into());
    let p = preset(&name).ok_or_else(|| format!("no preset called '{name}'"))?;
    let grammar = p.lsystem()?;
    let options = TurtleOptions::for_preset(p);
    let word = grammar.derive(p.generations, 1)?;
    let mut builder = MeshBuilder::new(&options);
    let stats = interpret(&word, &options, &mut builder)?;
    let mesh = builder.finish();
    assert!(mesh.triangle_count() > 0 && stats.segments > 0);
    sylva::base::file::write(&out, |w| write_obj(&mesh, w))?;
    println!(
        "wrote {out}: {} triangles from {} segments",
        mesh.triangle_count(),
        stats.segments
    );
    Ok(())
}
