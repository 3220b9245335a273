//! What covers a material-id render: the share of its pixels showing terrain, bark, leaves,
//! sky, or anything else (which a correct render never shows).

use crate::materials::{ID_BARK, ID_LEAF, ID_TERRAIN};

/// Fractions of a picture's pixels, summing to 1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Coverage {
    pub(crate) terrain: f64,
    pub(crate) bark: f64,
    pub(crate) leaves: f64,
    pub(crate) sky: f64,
    pub(crate) other: f64,
}

impl Coverage {
    /// Counts the flat colours of an RGBA8 id render (`render::Mode::Ids`).
    pub(crate) fn of_ids(rgba: &[u8]) -> Coverage {
        let classify = |p: &[u8]| -> usize {
            let close = |c: [f32; 3]| (0..3).all(|k| (f32::from(p[k]) / 255.0 - c[k]).abs() < 0.1);
            if close(ID_TERRAIN) {
                0
            } else if close(ID_BARK) {
                1
            } else if close(ID_LEAF) {
                2
            } else if p[..3].iter().all(|&v| v < 10) {
                3
            } else {
                4
            }
        };
        let mut counts = [0usize; 5];
        for p in rgba.chunks_exact(4) {
            counts[classify(p)] += 1;
        }
        let total = (rgba.len() / 4).max(1) as f64;
        let [terrain, bark, leaves, sky, other] = counts.map(|c| c as f64 / total);
        Coverage {
            terrain,
            bark,
            leaves,
            sky,
            other,
        }
    }
}

impl std::fmt::Display for Coverage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "terrain {:.1}%, bark {:.1}%, leaves {:.1}%, sky {:.1}%, other {:.1}%",
            100.0 * self.terrain,
            100.0 * self.bark,
            100.0 * self.leaves,
            100.0 * self.sky,
            100.0 * self.other
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_each_material_colour() {
        let px = |c: [f32; 3]| c.map(|v| (v * 255.0) as u8);
        let mut rgba = Vec::new();
        for c in [ID_TERRAIN, ID_BARK, ID_LEAF, ID_LEAF, [0.0; 3], [0.5; 3]] {
            let [r, g, b] = px(c);
            rgba.extend_from_slice(&[r, g, b, 255]);
        }
        let c = Coverage::of_ids(&rgba);
        let sixth = 1.0 / 6.0;
        assert_eq!(
            [c.terrain, c.bark, c.leaves, c.sky, c.other],
            [sixth, sixth, 2.0 * sixth, sixth, sixth]
        );
    }
}
