//! Triangle meshes of heightmaps, with a stride for coarser levels of detail.

use bytemuck::{Pod, Zeroable};
use glam::Vec3;
use rayon::prelude::*;

use crate::error::{OutOfRange, TerrainError};
use crate::heightmap::Heightmap;

/// Fewest rows of vertices or quads a task makes.
const ROWS_PER_TASK: usize = 8;

/// `v` at `len` elements: kept as it is when it has that many already (their memory in use
/// is overwritten in place), else filled anew on every core (fresh pages are most of the
/// cost of a large mesh, and the kernel gives them to both cores at once).
fn resize<T: Default + Clone + Send + Sync>(v: &mut Vec<T>, len: usize) {
    if v.len() != len {
        v.clear();
        v.par_extend(rayon::iter::repeat_n(T::default(), len));
    }
}

/// One terrain vertex: 32 bytes, `#[repr(C)]` and `Pod` for direct upload.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default, Pod, Zeroable)]
pub struct TerrainVertex {
    /// World position.
    pub position: [f32; 3],
    /// Unit normal.
    pub normal: [f32; 3],
    /// Texture coordinates, 0 to 1 across the map.
    pub uv: [f32; 2],
}

/// An indexed triangle mesh of a terrain.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TerrainMesh {
    /// Vertices, row-major.
    pub vertices: Vec<TerrainVertex>,
    /// Triangles, counter-clockwise seen from above.
    pub indices: Vec<u32>,
}

impl Heightmap {
    /// A mesh of every `stride`-th sample in each direction (1 for full detail; `stride` must
    /// divide `size - 1`).
    ///
    /// ```
    /// let map = sylva_terrain::Heightmap::flat(9, 1.0).unwrap();
    /// let mesh = map.mesh(2).unwrap();
    /// assert_eq!(mesh.vertices.len(), 25);
    /// assert_eq!(mesh.indices.len(), 4 * 4 * 6);
    /// ```
    pub fn mesh(&self, stride: usize) -> Result<TerrainMesh, TerrainError> {
        let mut mesh = TerrainMesh::default();
        self.mesh_into(stride, &mut mesh)?;
        Ok(mesh)
    }

    /// The stride of a mesh whose vertices stand at least `spacing` metres apart, or as near
    /// as the map allows: the smallest power of two dividing `size - 1` that reaches it (1
    /// when the samples already do). A small world's map is as many samples as a large
    /// one's, so its full-detail mesh would be finer than its trees need and most of its
    /// file.
    ///
    /// ```
    /// let map = sylva_terrain::Heightmap::flat(257, 100.0 / 256.0).unwrap();
    /// assert_eq!(map.stride_for_spacing(1.5), 4);
    /// assert_eq!(map.stride_for_spacing(0.1), 1);
    /// ```
    pub fn stride_for_spacing(&self, spacing: f32) -> usize {
        let mut stride = 1;
        while self.spacing() * (stride as f32) < spacing
            && (self.size() - 1).is_multiple_of(stride * 2)
            && stride * 2 < self.size()
        {
            stride *= 2;
        }
        stride
    }

    /// [`Heightmap::mesh`] into `mesh`, whose vectors are reused: meshing again into memory
    /// already in use skips the cost of fresh pages, which is most of a large mesh's (a
    /// 4097 x 4097 mesh is 940 MB).
    ///
    /// ```
    /// let map = sylva_terrain::Heightmap::flat(9, 1.0).unwrap();
    /// let mut mesh = map.mesh(1).unwrap();
    /// map.mesh_into(2, &mut mesh).unwrap();
    /// assert_eq!(mesh, map.mesh(2).unwrap());
    /// ```
    pub fn mesh_into(&self, stride: usize, mesh: &mut TerrainMesh) -> Result<(), TerrainError> {
        let cells = self.size() - 1;
        if stride == 0 || !cells.is_multiple_of(stride) {
            return Err(OutOfRange {
                name: "stride",
                value: stride as f64,
                expected: "a divisor of size - 1",
            }
            .into());
        }
        let m = cells / stride + 1;
        let s = self.spacing();
        let origin = self.origin();
        // Vertices and triangles a row at a time on every core, written in place. The
        // vectors are sized first; a mesh of the same size keeps its memory untouched.
        let quads = m - 1;
        resize(&mut mesh.vertices, m * m);
        resize(&mut mesh.indices, quads * quads * 6);
        let last = (m - 1) as f32;
        let n = self.size();
        // What every row shares, worked out once: each column's x and u.
        let columns: Vec<(f32, f32)> = (0..m)
            .map(|i| (origin.x + (i * stride) as f32 * s, i as f32 / last))
            .collect();
        mesh.vertices
            .par_chunks_mut(m)
            .enumerate()
            .with_min_len(ROWS_PER_TASK)
            .for_each_init(Vec::new, |normals, (j, row)| {
                let z = j * stride;
                let (wz, v) = (origin.y + z as f32 * s, j as f32 / last);
                let heights = &self.heights()[z * n..(z + 1) * n];
                self.row_normals(z, stride, normals);
                let samples = heights.iter().step_by(stride);
                for (((vertex, normal), &(x, u)), &height) in row
                    .iter_mut()
                    .zip(normals.iter())
                    .zip(&columns)
                    .zip(samples)
                {
                    *vertex = TerrainVertex {
                        position: [x, height, wz],
                        normal: *normal,
                        uv: [u, v],
                    };
                }
            });
        let m32 = m as u32;
        if quads > 0 {
            mesh.indices
                .par_chunks_mut(quads * 6)
                .enumerate()
                .with_min_len(ROWS_PER_TASK)
                .for_each(|(j, row)| {
                    for (i, quad) in row.chunks_exact_mut(6).enumerate() {
                        let a = j as u32 * m32 + i as u32;
                        let (b, c, d) = (a + 1, a + m32, a + m32 + 1);
                        // Two triangles, counter-clockwise seen from above.
                        quad.copy_from_slice(&[a, c, d, a, d, b]);
                    }
                });
        }
        Ok(())
    }

