//! Triangle meshes of heightmaps, with a stride for coarser levels of detail.

use bytemuck::{Pod, Zeroable};
use glam::Vec3;

use crate::error::{OutOfRange, TerrainError};
use crate::heightmap::Heightmap;

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
        let mut vertices = Vec::with_capacity(m * m);
        let s = self.spacing();
        for j in 0..m {
            for i in 0..m {
                let (x, z) = (i * stride, j * stride);
                let wx = self.origin().x + x as f32 * s;
                let wz = self.origin().y + z as f32 * s;
                let normal = self.grid_normal(x, z);
                vertices.push(TerrainVertex {
                    position: Vec3::new(wx, self.get(x, z), wz).to_array(),
                    normal: normal.to_array(),
                    uv: [i as f32 / (m - 1) as f32, j as f32 / (m - 1) as f32],
                });
            }
        }
        let mut indices = Vec::with_capacity((m - 1) * (m - 1) * 6);
        for j in 0..m as u32 - 1 {
            for i in 0..m as u32 - 1 {
                let a = j * m as u32 + i;
                let (b, c, d) = (a + 1, a + m as u32, a + m as u32 + 1);
                indices.extend_from_slice(&[a, c, d, a, d, b]);
            }
        }
        Ok(TerrainMesh { vertices, indices })
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
