//! Leaf cards at a coarser level: thinned by an even running share and grown about their
//! centres, so fewer cards cover what the full set did.

use glam::Vec3;
use sylva_turtle::Vertex;

/// Whether triangles `t` and `t + 1` of `indices` are one leaf card as the turtle draws it:
/// four consecutive vertices, `[a, a+1, a+2, a, a+2, a+3]`.
fn card_at(indices: &[u32], t: usize) -> Option<u32> {
    let q = indices.get(t * 3..t * 3 + 6)?;
    let a = q[0];
    a.checked_add(3)?;
    (q == [a, a + 1, a + 2, a, a + 2, a + 3]).then_some(a)
}

/// The leaf triangles with a share `keep` of the cards, grown by `grow`: every card's place
/// in the sequence decides whether it stays (an even spread along each twig), and the cards
/// kept grow about their centres into
/// `extra`, numbered from `base`.
pub(crate) fn thin_leaves(
    vertices: &[Vertex],
    leaves: &[u32],
    (keep, grow): (f32, f32),
    base: u32,
    extra: &mut Vec<Vertex>,
) -> (Vec<u32>, Vec<u32>, Vec<u32>) {
    let keep = keep.clamp(1e-3, 1.0);
    let triangles = leaves.len() / 3;
    let mut out = Vec::with_capacity(leaves.len());
    let mut before = Vec::with_capacity(triangles + 1);
    let mut source = Vec::new();
    let mut cards = 0u64;
    let mut t = 0usize;
    while t < triangles {
        before.push((out.len() / 3) as u32);
        let card = card_at(leaves, t).filter(|&a| (a as usize + 3) < vertices.len());
        let Some(a) = card else {
            out.extend_from_slice(&leaves[t * 3..t * 3 + 3]);
            source.push(t as u32);
            t += 1;
            continue;
        };
        // Card c stays when the running share keep * c passes an integer.
        let stays = ((cards + 1) as f64 * f64::from(keep)).floor()
            > (cards as f64 * f64::from(keep)).floor();
        cards += 1;
        before.push((out.len() / 3) as u32);
        if stays {
            let corners = &vertices[a as usize..a as usize + 4];
            let first = if grow == 1.0 {
                a
            } else {
                let centre = corners.iter().map(|v| Vec3::from(v.position)).sum::<Vec3>() * 0.25;
                let first = base + extra.len() as u32;
                extra.extend(corners.iter().map(|v| Vertex {
                    position: (centre + (Vec3::from(v.position) - centre) * grow).to_array(),
                    ..*v
                }));
                first
            };
            out.extend_from_slice(&[first, first + 1, first + 2, first, first + 2, first + 3]);
            source.extend_from_slice(&[t as u32, t as u32 + 1]);
        }
        t += 2;
    }
    before.push((out.len() / 3) as u32);
    (out, before, source)
}
