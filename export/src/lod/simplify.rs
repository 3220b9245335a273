//! Coarser meshes of a tree, by what the turtle drew rather than by generic decimation:
//! branch tubes lose ring sides where the branch is thin, lose rings where the branch runs
//! straight, and the thinnest branches go; leaf cards are thinned and the cards kept grow so
//! that the leaf area stays. Every bark vertex of the result lies within
//! [`LodLevel::bark_error`] of the surface it stands for, by construction.
//!
//! Tubes are recognised by the layout [`sylva_turtle::MeshBuilder`] writes: a ring is a run of
//! `sides + 1` vertices with `u = k / sides` and one `v` and wind, and consecutive rings of an
//! axis are joined by quads. Anything else (caps, polygons) is kept as it is.

use glam::Vec3;
use sylva_turtle::{Mesh, Vertex};

use super::leaves::thin_leaves;

/// One level of detail below the full mesh.
///
/// ```
/// use sylva_export::lod::LodLevel;
/// let level = LodLevel { bark_error: 0.05, leaf_keep: 0.5, leaf_growth: None };
/// // A kept card grows by sqrt(2) about its centre: a 0.4 m card's edge moves 4 cm out.
/// assert!((level.leaf_error(0.4) - 0.0828).abs() < 1e-3);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LodLevel {
    /// The farthest a bark vertex may move, in metres (in the mesh's units): rings keep the
    /// fewest sides whose chords stay this close to the circle, rings along straight stretches
    /// are dropped while the surface stays this close, and branches thinner than a quarter of
    /// it are left out (at the distance where this is a pixel, they are a quarter pixel wide).
    pub bark_error: f32,
    /// Share of the leaf cards kept, in `(0, 1]`; each card kept grows about its centre by
    /// [`LodLevel::leaf_growth`].
    pub leaf_keep: f32,
    /// How much each card kept grows across: `None` for `sqrt(1 / keep)`, which keeps the
    /// cards' area; fewer cards overlap less, so a tree's coverage is kept by a little less
    /// ([`calibrate_leaves`](crate::lod::calibrate_leaves) finds it).
    pub leaf_growth: Option<f32>,
}

impl LodLevel {
    /// How far the edge of a card of side `card` moves when it grows: the level's error for
    /// leaves.
    pub fn leaf_error(&self, card: f32) -> f32 {
        0.5 * card * (self.growth() - 1.0)
    }

    /// The factor each card kept grows by.
    pub fn growth(&self) -> f32 {
        let keep = self.leaf_keep.clamp(1e-3, 1.0);
        self.leaf_growth
            .filter(|g| g.is_finite() && *g > 0.0)
            .unwrap_or((1.0 / keep).sqrt())
            .clamp(0.1, 10.0)
    }
}

/// A mesh's triangles at one level, over the mesh's vertices plus `extra` appended after them.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Simplified {
    /// Vertices to append after the source's (the grown leaf cards).
    pub(crate) extra: Vec<Vertex>,
    pub(crate) bark: Vec<u32>,
    pub(crate) leaves: Vec<u32>,
    /// For each source bark triangle, the kept triangles before it (one more entry at the
    /// end): a span of the source's index buffer maps to one of the result's through it.
    pub(crate) bark_before: Vec<u32>,
    pub(crate) leaves_before: Vec<u32>,
    /// Which source triangle each kept triangle came from.
    pub(crate) bark_source: Vec<u32>,
    pub(crate) leaf_source: Vec<u32>,
}

impl Simplified {
    /// A span of source indices `start..end` (multiples of 3) as a span of the result's.
    pub(crate) fn map_span(before: &[u32], start: u32, end: u32) -> (u32, u32) {
        let at = |i: u32| before.get((i / 3) as usize).copied().unwrap_or(0) * 3;
        (at(start), at(end))
    }
}

/// A ring of a tube: `sides + 1` vertices from `first` (the last repeats the first's place
/// with `u = 1`).
#[derive(Debug, Clone, Copy)]
struct Ring {
    first: u32,
    sides: u32,
    centre: Vec3,
    radius: f32,
}

const NONE: u32 = u32::MAX;

