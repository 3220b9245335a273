//! How a tree vertex is written ([`VertexLayout`]): in two views, one beginning with its
//! floats and one of its other attributes, the tangent of the bark's normal map and the shade
//! of the leaf cluster it belongs to among them. Instanced forests and tiles quantize normals
//! and tangents to bytes (`KHR_mesh_quantization`: a step under half a degree, finer than the
//! bark's normal map resolves), 48 bytes a vertex where floats make 68; positions, uvs (bark
//! coordinates tile past 1) and wind stay floats. (A vertex's seasons are what its `_WIND`
//! and `NORMAL` hold already: see `builder::tree_attributes`.)

use std::borrow::Cow;

use bytemuck::{Pod, Zeroable};
use sylva_forest::cluster_shade;
use sylva_turtle::{Vertex, Wind};

use super::tangent::tangents;

/// How a file lays out its tree vertices.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum VertexLayout {
    /// 68 bytes: the turtle's vertex as it is (position, normal, uv, wind floats), then a
    /// float tangent and the leaf shade: for files any importer reads (one tree, levels of
    /// detail, a forest without instancing, which Godot 4 opens; it reads neither
    /// `EXT_mesh_gpu_instancing` nor `KHR_mesh_quantization`).
    Float,
    /// 48 bytes: position, uv and wind floats ([`TreeVertex`]), then normal and tangent as
    /// normalized bytes and the leaf shade ([`QuantizedExtras`]): for instanced forests and
    /// tiles, whose importers (three.js, CesiumJS, Blender, glTFast) read both extensions.
    Quantized,
}

/// A tree vertex's floats in [`VertexLayout::Quantized`]: `POSITION`, `TEXCOORD_0`, `_WIND`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub(super) struct TreeVertex {
    pub(super) position: [f32; 3],
    pub(super) uv: [f32; 2],
    pub(super) wind: [f32; 4],
}

/// A vertex's other attributes in [`VertexLayout::Float`]: `TANGENT`, then `COLOR_0` as
/// normalized bytes.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub(super) struct FloatExtras {
    pub(super) tangent: [f32; 4],
    pub(super) colour: [u8; 4],
}

/// A vertex's other attributes in [`VertexLayout::Quantized`], as normalized bytes:
/// `NORMAL` (and a byte of padding), `TANGENT`, then `COLOR_0`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub(super) struct QuantizedExtras {
    pub(super) normal: [i8; 4],
    pub(super) tangent: [i8; 4],
    pub(super) colour: [u8; 4],
}

/// Where each attribute sits in a layout's two views: `(view, offset)`, view 0 the
/// vertices and 1 the extras.
#[derive(Debug, Clone, Copy)]
pub(super) struct Offsets {
    pub(super) normal: (usize, usize),
    pub(super) uv: usize,
    pub(super) wind: usize,
    pub(super) tangent: (usize, usize),
    pub(super) colour: usize,
}

impl VertexLayout {
    /// Bytes of a vertex in the vertex view (its stride).
    pub(super) fn vertex_bytes(self) -> usize {
        match self {
            VertexLayout::Float => size_of::<Vertex>(),
            VertexLayout::Quantized => size_of::<TreeVertex>(),
        }
    }

    /// Bytes of a vertex in the extras view (its stride).
    pub(super) fn extras_bytes(self) -> usize {
        match self {
            VertexLayout::Float => size_of::<FloatExtras>(),
            VertexLayout::Quantized => size_of::<QuantizedExtras>(),
        }
    }

    /// Where the attributes sit.
    pub(super) fn offsets(self) -> Offsets {
        match self {
            VertexLayout::Float => Offsets {
                normal: (0, 12),
                uv: 24,
                wind: 32,
                tangent: (1, 0),
                colour: 16,
            },
            VertexLayout::Quantized => Offsets {
                normal: (1, 0),
                uv: 12,
                wind: 20,
                tangent: (1, 4),
                colour: 8,
            },
        }
    }

    /// The vertex view's bytes of `vertices`: the turtle's own vertices as they are in
    /// [`VertexLayout::Float`] (no copy), their floats one after another otherwise.
    pub(super) fn vertices(self, vertices: &[Vertex]) -> Cow<'_, [u8]> {
        match self {
            VertexLayout::Float => Cow::Borrowed(bytemuck::cast_slice(vertices)),
            VertexLayout::Quantized => {
                Cow::Owned(bytes_of_each(vertices.iter().map(|v| TreeVertex {
                    position: v.position,
                    uv: v.uv,
                    wind: v.wind,
                })))
            }
        }
    }

    /// The extras view's bytes of `vertices`: tangents from the `bark` triangles (the leaves'
    /// normals need none); the leaf cards' vertices (those of `leaves`) coloured by their
    /// card's [`cluster_shade`], every other vertex white, so that `COLOR_0` shades only the
    /// leaves; in [`VertexLayout::Quantized`] the normals too.
    pub(super) fn extras(self, vertices: &[Vertex], bark: &[u32], leaves: &[u32]) -> Vec<u8> {
        let shades = leaf_shades(vertices, leaves);
        let tangents = tangents(vertices, bark);
        let each = vertices.iter().zip(tangents).zip(shades);
        match self {
            VertexLayout::Float => {
                bytes_of_each(each.map(|((_, tangent), colour)| FloatExtras { tangent, colour }))
            }
            VertexLayout::Quantized => bytes_of_each(each.map(|((v, t), colour)| {
                let [nx, ny, nz] = unit_bytes(v.normal);
                let [tx, ty, tz] = unit_bytes([t[0], t[1], t[2]]);
                let handedness = if t[3] < 0.0 { -127 } else { 127 };
                QuantizedExtras {
                    normal: [nx, ny, nz, 0],
                    tangent: [tx, ty, tz, handedness],
                    colour,
                }
            })),
        }
    }
}

