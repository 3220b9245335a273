//! Triangle meshes of branches, polygons and leaves, ready for GPU upload.

use bytemuck::{Pod, Zeroable};
use glam::{Affine3A, Vec3};

/// One mesh vertex: 48 bytes, `#[repr(C)]` and `Pod` for direct upload.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default, Pod, Zeroable)]
pub struct Vertex {
    /// Position.
    pub position: [f32; 3],
    /// Unit normal.
    pub normal: [f32; 3],
    /// Texture coordinates: on branches u runs once around the circumference (0 to 1) and v
    /// along the length, one unit per circumference travelled, so a bark texture that tiles
    /// once around a branch keeps square texels on thick and thin branches alike.
    pub uv: [f32; 2],
    /// Wind data: xyz is the pivot, where the vertex's branch leaves its parent (a leaf's
    /// own base for leaf cards), in the mesh's space, so it moves with any transform applied
    /// to the vertex; w is the branch's hierarchy depth (its bracket depth, 0 for the trunk;
    /// a leaf card is one deeper than the branch carrying it) plus a phase in `[0, 1)` drawn
    /// per branch: `floor(w)` is the depth, `fract(w)` the phase. See [`Wind`].
    pub wind: [f32; 4],
}

/// The wind data of a vertex, unpacked from [`Vertex::wind`].
///
/// ```
/// use sylva_turtle::{Wind, Vertex};
/// let v = Vertex { wind: [1.0, 2.0, 3.0, 4.25], ..Default::default() };
/// assert_eq!(Wind::of(&v), Wind { pivot: [1.0, 2.0, 3.0], depth: 4, phase: 0.25 });
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wind {
    /// Where the branch leaves its parent.
    pub pivot: [f32; 3],
    /// Bracket depth of the branch.
    pub depth: u32,
    /// A per-branch phase in `[0, 1)`, so that branches do not sway in step.
    pub phase: f32,
}

impl Wind {
    /// Unpacks a vertex's wind data.
    pub fn of(vertex: &Vertex) -> Wind {
        let w = vertex.wind[3].max(0.0);
        Wind {
            pivot: [vertex.wind[0], vertex.wind[1], vertex.wind[2]],
            depth: w.floor() as u32,
            phase: w.fract(),
        }
    }

    /// Packs into [`Vertex::wind`]'s layout.
    pub fn packed(&self) -> [f32; 4] {
        // Keep the fraction below 1 after rounding to f32 next to large depths.
        let phase = self.phase.clamp(0.0, 0.999);
        [
            self.pivot[0],
            self.pivot[1],
            self.pivot[2],
            self.depth as f32 + phase,
        ]
    }

    /// The wind data of a branch whose first segment is `segment`: phase drawn from its id.
    pub(crate) fn branch(pivot: Vec3, depth: u32, segment: u32) -> Wind {
        Wind {
            pivot: pivot.to_array(),
            depth,
            phase: sylva_base::hash::unit_f32(sylva_base::hash::mix(u64::from(segment) + 1)),
        }
    }
}

/// Which surface a triangle belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Material {
    /// Branch tubes.
    Bark,
    /// Polygons and leaves.
    Leaf,
}

/// Vertex buffer shared by two index lists, one per [`Material`].
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Mesh {
    /// All vertices.
    pub vertices: Vec<Vertex>,
    /// Triangles of branch tubes (three indices each).
    pub bark: Vec<u32>,
    /// Triangles of polygons and leaves.
    pub leaves: Vec<u32>,
    /// The colour index of each bark triangle (cpfg's and L-Py's `;` and `,`); empty when the
    /// turtle never changed colour.
    pub bark_colours: Vec<u32>,
    /// The colour index of each leaf triangle; empty when the turtle never changed colour.
    pub leaf_colours: Vec<u32>,
}

impl Mesh {
    /// Number of triangles of both materials.
    pub fn triangle_count(&self) -> usize {
        (self.bark.len() + self.leaves.len()) / 3
    }

    /// Bytes of vertex and index data.
    pub fn byte_size(&self) -> usize {
        self.vertices.len() * size_of::<Vertex>() + (self.bark.len() + self.leaves.len()) * 4
    }

    /// Indices of one material.
    pub fn indices(&self, material: Material) -> &[u32] {
        match material {
            Material::Bark => &self.bark,
            Material::Leaf => &self.leaves,
        }
    }

    /// Smallest box holding every vertex, or `None` for an empty mesh.
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        let mut it = self.vertices.iter().map(|v| Vec3::from(v.position));
        let first = it.next()?;
        Some(it.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p))))
    }

    /// Every triangle of both materials as world-space corner positions under `transform`.
    pub fn triangles(&self, transform: &Affine3A) -> impl Iterator<Item = [Vec3; 3]> + '_ {
        let t = *transform;
        self.bark
            .chunks_exact(3)
            .chain(self.leaves.chunks_exact(3))
            .map(move |tri| {
                [tri[0], tri[1], tri[2]]
                    .map(|i| t.transform_point3(Vec3::from(self.vertices[i as usize].position)))
            })
    }
}
