//! `UsdGeomMesh` prims: a prototype's bark or leaves, numbered onto the vertices it uses, and
//! the terrain.

use sylva_terrain::TerrainMesh;
use sylva_turtle::Vertex;

use super::text::{array_of, tuple};

/// A triangle mesh as a USD mesh holds it: per-vertex positions, normals, texture
/// coordinates (USD's `st`, t up the image) and optionally colours.
#[derive(Debug, Clone, Default, PartialEq)]
pub(super) struct MeshData {
    pub(super) positions: Vec<[f32; 3]>,
    pub(super) normals: Vec<[f32; 3]>,
    pub(super) st: Vec<[f32; 2]>,
    pub(super) colours: Option<Vec<[f32; 3]>>,
    /// A tree vertex's card order and snow catch ([`sylva_forest::vertex_phenology`]).
    pub(super) phenology: Option<Vec<[f32; 2]>>,
    pub(super) triangles: Vec<u32>,
}

/// glTF's texture coordinates run down the image from its top row; USD's `t` runs up from
/// the bottom row.
fn st_of(uv: [f32; 2]) -> [f32; 2] {
    [uv[0], 1.0 - uv[1]]
}

impl MeshData {
    /// The triangles `triangles` (indices into `vertices`) as a mesh of their own holding
    /// only the vertices they use, in order of first use, with their seasons' data (leaf
    /// `cards` or bark). `scratch` has an entry per vertex, all `u32::MAX`, and is left so.
    pub(super) fn of_triangles(
        vertices: &[Vertex],
        triangles: &[u32],
        cards: bool,
        scratch: &mut [u32],
    ) -> MeshData {
        let mut mesh = MeshData {
            phenology: Some(Vec::new()),
            ..MeshData::default()
        };
        let mut used = Vec::new();
        for &i in triangles {
            let slot = &mut scratch[i as usize];
            if *slot == u32::MAX {
                *slot = used.len() as u32;
                used.push(i);
                let v = &vertices[i as usize];
                mesh.positions.push(v.position);
                mesh.normals.push(v.normal);
                mesh.st.push(st_of(v.uv));
                if let Some(p) = &mut mesh.phenology {
                    p.push(sylva_forest::vertex_phenology(v, cards));
                }
            }
            mesh.triangles.push(*slot);
        }
        for i in used {
            scratch[i as usize] = u32::MAX;
        }
        mesh
    }

    /// The terrain, its vertices coloured `colours` (linear RGB).
    pub(super) fn of_terrain(terrain: &TerrainMesh, colours: Vec<[f32; 3]>) -> MeshData {
        MeshData {
            positions: terrain.vertices.iter().map(|v| v.position).collect(),
            normals: terrain.vertices.iter().map(|v| v.normal).collect(),
            st: terrain.vertices.iter().map(|v| st_of(v.uv)).collect(),
            colours: Some(colours),
            phenology: None,
            triangles: terrain.indices.clone(),
        }
    }

