//! What the exporter adds to each tree vertex beside the turtle's own attributes: the
//! tangent of the bark's normal map, the shade of the leaf cluster the vertex belongs to and
//! interleaved in one view, 20 bytes a vertex. (The seasons' data of a vertex is what its
//! `_WIND` and `NORMAL` hold already: see `builder::tree_attributes`.)

use bytemuck::{Pod, Zeroable};
use sylva_forest::cluster_shade;
use sylva_turtle::{Vertex, Wind};

use super::tangent::tangents;

/// One vertex's extra attributes: `TANGENT`, then `COLOR_0` as normalized bytes.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub(super) struct VertexExtras {
    pub(super) tangent: [f32; 4],
    pub(super) colour: [u8; 4],
}

/// Bytes of [`VertexExtras`], the stride of their view.
pub(super) const EXTRAS_BYTES: usize = size_of::<VertexExtras>();

/// Where `COLOR_0` sits in [`VertexExtras`].
pub(super) const COLOUR_OFFSET: usize = 16;

/// The extras of `vertices`: tangents from the `bark` triangles (the leaves' normals need
/// none); the leaf cards' vertices (those of `leaves`) coloured by their card's
/// [`cluster_shade`], every other vertex white, so that `COLOR_0` shades only the leaves.
pub(super) fn vertex_extras(
    vertices: &[Vertex],
    bark: &[u32],
    leaves: &[u32],
) -> Vec<VertexExtras> {
    let mut on_card = vec![false; vertices.len()];
    for &i in leaves {
        if let Some(card) = on_card.get_mut(i as usize) {
            *card = true;
        }
    }
    let byte = |c: f32| (c.clamp(0.0, 1.0) * 255.0).round() as u8;
    tangents(vertices, bark)
        .into_iter()
        .zip(vertices.iter().zip(on_card))
        .map(|(tangent, (v, card))| {
            let colour = if card {
                let [r, g, b] = cluster_shade(Wind::of(v).phase);
                [byte(r), byte(g), byte(b), 255]
            } else {
                [255; 4]
            };
            VertexExtras { tangent, colour }
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
        let extras = vertex_extras(&mesh.vertices, &mesh.bark, &mesh.leaves);
        assert_eq!(extras.len(), mesh.vertices.len());
        for &i in &mesh.bark {
            assert_eq!(extras[i as usize].colour, [255; 4]);
        }
        let card = |k: usize| extras[mesh.leaves[6 * k] as usize].colour;
        for k in 0..2 {
            for &i in &mesh.leaves[6 * k..6 * k + 6] {
                assert_eq!(extras[i as usize].colour, card(k));
            }
            assert!(card(k)[..3].iter().all(|&c| c >= 178));
        }
        assert_ne!(card(0), card(1));
        assert_eq!(EXTRAS_BYTES, 20);
    }
}