/// The bytes of `items`, one after another, in one allocation.
fn bytes_of_each<P: Pod>(items: impl ExactSizeIterator<Item = P>) -> Vec<u8> {
    let mut bytes = Vec::with_capacity(items.len() * size_of::<P>());
    for item in items {
        bytes.extend_from_slice(bytemuck::bytes_of(&item));
    }
    bytes
}

/// A component in [-1, 1] as a normalized signed byte (glTF decodes `max(c / 127, -1)`).
fn snorm8(c: f32) -> i8 {
    let c = if c.is_finite() { c } else { 0.0 };
    (c.clamp(-1.0, 1.0) * 127.0).round() as i8
}

/// A unit vector as normalized bytes, the byte triple nearest to unit length along it: a
/// plain rounding can leave it 1.5% short or long, more than glTF's validator allows a
/// normal.
fn unit_bytes(v: [f32; 3]) -> [i8; 3] {
    let length = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if !length.is_finite() || length <= 1e-12 {
        return [0, 127, 0];
    }
    let u = v.map(|c| c / length);
    let mut best = u.map(snorm8);
    let mut best_error = f32::MAX;
    // Every rounding up or down of each component: the one whose length is nearest 1 and
    // direction nearest u.
    for k in 0..8 {
        let candidate: [i8; 3] = std::array::from_fn(|i| {
            let scaled = u[i] * 127.0;
            let c = if k & (1 << i) == 0 {
                scaled.floor()
            } else {
                scaled.ceil()
            };
            c.clamp(-127.0, 127.0) as i8
        });
        let f = candidate.map(|c| f32::from(c) / 127.0);
        let len = (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt();
        let dot = (f[0] * u[0] + f[1] * u[1] + f[2] * u[2]) / len.max(1e-6);
        let error = (len - 1.0).abs() + (1.0 - dot);
        if error < best_error {
            best_error = error;
            best = candidate;
        }
    }
    best
}

/// Each vertex's `COLOR_0`: the leaf cards' vertices (those of `leaves`) by their card's
/// [`cluster_shade`], every other vertex white.
fn leaf_shades(vertices: &[Vertex], leaves: &[u32]) -> Vec<[u8; 4]> {
    let mut on_card = vec![false; vertices.len()];
    for &i in leaves {
        if let Some(card) = on_card.get_mut(i as usize) {
            *card = true;
        }
    }
    let byte = |c: f32| (c.clamp(0.0, 1.0) * 255.0).round() as u8;
    vertices
        .iter()
        .zip(on_card)
        .map(|(v, card)| {
            if card {
                let [r, g, b] = cluster_shade(Wind::of(v).phase);
                [byte(r), byte(g), byte(b), 255]
            } else {
                [255; 4]
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Leaf vertices carry their card's shade, the same for the card's four corners and
    /// different between cards; bark vertices stay white.
    #[test]
    fn leaves_are_shaded_per_card_and_bark_stays_white() {
        let word: sylva_lsys::Word = "!(0.1)F(1)[&(40)J]/(90)[&(40)J]".parse().unwrap();
        let options = sylva_turtle::TurtleOptions::default().with_radial_segments(4);
        let mut builder = sylva_turtle::MeshBuilder::new(&options);
        sylva_turtle::interpret(&word, &options, &mut builder).unwrap();
        let mesh = builder.finish();
        assert_eq!(mesh.leaves.len(), 12, "two cards");
        for layout in [VertexLayout::Float, VertexLayout::Quantized] {
            let bytes = layout.extras(&mesh.vertices, &mesh.bark, &mesh.leaves);
            let stride = layout.extras_bytes();
            assert_eq!(bytes.len(), stride * mesh.vertices.len());
            let at = layout.offsets().colour;
            let colour = |i: u32| &bytes[i as usize * stride + at..][..4];
            for &i in &mesh.bark {
                assert_eq!(colour(i), [255; 4]);
            }
            let card = |k: usize| colour(mesh.leaves[6 * k]);
            for k in 0..2 {
                for &i in &mesh.leaves[6 * k..6 * k + 6] {
                    assert_eq!(colour(i), card(k));
                }
                assert!(card(k)[..3].iter().all(|&c| c >= 178));
            }
            assert_ne!(card(0), card(1));
        }
        let quantized = VertexLayout::Quantized;
        assert_eq!(quantized.vertex_bytes() + quantized.extras_bytes(), 48);
        let float = VertexLayout::Float;
        assert_eq!(float.vertex_bytes() + float.extras_bytes(), 68);
    }

    /// Byte normals stay unit length within glTF's tolerance and within a degree of the
    /// vector they stand for, over many directions.
    #[test]
    fn byte_unit_vectors_keep_length_and_direction() {
        for k in 0..2000 {
            let t = k as f32 * 0.618_034;
            let z = 1.0 - 2.0 * ((k as f32 + 0.5) / 2000.0);
            let r = (1.0 - z * z).sqrt();
            let v = [
                r * (t * std::f32::consts::TAU).cos(),
                z,
                r * (t * std::f32::consts::TAU).sin(),
            ];
            let f = unit_bytes(v).map(|c| f32::from(c) / 127.0);
            let len = (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt();
            assert!((len - 1.0).abs() < 0.005, "{v:?} -> {f:?} length {len}");
            let dot = (f[0] * v[0] + f[1] * v[1] + f[2] * v[2]) / len;
            assert!(dot > 1.0f32.to_radians().cos(), "{v:?} -> {f:?}");
        }
        assert_eq!(unit_bytes([0.0, 0.0, 0.0]), [0, 127, 0]);
    }
}
