//! Wavefront OBJ export of one mesh.

use std::io::{self, Write};

use crate::mesh::Mesh;

/// Writes `mesh` as OBJ with normals and texture coordinates, in two groups `bark` and
/// `leaves`; where the turtle changed colour, each run of triangles names its colour index
/// as material `colour_N` (`usemtl`).
///
/// ```
/// let mut out = Vec::new();
/// sylva_turtle::write_obj(&sylva_turtle::Mesh::default(), &mut out).unwrap();
/// assert!(String::from_utf8(out).unwrap().starts_with("# sylva"));
/// ```
pub fn write_obj<W: Write>(mesh: &Mesh, out: W) -> io::Result<()> {
    let mut w = io::BufWriter::new(out);
    writeln!(
        w,
        "# sylva tree: {} vertices, {} triangles",
        mesh.vertices.len(),
        mesh.triangle_count()
    )?;
    for v in &mesh.vertices {
        writeln!(w, "v {} {} {}", v.position[0], v.position[1], v.position[2])?;
    }
    for v in &mesh.vertices {
        writeln!(w, "vn {} {} {}", v.normal[0], v.normal[1], v.normal[2])?;
    }
    for v in &mesh.vertices {
        writeln!(w, "vt {} {}", v.uv[0], v.uv[1])?;
    }
    for (name, indices, colours) in [
        ("bark", &mesh.bark, &mesh.bark_colours),
        ("leaves", &mesh.leaves, &mesh.leaf_colours),
    ] {
        if indices.is_empty() {
            continue;
        }
        writeln!(w, "g {name}")?;
        let mut current = None;
        for (k, t) in indices.chunks_exact(3).enumerate() {
            if let Some(&colour) = colours.get(k)
                && current != Some(colour)
            {
                writeln!(w, "usemtl colour_{colour}")?;
                current = Some(colour);
            }
            let [a, b, c] = [t[0] + 1, t[1] + 1, t[2] + 1];
            writeln!(w, "f {a}/{a}/{a} {b}/{b}/{b} {c}/{c}/{c}")?;
        }
    }
    w.flush()
}
