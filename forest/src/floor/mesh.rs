//! The meshes of the floor's kinds, made once: grass tufts as plain blades, ferns and shrubs
//! by the turtle with leaf cards, a fallen branch laid on the ground, a rock.

use glam::{Quat, Vec3};
use sylva_base::hash::{mix, unit_f32};
use sylva_turtle::{Mesh, TurtleOptions, Vertex};

use crate::error::ForestError;
use crate::ground::GroundKind;
use crate::species::Species;

impl GroundKind {
    /// The kind's mesh, in metres, standing on its origin: the same for every item (items
    /// differ by yaw and scale).
    pub fn mesh(self) -> Result<Mesh, ForestError> {
        match self {
            GroundKind::Grass => Ok(grass_tuft()),
            GroundKind::Fern => turtle_mesh("fern", FERN, fern_options()),
            GroundKind::Shrub => {
                // A young hazel at a third of its size, its apices drawn as leaf clusters.
                let mut hazel = Species::from_preset("sylva-hazel", 4)?;
                hazel.turtle.symbols.set("L", sylva_turtle::Command::Leaf);
                hazel.turtle.step *= 0.35;
                hazel.turtle.width *= 0.4;
                hazel.turtle.leaf_size = [0.2, 0.18];
                hazel.turtle.leaf_facing = 0.85;
                hazel.turtle.radial_segments = 4;
                hazel.mesh(4, 7)
            }
            GroundKind::Branch => {
                let mut mesh = turtle_mesh("fallen branch", BRANCH, branch_options())?;
                // The turtle grows up +Y: laid down along +X, resting on the ground.
                let lay = Quat::from_rotation_z(-std::f32::consts::FRAC_PI_2);
                for v in &mut mesh.vertices {
                    let p = lay * Vec3::from(v.position) + Vec3::new(-0.8, 0.07, 0.0);
                    v.position = p.to_array();
                    v.normal = (lay * Vec3::from(v.normal)).to_array();
                    let w = lay * Vec3::new(v.wind[0], v.wind[1], v.wind[2]);
                    // Lying on the ground, a branch does not sway.
                    v.wind = [w.x, w.y + 0.07, w.z, 0.0];
                }
                Ok(mesh)
            }
            GroundKind::Rock => Ok(rock()),
        }
    }
}

/// A fern: five to six fronds arching out from the crown, each a stalk with paired leaflet
/// cards that shorten towards its tip.
const FERN: &str = "
axiom: /(10)[&(52)A(11)]/(67)[&(60)A(10)]/(75)[&(48)A(12)]/(70)[&(64)A(9)]/(68)[&(56)A(11)]
A(n) : n > 0 -> F(0.055)[+(72)J][-(72)J]&(7)A(n-1)
";

fn fern_options() -> TurtleOptions {
    let mut o = TurtleOptions::default();
    o.width = 0.006;
    o.radial_segments = 3;
    o.leaf_size = [0.13, 0.06];
    o.leaf_facing = 0.6;
    o
}

/// A fallen branch: a limb with a few side branches, broken at both ends, rolled so that its
/// side branches lie along the ground once it is laid down.
const BRANCH: &str = "
axiom: /(90)!(0.11)F(0.5)+(12)F(0.45)[-(40)!(0.05)F(0.45)+(15)F(0.3)]-(14)!(0.09)F(0.5)[+(55)!(0.04)F(0.4)]F(0.35)
";

fn branch_options() -> TurtleOptions {
    let mut o = TurtleOptions::default();
    o.radial_segments = 6;
    o
}

/// The mesh the turtle draws of `grammar` (derived 14 generations, seed 1) with `options`.
fn turtle_mesh(name: &str, grammar: &str, options: TurtleOptions) -> Result<Mesh, ForestError> {
    let mut plant = Species::new(name, grammar.parse()?, 14);
    plant.turtle = options;
    plant.mesh(14, 1)
}

