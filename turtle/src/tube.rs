//! The builder of tube meshes: rings along each axis, joined into bark triangles, with leaf
//! quads and triangulated polygons.

use glam::{Quat, Vec3};

use crate::frame::Frame;
use crate::mesh::{Mesh, Vertex, Wind};
use crate::options::{BranchShape, TurtleOptions};
use crate::sink::{GeometrySink, Segment};
use crate::swell::{self, COLLAR_MAX, FLARE_MAX, Profile};

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
    /// [`TurtleOptions::branch_collar`], finite and not negative.
    branch_collar: f32,
    /// The radius of the tree's first segment: collars are drawn on branches of at least
    /// [`COLLAR_MIN_SHARE`] of it, where they can be seen.
    base_radius: f32,
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
            root_flare: finite_within(options.root_flare, FLARE_MAX),
            branch_collar: finite_within(options.branch_collar, COLLAR_MAX),
            base_radius: 0.0,
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

    /// Draws the extra rings of `profile` up segment `s` from the ring `a` at texture height
    /// `v0`, joining each to the one below; `base` widens the first ring in place. Returns
    /// the last ring and its `v`.
    fn swell(
        &mut self,
        s: &Segment,
        ring: &RingFrame,
        (a, v0): (u32, f32),
        (base, profile): (Option<f32>, &Profile),
        wind: [f32; 4],
    ) -> (u32, f32) {
        let start = s.start();
        let mut below = (0.0f32, s.start_radius);
        if let Some(base) = base {
            for (k, &(c, sn)) in self.circle.iter().enumerate() {
                let d = ring.left * c + ring.up * sn;
                self.mesh.vertices[a as usize + k].position = (start + d * base).to_array();
            }
            below.1 = base;
        }
        let heading = s.frame.heading();
        let (mut last, mut v) = (a, v0);
        for &(h, r) in profile.rings() {
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

/// The thinnest branch given a collar, as a share of the tree's base radius: thinner ones
/// would add rings no one sees.
const COLLAR_MIN_SHARE: f32 = 0.05;

/// `value` within `0..=max`, 0 when it is not a number.
fn finite_within(value: f32, max: f32) -> f32 {
    if value.is_finite() {
        value.clamp(0.0, max)
    } else {
        0.0
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
        // Where the segment's parent ended: the ring a continuing frustum shares, the texture
        // height a new axis continues, the surface a branch's collar meets.
        let parent = s.parent.and_then(|p| self.ends.get(p as usize)).copied();
        let shared = parent.filter(|_| self.shape == BranchShape::Frustum && s.continues_parent);
        let (a, v0, ring, wind) = match shared {
            Some(e) => (
                e.first_vertex,
                e.v,
                e.ring.transported(s.frame.heading()),
                e.wind,
            ),
            None => {
                // A new axis: its pivot is where it starts, and its bark continues the
                // parent's texture height there, so the bark runs on across the joint.
                let wind = Wind::branch(start, s.depth, s.id).packed();
                let ring = RingFrame::of(&s.frame);
                let v = parent.map_or(0.0, |e| e.v);
                if self.caps {
                    self.cap(start, &ring, s.start_radius, false, wind);
                }
                let first = self.ring(start, &ring, s.start_radius, v, wind);
                (first, v, ring, wind)
            }
        };
        self.depth = s.depth;
        // Where the tube swells: the root flare at the tree's base (the first segment drawn,
        // id 0, at depth 0), the collar where a branch leaves its parent.
        if s.id == 0 {
            self.base_radius = s.start_radius;
        }
        let swelling = if s.id == 0 && s.depth == 0 {
            swell::flare(s, self.root_flare).map(|(base, p)| (Some(base), p))
        } else if !s.continues_parent && s.start_radius >= COLLAR_MIN_SHARE * self.base_radius {
            parent
                .and_then(|e| swell::collar(s, e.ring.heading, e.radius, self.branch_collar))
                .map(|p| (None, p))
        } else {
            None
        };
        let (a, v0, from) = match swelling {
            Some((base, profile)) => {
                let (last, v) = self.swell(s, &ring, (a, v0), (base, &profile), wind);
                let top = profile.rings().last().map_or(0.0, |r| r.0);
                (last, v, top)
            }
            None => (a, v0, 0.0),
        };
        // v advances by the length in circumferences at the segment's mean radius.
        let circumference = std::f32::consts::PI * (s.start_radius + s.end_radius);
        let v1 = v0 + (s.length - from) / circumference.max(1e-4);
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

    fn leaf(&mut self, frame: &Frame, size: [f32; 2], order: f32) {
        let p = frame.position;
        // A card flutters about its base, one level deeper than the branch carrying it; its
        // phase is its order in the leaf season, distinct per card, so a shader reads both
        // from the one attribute.
        let wind = Wind {
            pivot: p.to_array(),
            depth: self.depth + 1,
            // Below 1 by a margin that survives being added to the depth in one f32.
            phase: order.clamp(0.0, 0.999),
        }
        .packed();
        self.quad(frame.card_corners(size), frame.up(), wind);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::interpret;
    use crate::swell::{FLARE_REACH, FLARE_RINGS};

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