    /// The normals of row `z`'s vertices (every `stride`-th sample) into `out`: the edges'
    /// by [`Heightmap::grid_normal`], the rest by the same arithmetic in a loop over the
    /// row that vectorises (the divisions and square roots were most of meshing's time
    /// one call at a time). The same bits as `grid_normal` gives for every vertex.
    fn row_normals(&self, z: usize, stride: usize, out: &mut Vec<[f32; 3]>) {
        let (n, last) = (self.size(), self.size() - 1);
        let m = last / stride + 1;
        out.clear();
        out.resize(m, [0.0; 3]);
        if z == 0 || z == last || m < 3 {
            for (i, normal) in out.iter_mut().enumerate() {
                *normal = self.grid_normal(i * stride, z).to_array();
            }
            return;
        }
        let h = self.heights();
        let (above, row, below) = (
            &h[(z - 1) * n..z * n],
            &h[z * n..(z + 1) * n],
            &h[(z + 1) * n..(z + 2) * n],
        );
        // Interior samples: both differences span two spacings.
        let across = 2.0 * self.spacing();
        for (i, normal) in out.iter_mut().enumerate().take(m - 1).skip(1) {
            let x = i * stride;
            let dx = (row[x + 1] - row[x - 1]) / across;
            let dz = (below[x] - above[x]) / across;
            // Vec3::normalize_or, term by term: the reciprocal of the length, or straight
            // up where it is not a positive finite number.
            let (a, b, c) = (-dx, 1.0f32, -dz);
            let recip = 1.0 / ((a * a + b * b) + c * c).sqrt();
            *normal = if recip.is_finite() && recip > 0.0 {
                [a * recip, b * recip, c * recip]
            } else {
                [0.0, 1.0, 0.0]
            };
        }
        out[0] = self.grid_normal(0, z).to_array();
        out[m - 1] = self.grid_normal(last, z).to_array();
    }

    /// Normal at a sample by central differences over one spacing (one-sided at the edges),
    /// the same as [`HeightField::normal`](crate::HeightField::normal) there but without the interpolation.
    fn grid_normal(&self, x: usize, z: usize) -> Vec3 {
        let last = self.size() - 1;
        let (x0, x1) = (x.saturating_sub(1), (x + 1).min(last));
        let (z0, z1) = (z.saturating_sub(1), (z + 1).min(last));
        let s = self.spacing();
        let dx = (self.get(x1, z) - self.get(x0, z)) / ((x1 - x0) as f32 * s);
        let dz = (self.get(x, z1) - self.get(x, z0)) / ((z1 - z0) as f32 * s);
        Vec3::new(-dx, 1.0, -dz).normalize_or(Vec3::Y)
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    proptest! {
        /// A row's normals are `grid_normal`'s, bit for bit, for every vertex of every row
        /// at every stride, on rough maps (steep differences included).
        #[test]
        fn row_normals_are_the_grid_normals(
            levels in 1u32..6,
            seed in any::<u64>(),
            amplitude in prop::sample::select(vec![0.0f32, 1.0, 300.0, 1e30]),
            stride_level in 0u32..3,
        ) {
            let size = (1usize << levels) + 1;
            let map = crate::DiamondSquare::new(size)
                .with_seed(seed)
                .with_amplitude(amplitude)
                .generate()
                .expect("valid");
            let stride = 1usize << stride_level.min(levels - 1);
            let mut normals = Vec::new();
            for z in (0..size).step_by(stride) {
                map.row_normals(z, stride, &mut normals);
                for (i, normal) in normals.iter().enumerate() {
                    let expected = map.grid_normal(i * stride, z).to_array();
                    prop_assert_eq!(normal.map(f32::to_bits), expected.map(f32::to_bits));
                }
            }
        }
    }
}