/// The rings among `vertices`, in order.
fn find_rings(vertices: &[Vertex]) -> Vec<Ring> {
    let mut rings = Vec::new();
    let mut i = 0usize;
    while i < vertices.len() {
        let start = &vertices[i];
        if start.uv[0] != 0.0 {
            i += 1;
            continue;
        }
        // The run of vertices sharing the first's v and wind, up to the one with u = 1.
        let mut end = None;
        for (k, v) in vertices[i + 1..].iter().enumerate() {
            if v.uv[1] != start.uv[1] || v.wind != start.wind {
                break;
            }
            if v.uv[0] == 1.0 {
                end = Some(k + 1);
                break;
            }
        }
        let Some(sides) = end.filter(|&s| s >= 3) else {
            i += 1;
            continue;
        };
        let run = &vertices[i..=i + sides];
        let evenly = run
            .iter()
            .enumerate()
            .all(|(k, v)| v.uv[0] == k as f32 / sides as f32);
        if !evenly {
            i += 1;
            continue;
        }
        let centre = run[..sides]
            .iter()
            .map(|v| Vec3::from(v.position))
            .sum::<Vec3>()
            / sides as f32;
        let radius = run[..sides]
            .iter()
            .map(|v| Vec3::from(v.position).distance(centre))
            .sum::<f32>()
            / sides as f32;
        rings.push(Ring {
            first: i as u32,
            sides: sides as u32,
            centre,
            radius,
        });
        i += sides + 1;
    }
    rings
}

/// The vertex map of the bark at `error`: each vertex to the one that stands for it.
fn bark_map(vertices: &[Vertex], bark: &[u32], error: f32) -> Vec<u32> {
    let mut map: Vec<u32> = (0..vertices.len() as u32).collect();
    let rings = find_rings(vertices);
    if rings.is_empty() {
        return map;
    }
    let mut ring_of = vec![NONE; vertices.len()];
    for (r, ring) in rings.iter().enumerate() {
        for k in 0..=ring.sides {
            ring_of[(ring.first + k) as usize] = r as u32;
        }
    }
    // Successor and predecessor of each ring along its axis; a ring with more than one of
    // either ends the chains it is part of (it is kept).
    const MANY: u32 = NONE - 1;
    let (mut next, mut prev) = (vec![NONE; rings.len()], vec![NONE; rings.len()]);
    let link = |slot: &mut u32, to: u32| {
        *slot = match *slot {
            NONE => to,
            s if s == to => s,
            _ => MANY,
        }
    };
    for t in bark.chunks_exact(3) {
        let rs = [t[0], t[1], t[2]].map(|i| ring_of.get(i as usize).copied().unwrap_or(NONE));
        if rs.contains(&NONE) {
            continue;
        }
        let (lo, hi) = (
            rs.iter().copied().min().unwrap_or(NONE),
            rs.iter().copied().max().unwrap_or(NONE),
        );
        if lo != hi {
            link(&mut next[lo as usize], hi);
            link(&mut prev[hi as usize], lo);
        }
    }
    let single = |s: u32| s != NONE && s != MANY;
    let mut visited = vec![false; rings.len()];
    let mut chain = Vec::new();
    for start in 0..rings.len() {
        // Chains start at rings with no single predecessor that links back.
        let p = prev[start];
        if visited[start] || (single(p) && next[p as usize] == start as u32) {
            continue;
        }
        chain.clear();
        let mut r = start as u32;
        loop {
            visited[r as usize] = true;
            chain.push(r);
            let n = next[r as usize];
            if !single(n) || prev[n as usize] != r || visited[n as usize] {
                break;
            }
            r = n;
        }
        simplify_chain(vertices, &rings, &chain, error, &mut map);
    }
    map
}

