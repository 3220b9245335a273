//! Triangle meshes of branches, polygons and leaves, ready for GPU upload.

use bytemuck::{Pod, Zeroable};
use glam::{Affine3A, Quat, Vec3};

use crate::frame::Frame;
use crate::options::{BranchShape, TurtleOptions};
use crate::sink::{GeometrySink, Segment};

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
    fn branch(pivot: Vec3, depth: u32, segment: u32) -> Wind {
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

/// The last ring of an axis: where the next segment of the axis starts.
#[derive(Debug, Clone, Copy, Default)]
struct RingEnd {
    first_vertex: u32,
    v: f32,
    center: Vec3,
    /// The ring's own frame: heading and the two vectors its circle is drawn with. Carried
    /// along the axis by parallel transport, not taken from the turtle, so that a roll of the
    /// turtle between segments (`/`, `\`) does not twist the tube.
    ring: RingFrame,
    radius: f32,
    /// Wind data of the axis the ring belongs to, packed.
    wind: [f32; 4],
}

/// The orientation of one ring of a tube.
#[derive(Debug, Clone, Copy, Default)]
struct RingFrame {
    heading: Vec3,
    left: Vec3,
    up: Vec3,
}

impl RingFrame {
    fn of(frame: &Frame) -> Self {
        RingFrame {
            heading: frame.heading(),
            left: frame.left(),
            up: frame.up(),
        }
    }

    /// This frame carried to a new heading by the smallest rotation (parallel transport):
    /// rings along a bending axis keep their seam on the same side.
    fn transported(&self, heading: Vec3) -> Self {
        let turn = Quat::from_rotation_arc(self.heading, heading);
        RingFrame {
            heading,
            left: (turn * self.left).normalize(),
            up: (turn * self.up).normalize(),
        }
    }
}

/// Rings drawn up a flared trunk base.
const FLARE_RINGS: usize = 4;
/// How far up the trunk the flare's rings reach, in base radii.
const FLARE_REACH: f32 = 3.0;
/// The widest flare accepted (a base four times the trunk's radius).
const FLARE_MAX: f32 = 3.0;

/// A [`GeometrySink`] that builds a [`Mesh`]: tubes for segments, triangulated polygons, leaf
/// quads.
#[derive(Debug, Clone)]
pub struct MeshBuilder {
    /// The mesh built so far.
    pub mesh: Mesh,
    shape: BranchShape,
    caps: bool,
    /// [`TurtleOptions::root_flare`], finite and not negative.
    root_flare: f32,
    circle: Vec<(f32, f32)>,
    ends: Vec<RingEnd>,
    /// Bracket depth of the last segment drawn: leaves and polygons sit one deeper.
    depth: u32,
    /// The turtle's colour index, and whether it ever changed (then triangles get colours).
    colour: u32,
    coloured: bool,
}

impl MeshBuilder {
    /// A builder using the meshing settings of `options` (shape, radial segments, caps).
    pub fn new(options: &TurtleOptions) -> Self {
        let sides = options.radial_segments.clamp(3, 1024);
        let circle = (0..=sides)
            .map(|i| {
                let t = std::f32::consts::TAU * i as f32 / sides as f32;
                (t.cos(), t.sin())
            })
            .collect();
        MeshBuilder {
            mesh: Mesh::default(),
            shape: options.shape,
            caps: options.caps,
            root_flare: if options.root_flare.is_finite() {
                options.root_flare.clamp(0.0, FLARE_MAX)
            } else {
                0.0
            },
            circle,
            ends: Vec::new(),
            depth: 0,
            colour: 0,
            coloured: false,
        }
    }

    /// Takes the mesh out, leaving the builder empty.
    pub fn finish(&mut self) -> Mesh {
        self.paint();
        std::mem::take(&mut self.mesh)
    }

    /// Gives the triangles added since the last colour change the colour in force.
    fn paint(&mut self) {
        if self.coloured {
            let colour = self.colour;
            self.mesh
                .bark_colours
                .resize(self.mesh.bark.len() / 3, colour);
            self.mesh
                .leaf_colours
                .resize(self.mesh.leaves.len() / 3, colour);
        }
    }

    fn ring(
        &mut self,
        center: Vec3,
        frame: &RingFrame,
        radius: f32,
        v: f32,
        wind: [f32; 4],
    ) -> u32 {
        let first = self.mesh.vertices.len() as u32;
        let (l, u) = (frame.left, frame.up);
        let sides = (self.circle.len() - 1) as f32;
        for (i, &(c, s)) in self.circle.iter().enumerate() {
            let d = l * c + u * s;
            self.mesh.vertices.push(Vertex {
                position: (center + d * radius).to_array(),
                normal: d.to_array(),
                uv: [i as f32 / sides, v],
                wind,
            });
        }
        first
    }

    /// Rings up the flared base of segment `s`, from the first ring `a` at texture height
    /// `v0`: the frustum's radius times `1 + flare * e^(-h / (1.2 r))` at height `h` over
    /// [`FLARE_RINGS`] rings within the segment's first [`FLARE_REACH`] base radii (and its
    /// first 60%). The base ring itself is widened in place. Returns the last ring and its `v`.
    fn flare(
        &mut self,
        s: &Segment,
        ring: &RingFrame,
        (a, v0): (u32, f32),
        wind: [f32; 4],
    ) -> (u32, f32) {
        if self.root_flare <= 0.0 || s.length <= 0.0 || s.start_radius <= 0.0 {
            return (a, v0);
        }
        let (r0, flare) = (s.start_radius, self.root_flare);
        let reach = (FLARE_REACH * r0).min(0.6 * s.length);
        let radius_at = |h: f32| {
            let t = h / s.length;
            let frustum = s.start_radius + (s.end_radius - s.start_radius) * t;
            frustum * (1.0 + flare * (-h / (1.2 * r0)).exp())
        };
        // Widen the base ring where it stands.
        let start = s.start();
        let base = radius_at(0.0);
        for (k, &(c, sn)) in self.circle.iter().enumerate() {
            let d = ring.left * c + ring.up * sn;
            self.mesh.vertices[a as usize + k].position = (start + d * base).to_array();
        }
        let heading = s.frame.heading();
        let (mut last, mut v, mut below) = (a, v0, (0.0f32, base));
        for k in 1..=FLARE_RINGS {
            let h = reach * k as f32 / FLARE_RINGS as f32;
            let r = radius_at(h);
            v += (h - below.0) / (std::f32::consts::PI * (r + below.1)).max(1e-4);
            let next = self.ring(start + heading * h, ring, r, v, wind);
            self.join(last, next);
            (last, below) = (next, (h, r));
        }
        (last, v)
    }

    fn join(&mut self, a: u32, b: u32) {
        let n = (self.circle.len() - 1) as u32;
        for i in 0..n {
            let (a0, a1, b0, b1) = (a + i, a + i + 1, b + i, b + i + 1);
            self.mesh.bark.extend_from_slice(&[a0, a1, b1, a0, b1, b0]);
        }
    }

    fn cap(
        &mut self,
        center: Vec3,
        frame: &RingFrame,
        radius: f32,
        facing_forward: bool,
        wind: [f32; 4],
    ) {
        let normal = if facing_forward {
            frame.heading
        } else {
            -frame.heading
        };
        let (l, u) = (frame.left, frame.up);
        let first = self.mesh.vertices.len() as u32;
        self.mesh.vertices.push(Vertex {
            position: center.to_array(),
            normal: normal.to_array(),
            uv: [0.5, 0.5],
            wind,
        });
        let n = self.circle.len() - 1;
        for &(c, s) in &self.circle[..n] {
            self.mesh.vertices.push(Vertex {
                position: (center + (l * c + u * s) * radius).to_array(),
                normal: normal.to_array(),
                uv: [0.5 + 0.5 * c, 0.5 + 0.5 * s],
                wind,
            });
        }
        for i in 0..n as u32 {
            let (p, q) = (first + 1 + i, first + 1 + (i + 1) % n as u32);
            if facing_forward {
                self.mesh.bark.extend_from_slice(&[first, p, q]);
            } else {
                self.mesh.bark.extend_from_slice(&[first, q, p]);
            }
        }
    }

    fn quad(&mut self, corners: [Vec3; 4], normal: Vec3, wind: [f32; 4]) {
        let first = self.mesh.vertices.len() as u32;
        let uvs = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        for (p, uv) in corners.into_iter().zip(uvs) {
            self.mesh.vertices.push(Vertex {
                position: p.to_array(),
                normal: normal.to_array(),
                uv,
                wind,
            });
        }
        self.mesh.leaves.extend_from_slice(&[
            first,
            first + 1,
            first + 2,
            first,
            first + 2,
            first + 3,
        ]);
    }
}

impl GeometrySink for MeshBuilder {
    fn begin(&mut self) {
        self.ends.clear();
        self.depth = 0;
        self.paint();
        self.colour = 0;
    }

    fn segment(&mut self, s: &Segment) {
        let start = s.start();
        let end = s.end();
        let shared = match (self.shape, s.continues_parent, s.parent) {
            (BranchShape::Frustum, true, Some(p)) => self.ends.get(p as usize).copied(),
            _ => None,
        };
        let (a, v0, ring, wind) = match shared {
            Some(e) => (
                e.first_vertex,
                e.v,
                e.ring.transported(s.frame.heading()),
                e.wind,
            ),
            None => {
                // A new axis: its pivot is where it starts.
                let wind = Wind::branch(start, s.depth, s.id).packed();
                let ring = RingFrame::of(&s.frame);
                if self.caps {
                    self.cap(start, &ring, s.start_radius, false, wind);
                }
                let first = self.ring(start, &ring, s.start_radius, 0.0, wind);
                (first, 0.0, ring, wind)
            }
        };
        self.depth = s.depth;
        // The root flare: the first segment of the first axis widens towards the ground,
        // drawn as a few rings whose radius fades back to the frustum's.
        // The first segment drawn (id 0) has no parent; at depth 0 it is the tree's own base.
        let (a, v0) = if s.id == 0 && s.depth == 0 {
            self.flare(s, &ring, (a, v0), wind)
        } else {
            (a, v0)
        };
        // v advances by the length in circumferences at the segment's mean radius.
        let circumference = std::f32::consts::PI * (s.start_radius + s.end_radius);
        let v1 = v0 + s.length / circumference.max(1e-4);
        let b = self.ring(end, &ring, s.end_radius, v1, wind);
        self.join(a, b);
        let id = s.id as usize;
        if self.ends.len() <= id {
            self.ends.resize(id + 1, RingEnd::default());
        }
        self.ends[id] = RingEnd {
            first_vertex: b,
            v: v1,
            center: end,
            ring,
            radius: s.end_radius,
            wind,
        };
        if self.caps && self.shape == BranchShape::Cylinder {
            self.cap(end, &ring, s.end_radius, true, wind);
        }
    }

    fn colour(&mut self, index: u32) {
        if index != self.colour {
            // The first change gives every earlier triangle colour 0.
            self.coloured = true;
            self.paint();
            self.colour = index;
        }
    }

    fn end(&mut self) {
        self.paint();
    }

    fn axis_end(&mut self, id: u32) {
        if self.caps
            && self.shape == BranchShape::Frustum
            && let Some(e) = self.ends.get(id as usize).copied()
        {
            self.cap(e.center, &e.ring, e.radius, true, e.wind);
        }
    }

    fn polygon(&mut self, vertices: &[Vec3]) {
        // Newell's method gives a robust normal for any simple polygon.
        let mut normal = Vec3::ZERO;
        for (i, a) in vertices.iter().enumerate() {
            let b = vertices[(i + 1) % vertices.len()];
            normal += Vec3::new(
                (a.y - b.y) * (a.z + b.z),
                (a.z - b.z) * (a.x + b.x),
                (a.x - b.x) * (a.y + b.y),
            );
        }
        let Some(normal) = normal.try_normalize() else {
            return;
        };
        let first = self.mesh.vertices.len() as u32;
        // A polygon sways about its first vertex, one level deeper than the last branch.
        let wind = Wind::branch(vertices[0], self.depth + 1, first).packed();
        for p in vertices {
            self.mesh.vertices.push(Vertex {
                position: p.to_array(),
                normal: normal.to_array(),
                uv: [0.5, 0.5],
                wind,
            });
        }
        for i in 1..vertices.len() as u32 - 1 {
            self.mesh
                .leaves
                .extend_from_slice(&[first, first + i, first + i + 1]);
        }
    }

    fn leaf(&mut self, frame: &Frame, size: [f32; 2]) {
        let (h, l) = (frame.heading() * size[0], frame.left() * (size[1] * 0.5));
        let p = frame.position;
        // A card flutters about its base, one level deeper than the branch carrying it; its
        // phase comes from its first vertex's index, distinct per card.
        let first = self.mesh.vertices.len() as u32;
        let wind = Wind::branch(p, self.depth + 1, first).packed();
        // Counter-clockwise seen from the up vector, which is the leaf's normal.
        self.quad([p + l, p - l, p - l + h, p + l + h], frame.up(), wind);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::interpret;

    /// The radius of every ring of `mesh` (each `sides + 1` vertices round an axis up y),
    /// from the bottom up.
    fn ring_radii(mesh: &Mesh, sides: usize) -> Vec<(f32, f32)> {
        mesh.vertices
            .chunks_exact(sides + 1)
            .map(|ring| {
                let [x, y, z] = ring[0].position;
                (y, (x * x + z * z).sqrt())
            })
            .collect()
    }

    fn trunk(flare: f32) -> Mesh {
        let word: sylva_lsys::Word = "!(0.4)F(4)".parse().unwrap();
        let options = TurtleOptions::default()
            .with_radial_segments(6)
            .with_root_flare(flare);
        let mut builder = MeshBuilder::new(&options);
        interpret(&word, &options, &mut builder).unwrap();
        builder.finish()
    }

    /// A flared base is (1 + flare) times the trunk's radius at the ground and narrows
    /// steadily to the trunk's radius within a few radii; no flare draws the plain frustum.
    #[test]
    fn the_root_flare_widens_the_base_and_fades_up_the_trunk() {
        let plain = ring_radii(&trunk(0.0), 6);
        assert_eq!(plain.len(), 2);
        let flared = ring_radii(&trunk(0.6), 6);
        assert_eq!(flared.len(), 2 + FLARE_RINGS);
        let (r, base) = (0.2, flared[0]);
        assert!(
            (base.0).abs() < 1e-6 && (base.1 - 1.6 * r).abs() < 1e-4,
            "{base:?}"
        );
        assert!(
            flared
                .windows(2)
                .all(|w| w[1].0 > w[0].0 && w[1].1 < w[0].1),
            "{flared:?}"
        );
        let top_of_flare = flared[FLARE_RINGS];
        assert!((top_of_flare.0 - FLARE_REACH * r).abs() < 1e-4);
        assert!(top_of_flare.1 < 1.1 * r, "{top_of_flare:?}");
        assert_eq!(flared.last(), plain.last());
        // Bad settings draw no flare rather than a broken one.
        assert_eq!(ring_radii(&trunk(f32::NAN), 6), plain);
    }
}
