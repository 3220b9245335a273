//! A variant's size, from its cached geometry: how tall its trees grow and how wide their
//! crowns reach, for bounding volumes.

use crate::variants::Variant;

/// A variant's size: height of its geometry and the horizontal radius of its crown.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Extent {
    /// Height of the variant's geometry above its root, metres (unscaled).
    pub height: f32,
    /// Horizontal radius of its crown, metres (unscaled).
    pub crown: f32,
}

impl Extent {
    /// The extent of a variant's cached geometry (its largest hero).
    pub fn of(variant: &Variant) -> Extent {
        let (mut height, mut crown) = (0.0f32, 0.0f32);
        for v in &variant.cache.vertices {
            let [x, y, z] = v.position;
            height = height.max(y);
            crown = crown.max((x * x + z * z).sqrt());
        }
        Extent {
            height: height.max(0.5),
            crown: crown.max(0.3),
        }
    }
}