/// Drops the rings of one axis that the error allows, and the sides each kept ring can lose;
/// leaves the whole axis out when it is thinner than a quarter of the error.
fn simplify_chain(vertices: &[Vertex], rings: &[Ring], chain: &[u32], error: f32, map: &mut [u32]) {
    let ring = |k: usize| &rings[chain[k] as usize];
    if chain
        .iter()
        .all(|&r| rings[r as usize].radius < 0.25 * error)
    {
        let anchor = ring(0).first;
        for &r in chain {
            let r = &rings[r as usize];
            for k in 0..=r.sides {
                map[(r.first + k) as usize] = anchor;
            }
        }
        return;
    }
    // Half the error for dropping rings and half for dropping sides: the two add up.
    let half = 0.5 * error;
    let at = |r: &Ring, k: u32| Vec3::from(vertices[(r.first + k) as usize].position);
    // Whether ring `j` lies within the error of the tube from ring `a` to ring `b`: each of
    // its vertices against the same vertex interpolated between theirs.
    let fits = |j: usize, a: usize, b: usize| {
        let (rj, ra, rb) = (ring(j), ring(a), ring(b));
        if rj.sides != ra.sides || rj.sides != rb.sides {
            return false;
        }
        let axis = rb.centre - ra.centre;
        let t = if axis.length_squared() > 0.0 {
            ((rj.centre - ra.centre).dot(axis) / axis.length_squared()).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (0..rj.sides).all(|k| at(rj, k).distance(at(ra, k).lerp(at(rb, k), t)) <= half)
    };
    // Greedy along the axis: ring i goes while every ring since the last kept one fits the
    // tube from that ring to ring i + 1.
    let mut kept = vec![0usize];
    let mut last = 0usize;
    for i in 1..chain.len().saturating_sub(1) {
        if !(last + 1..=i).all(|j| fits(j, last, i + 1)) {
            kept.push(i);
            last = i;
        }
    }
    if chain.len() > 1 {
        kept.push(chain.len() - 1);
    }
    // Dropped rings fold onto the kept ring before them, vertex for vertex.
    let mut k = 0usize;
    for i in 0..chain.len() {
        if k + 1 < kept.len() && kept[k + 1] == i {
            k += 1;
        }
        if kept[k] != i {
            let (from, to) = (ring(i), ring(kept[k]));
            for s in 0..=from.sides {
                map[(from.first + s) as usize] = to.first + s;
            }
        }
    }
    // Each kept ring keeps the fewest sides whose chords stay within the error: a side spans
    // `gap` of the original sides, and its chord lies r (1 - cos(pi gap / n)) inside.
    for &i in &kept {
        let r = ring(i);
        let n = r.sides;
        let sides = (3..n)
            .find(|&m| {
                let gap = n.div_ceil(m) as f32;
                r.radius * (1.0 - (std::f32::consts::PI * gap / n as f32).cos()) <= half
            })
            .unwrap_or(n);
        if sides == n {
            continue;
        }
        // Kept corners round(k n / sides); each vertex folds onto the kept corner at or
        // before it (the seam vertex, k = sides, is always kept).
        let corners: Vec<u32> = (0..=sides)
            .map(|k| ((k * n) as f32 / sides as f32).round() as u32)
            .collect();
        let mut c = 0usize;
        for s in 0..=n {
            while c + 1 < corners.len() && corners[c + 1] <= s {
                c += 1;
            }
            map[(r.first + s) as usize] = r.first + corners[c];
        }
    }
    // Rings folded onto a kept ring follow that ring's corners.
    for i in 0..chain.len() {
        let r = ring(i);
        for s in 0..=r.sides {
            let v = (r.first + s) as usize;
            let to = map[v] as usize;
            map[v] = map[to];
        }
    }
}

/// Triangles of `indices` through `map`, dropping those that collapse; with, for each source
/// triangle, the kept ones before it, and each kept one's source.
fn remap(indices: &[u32], map: &[u32]) -> (Vec<u32>, Vec<u32>, Vec<u32>) {
    let mut out = Vec::with_capacity(indices.len());
    let mut before = Vec::with_capacity(indices.len() / 3 + 1);
    let mut source = Vec::new();
    for (t, tri) in indices.chunks_exact(3).enumerate() {
        before.push((out.len() / 3) as u32);
        let [a, b, c] = [tri[0], tri[1], tri[2]].map(|i| map.get(i as usize).copied().unwrap_or(i));
        if a != b && b != c && a != c {
            out.extend_from_slice(&[a, b, c]);
            source.push(t as u32);
        }
    }
    before.push((out.len() / 3) as u32);
    (out, before, source)
}

/// The triangles of a mesh (`vertices` with its bark and leaf indices) at `level`.
pub(crate) fn simplify(
    vertices: &[Vertex],
    bark: &[u32],
    leaves: &[u32],
    level: &LodLevel,
) -> Simplified {
    let map = bark_map(vertices, bark, level.bark_error.max(0.0));
    let (bark, bark_before, bark_source) = remap(bark, &map);
    let mut extra = Vec::new();
    let (leaves, leaves_before, leaf_source) = thin_leaves(
        vertices,
        leaves,
        (level.leaf_keep, level.growth()),
        vertices.len() as u32,
        &mut extra,
    );
    Simplified {
        extra,
        bark,
        leaves,
        bark_before,
        leaves_before,
        bark_source,
        leaf_source,
    }
}

/// A mesh at `level`, as a mesh of its own: only the vertices its triangles use, colours kept
/// per triangle.
///
/// ```
/// use sylva_export::lod::{LodLevel, simplify_mesh};
/// let species = sylva_forest::Species::from_preset("sylva-oak", 6)?;
/// let full = species.mesh(6, 1)?;
/// let coarse = simplify_mesh(&full, &LodLevel { bark_error: 0.05, leaf_keep: 0.5, leaf_growth: None });
/// assert!(coarse.triangle_count() * 10 < full.triangle_count() * 7);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn simplify_mesh(mesh: &Mesh, level: &LodLevel) -> Mesh {
    let s = simplify(&mesh.vertices, &mesh.bark, &mesh.leaves, level);
    let all = |i: u32| -> &Vertex {
        let i = i as usize;
        mesh.vertices
            .get(i)
            .unwrap_or_else(|| &s.extra[i - mesh.vertices.len()])
    };
    let mut new_index = vec![NONE; mesh.vertices.len() + s.extra.len()];
    let mut vertices = Vec::new();
    let mut renumber = |indices: &[u32]| -> Vec<u32> {
        indices
            .iter()
            .map(|&i| {
                if new_index[i as usize] == NONE {
                    new_index[i as usize] = vertices.len() as u32;
                    vertices.push(*all(i));
                }
                new_index[i as usize]
            })
            .collect()
    };
    let bark = renumber(&s.bark);
    let leaves = renumber(&s.leaves);
    let colours = |of: &[u32], sources: &[u32]| -> Vec<u32> {
        if of.is_empty() {
            Vec::new()
        } else {
            sources
                .iter()
                .map(|&t| of.get(t as usize).copied().unwrap_or(0))
                .collect()
        }
    };
    Mesh {
        vertices,
        bark,
        leaves,
        bark_colours: colours(&mesh.bark_colours, &s.bark_source),
        leaf_colours: colours(&mesh.leaf_colours, &s.leaf_source),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use sylva_turtle::{MeshBuilder, TurtleOptions, interpret};

    /// A level that simplifies the bark alone, within `error`.
    fn bark_only(error: f32) -> LodLevel {
        LodLevel {
            bark_error: error,
            leaf_keep: 1.0,
            leaf_growth: None,
        }
    }

    fn tube(word: &str, sides: u32) -> Mesh {
        let mut options = TurtleOptions::default();
        options.radial_segments = sides;
        let mut builder = MeshBuilder::new(&options);
        let word: sylva_lsys::Word = word.parse().expect("word");
        interpret(&word, &options, &mut builder).expect("interprets");
        builder.finish()
    }

    #[test]
    fn the_turtles_rings_are_found() {
        let mesh = tube("!(1)F(1)F(1)F(1)", 6);
        let rings = find_rings(&mesh.vertices);
        assert_eq!(rings.len(), 4, "{rings:?}");
        assert!(rings.iter().all(|r| r.sides == 6));
        assert!(
            rings
                .iter()
                .all(|r| (r.radius - rings[0].radius).abs() < 1e-4)
        );
    }

    /// A straight tube keeps its end rings only: one strip of quads; a thick one keeps all
    /// six sides, a thin one three.
    #[test]
    fn a_straight_tube_keeps_its_ends() {
        let thick = tube("!(1)F(1)F(1)F(1)F(1)", 6);
        let coarse = simplify_mesh(&thick, &bark_only(0.01));
        assert_eq!(coarse.bark.len() / 3, 6 * 2);
        let thin = tube("!(0.08)F(1)F(1)F(1)F(1)", 6);
        let coarse = simplify_mesh(&thin, &bark_only(0.05));
        assert_eq!(coarse.bark.len() / 3, 3 * 2);
        // Thinner than a quarter of the error: left out.
        let gone = simplify_mesh(&thin, &bark_only(0.2));
        assert!(gone.bark.is_empty());
    }

    /// Half the cards stay, each twice the area.
    #[test]
    fn thinned_cards_keep_their_area() {
        let mesh = tube("!(0.1)F(1)J+J+J+J+J+J+J+J", 6);
        let mesh = Mesh {
            leaves: mesh.leaves.clone(),
            ..mesh
        };
        let cards = mesh.leaves.len() / 6;
        let area = |m: &Mesh| -> f32 {
            m.leaves
                .chunks_exact(3)
                .map(|t| {
                    let [a, b, c] =
                        [t[0], t[1], t[2]].map(|i| Vec3::from(m.vertices[i as usize].position));
                    0.5 * (b - a).cross(c - a).length()
                })
                .sum()
        };
        let half = simplify_mesh(
            &mesh,
            &LodLevel {
                bark_error: 0.0,
                leaf_keep: 0.5,
                leaf_growth: None,
            },
        );
        assert_eq!(half.leaves.len() / 6, cards / 2);
        assert!((area(&half) - area(&mesh)).abs() < 1e-3 * area(&mesh));
    }
}