/// A tuft of grass: 16 blades leaning out from one spot, each three triangles narrowing to
/// its tip, swaying as leaves do.
fn grass_tuft() -> Mesh {
    let mut mesh = Mesh::default();
    for k in 0..16u32 {
        let h = |salt: u64| unit_f32(mix(u64::from(k) * 31 + salt));
        let yaw = std::f32::consts::TAU * (k as f32 + h(1)) / 16.0;
        let lean = 0.15 + 0.5 * h(2);
        let height = 0.22 + 0.22 * h(3);
        let half = 0.006 + 0.004 * h(4);
        let out = Vec3::new(yaw.cos(), 0.0, yaw.sin());
        let across = Vec3::new(-out.z, 0.0, out.x);
        let base = out * (0.04 * h(5));
        // Up the blade, bending further out as it rises.
        let at = |t: f32| base + out * (lean * height * t * t) + Vec3::Y * (height * t);
        let normal = (Vec3::Y * 0.3 - out).normalize();
        let first = mesh.vertices.len() as u32;
        let wind = [base.x, 0.0, base.z, 4.0 + h(6).min(0.999)];
        for (t, width) in [(0.0, 1.0), (0.5, 0.75)] {
            for side in [-1.0f32, 1.0] {
                mesh.vertices.push(Vertex {
                    position: (at(t) + across * (side * half * width)).to_array(),
                    normal: normal.to_array(),
                    uv: [0.5 + 0.5 * side, t],
                    wind,
                });
            }
        }
        mesh.vertices.push(Vertex {
            position: at(1.0).to_array(),
            normal: normal.to_array(),
            uv: [0.5, 1.0],
            wind,
        });
        let [a, b, c, d, e] = [0, 1, 2, 3, 4].map(|i| first + i);
        mesh.leaves.extend_from_slice(&[a, b, d, a, d, c, c, d, e]);
    }
    mesh
}

/// A rock: a subdivided octahedron pushed in and out by noise, flattened and half sunk.
fn rock() -> Mesh {
    let mut positions: Vec<Vec3> = vec![
        Vec3::X,
        Vec3::NEG_X,
        Vec3::Y,
        Vec3::NEG_Y,
        Vec3::Z,
        Vec3::NEG_Z,
    ];
    let mut faces: Vec<[u32; 3]> = vec![
        [0, 2, 4],
        [4, 2, 1],
        [1, 2, 5],
        [5, 2, 0],
        [4, 3, 0],
        [1, 3, 4],
        [5, 3, 1],
        [0, 3, 5],
    ];
    for _ in 0..3 {
        let mut midpoints = std::collections::HashMap::new();
        let mut next = Vec::with_capacity(faces.len() * 4);
        for f in &faces {
            let mut mid = |a: u32, b: u32| -> u32 {
                *midpoints.entry((a.min(b), a.max(b))).or_insert_with(|| {
                    positions.push((positions[a as usize] + positions[b as usize]).normalize());
                    (positions.len() - 1) as u32
                })
            };
            let (ab, bc, ca) = (mid(f[0], f[1]), mid(f[1], f[2]), mid(f[2], f[0]));
            next.extend_from_slice(&[[f[0], ab, ca], [ab, f[1], bc], [ca, bc, f[2]], [ab, bc, ca]]);
        }
        faces = next;
    }
    let bump = |p: Vec3| {
        let cell = (p * 2.0).floor();
        let h = mix((cell.x as i64 as u64).wrapping_mul(0x9e37)
            ^ (cell.y as i64 as u64).wrapping_mul(0x85eb) << 16
            ^ (cell.z as i64 as u64).wrapping_mul(0xc2b2) << 32);
        0.85 + 0.3 * unit_f32(h)
    };
    let shaped: Vec<Vec3> = positions
        .iter()
        .map(|&p| {
            let r = bump(p) * (0.9 + 0.1 * (3.0 * p.x + 2.0 * p.z).sin());
            Vec3::new(p.x * 0.5, p.y * 0.28 + 0.06, p.z * 0.4) * r
        })
        .collect();
    let mut mesh = Mesh::default();
    // Flat shading: each face its own vertices, so the facets read as broken stone.
    for f in &faces {
        let [a, b, c] = f.map(|i| shaped[i as usize]);
        let n = (b - a).cross(c - a).normalize_or(Vec3::Y);
        let first = mesh.vertices.len() as u32;
        for (p, uv) in [(a, [0.0, 0.0]), (b, [1.0, 0.0]), (c, [0.5, 1.0])] {
            mesh.vertices.push(Vertex {
                position: p.to_array(),
                normal: n.to_array(),
                uv,
                wind: [0.0; 4],
            });
        }
        mesh.bark.extend_from_slice(&[first, first + 1, first + 2]);
    }
    mesh
}
