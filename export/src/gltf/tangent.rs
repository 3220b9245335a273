//! Per-vertex tangents from texture coordinates, for the bark's normal map: glTF clients are
//! told the tangent space rather than left to generate their own, which the specification
//! warns may differ between implementations.

use glam::{Vec2, Vec3};
use sylva_turtle::Vertex;

/// glTF `TANGENT`s of `vertices` (xyz along increasing u, w the handedness, so that the
/// bitangent is `cross(normal, xyz) * w`), accumulated over `triangles` from their uv
/// gradients and made orthogonal to each normal. Vertices no triangle gives a usable
/// gradient get any unit tangent perpendicular to their normal.
pub(super) fn tangents(vertices: &[Vertex], triangles: &[u32]) -> Vec<[f32; 4]> {
    let mut along_u = vec![Vec3::ZERO; vertices.len()];
    let mut along_v = vec![Vec3::ZERO; vertices.len()];
    for t in triangles.chunks_exact(3) {
        let [a, b, c] = [t[0], t[1], t[2]].map(|i| i as usize);
        let (Some(va), Some(vb), Some(vc)) = (vertices.get(a), vertices.get(b), vertices.get(c))
        else {
            continue;
        };
        let p = |v: &Vertex| Vec3::from(v.position);
        let uv = |v: &Vertex| Vec2::from(v.uv);
        let (e1, e2) = (p(vb) - p(va), p(vc) - p(va));
        let (d1, d2) = (uv(vb) - uv(va), uv(vc) - uv(va));
        let det = d1.x * d2.y - d2.x * d1.y;
        if det.abs() < 1e-12 {
            continue;
        }
        let tu = (e1 * d2.y - e2 * d1.y) / det;
        let tv = (e2 * d1.x - e1 * d2.x) / det;
        if !(tu.is_finite() && tv.is_finite()) {
            continue;
        }
        for i in [a, b, c] {
            along_u[i] += tu;
            along_v[i] += tv;
        }
    }
    vertices
        .iter()
        .zip(along_u.iter().zip(&along_v))
        .map(|(v, (&tu, &tv))| {
            let n = Vec3::from(v.normal).normalize_or(Vec3::Y);
            let t = (tu - n * n.dot(tu))
                .try_normalize()
                .unwrap_or_else(|| n.any_orthonormal_vector());
            let w = if n.cross(t).dot(tv) < 0.0 { -1.0 } else { 1.0 };
            [t.x, t.y, t.z, w]
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn vertex(position: [f32; 3], uv: [f32; 2]) -> Vertex {
        Vertex {
            position,
            normal: [0.0, 1.0, 0.0],
            uv,
            ..Default::default()
        }
    }

    #[test]
    fn tangent_follows_u_and_handedness_follows_v() {
        // u along +x; v along +z or -z.
        for (v_dir, w) in [(1.0, -1.0), (-1.0, 1.0)] {
            let quad = [
                vertex([0.0, 0.0, 0.0], [0.0, 0.0]),
                vertex([1.0, 0.0, 0.0], [1.0, 0.0]),
                vertex([1.0, 0.0, v_dir], [1.0, 1.0]),
                vertex([0.0, 0.0, v_dir], [0.0, 1.0]),
            ];
            for t in tangents(&quad, &[0, 1, 2, 0, 2, 3]) {
                assert_eq!(t, [1.0, 0.0, 0.0, w], "v along z * {v_dir}");
            }
        }
    }

    #[test]
    fn unused_and_degenerate_vertices_get_a_unit_perpendicular_tangent() {
        let v = [
            vertex([0.0, 0.0, 0.0], [0.5, 0.5]),
            vertex([1.0, 0.0, 0.0], [0.5, 0.5]),
            vertex([0.0, 0.0, 1.0], [0.5, 0.5]),
            vertex([5.0, 0.0, 5.0], [0.0, 0.0]),
        ];
        for t in tangents(&v, &[0, 1, 2, 7, 8, 9]) {
            let t3 = Vec3::new(t[0], t[1], t[2]);
            assert!((t3.length() - 1.0).abs() < 1e-5 && t3.y.abs() < 1e-5 && t[3].abs() == 1.0);
        }
    }
}