    /// The lowest and highest corner of the positions (zero for no vertices).
    pub(super) fn extent(&self) -> [[f32; 3]; 2] {
        let mut lo = [f32::INFINITY; 3];
        let mut hi = [f32::NEG_INFINITY; 3];
        for p in &self.positions {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        if self.positions.is_empty() {
            return [[0.0; 3]; 2];
        }
        [lo, hi]
    }

    /// Appends the mesh as `def Mesh "name"` at `indent`, bound to the material at
    /// `material`; leaf cards are `double_sided`.
    pub(super) fn write(
        &self,
        out: &mut String,
        (indent, name): (&str, &str),
        material: &str,
        double_sided: bool,
    ) {
        let i = indent;
        out.push_str(&format!(
            "{i}def Mesh \"{name}\" (\n{i}    prepend apiSchemas = [\"MaterialBindingAPI\"]\n{i})\n{i}{{\n"
        ));
        if double_sided {
            out.push_str(&format!("{i}    uniform bool doubleSided = 1\n"));
        }
        let [lo, hi] = self.extent();
        out.push_str(&format!("{i}    float3[] extent = ["));
        tuple(out, &lo);
        out.push_str(", ");
        tuple(out, &hi);
        out.push_str("]\n");
        out.push_str(&format!("{i}    int[] faceVertexCounts = "));
        array_of(out, 0..self.triangles.len() / 3, |o, _| o.push('3'));
        out.push_str(&format!("\n{i}    int[] faceVertexIndices = "));
        array_of(out, &self.triangles, |o, k| o.push_str(&k.to_string()));
        out.push_str(&format!("\n{i}    rel material:binding = <{material}>\n"));
        out.push_str(&format!("{i}    normal3f[] normals = "));
        array_of(out, &self.normals, |o, n| tuple(o, n));
        out.push_str(&format!(
            " (\n{i}        interpolation = \"vertex\"\n{i}    )\n"
        ));
        out.push_str(&format!("{i}    point3f[] points = "));
        array_of(out, &self.positions, |o, p| tuple(o, p));
        out.push('\n');
        if let Some(colours) = &self.colours {
            out.push_str(&format!("{i}    color3f[] primvars:displayColor = "));
            array_of(out, colours, |o, c| tuple(o, c));
            out.push_str(&format!(
                " (\n{i}        interpolation = \"vertex\"\n{i}    )\n"
            ));
        }
        if let Some(phenology) = &self.phenology {
            pairs_per_vertex(out, i, "float2[] primvars:sylva:phenology", phenology);
        }
        pairs_per_vertex(out, i, "texCoord2f[] primvars:st", &self.st);
        out.push_str(&format!(
            "{i}    uniform token subdivisionScheme = \"none\"\n{i}}}\n"
        ));
    }
}

/// A primvar of two numbers a vertex, `{indent}    declaration = [(a, b), ...]`, with
/// vertex interpolation.
fn pairs_per_vertex(out: &mut String, indent: &str, declaration: &str, values: &[[f32; 2]]) {
    out.push_str(&format!("{indent}    {declaration} = "));
    array_of(out, values, |o, pair| tuple(o, pair));
    out.push_str(&format!(
        " (\n{indent}        interpolation = \"vertex\"\n{indent}    )\n"
    ));
}

#[cfg(test)]
mod tests {
    use super::*;

    fn vertex(x: f32, v: f32) -> Vertex {
        Vertex {
            position: [x, 0.0, 0.0],
            normal: [0.0, 1.0, 0.0],
            uv: [0.25, v],
            wind: [0.0; 4],
        }
    }

    #[test]
    fn a_span_keeps_only_its_vertices_in_order_of_first_use() {
        let vertices: Vec<Vertex> = (0..6).map(|k| vertex(k as f32, 0.0)).collect();
        let mut scratch = vec![u32::MAX; vertices.len()];
        let mesh = MeshData::of_triangles(&vertices, &[4, 2, 5, 5, 2, 1], false, &mut scratch);
        assert_eq!(mesh.triangles, vec![0, 1, 2, 2, 1, 3]);
        let xs: Vec<f32> = mesh.positions.iter().map(|p| p[0]).collect();
        assert_eq!(xs, vec![4.0, 2.0, 5.0, 1.0]);
        assert!(scratch.iter().all(|&s| s == u32::MAX), "scratch left clean");
        assert_eq!(mesh.extent(), [[1.0, 0.0, 0.0], [5.0, 0.0, 0.0]]);
    }

    #[test]
    fn t_runs_up_the_image() {
        let vertices = [vertex(0.0, 0.0), vertex(1.0, 0.25), vertex(2.0, 3.0)];
        let mut scratch = vec![u32::MAX; 3];
        let mesh = MeshData::of_triangles(&vertices, &[0, 1, 2], false, &mut scratch);
        assert_eq!(mesh.st, vec![[0.25, 1.0], [0.25, 0.75], [0.25, -2.0]]);
    }

    #[test]
    fn a_mesh_prim_names_its_material_and_counts_its_faces() {
        let vertices = [vertex(0.0, 0.0), vertex(1.0, 0.0), vertex(2.0, 1.0)];
        let mut scratch = vec![u32::MAX; 3];
        let mesh = MeshData::of_triangles(&vertices, &[0, 1, 2], false, &mut scratch);
        let mut out = String::new();
        mesh.write(
            &mut out,
            ("  ", "leaves"),
            "/Forest/Materials/oak_leaves",
            true,
        );
        assert!(out.starts_with("  def Mesh \"leaves\" (\n"));
        assert!(out.contains("uniform bool doubleSided = 1"));
        assert!(out.contains("int[] faceVertexCounts = [3]\n"));
        assert!(out.contains("int[] faceVertexIndices = [0, 1, 2]\n"));
        assert!(out.contains("rel material:binding = </Forest/Materials/oak_leaves>"));
        assert!(out.contains("point3f[] points = [(0, 0, 0), (1, 0, 0), (2, 0, 0)]"));
        assert!(out.contains("float3[] extent = [(0, 0, 0), (2, 0, 0)]"));
        assert!(out.ends_with("  }\n"));
    }
}
