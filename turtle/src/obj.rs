//! Wavefront OBJ export of one mesh.

use std::io::{self, Write};

use crate::mesh::Mesh;

/// Writes `mesh` as OBJ with normals and texture coordinates, in two groups `bark` and
/// `leaves`.
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
    for (name, indices) in [("bark", &mesh.bark), ("leaves", &mesh.leaves)] {
        if indices.is_empty() {
            continue;
        }
        writeln!(w, "g {name}")?;
        for t in indices.chunks_exact(3) {
            let [a, b, c] = [t[0] + 1, t[1] + 1, t[2] + 1];
            writeln!(w, "f {a}/{a}/{a} {b}/{b}/{b} {c}/{c}/{c}")?;
        }
    }
    w.flush()
}
