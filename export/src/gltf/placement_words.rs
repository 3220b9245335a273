//! How a placement is spelt in a forest's GLB: five sections of 4-byte words, 60 bytes a
//! placement. Translation, scale, tint and wind are floats; the rotation is four normalized
//! shorts, which `EXT_mesh_gpu_instancing` allows (a step of 1/32767 of a unit
//! quaternion's component: under 0.004 degrees). The all-float 68 bytes were half of the
//! default forest's file.
//!
//! The tint stays float: three.js r170 hands `_COLOR_0` to its instance colours as it finds
//! it, and normalized bytes (four, as vertex data must fill whole words) drew nothing at
//! all.

use glam::Quat;

use super::{FLOAT, SHORT};

/// Words per placement in each section: translation, rotation, scale, tint, wind.
pub(super) const SECTION_WORDS: [usize; 5] = [3, 2, 3, 3, 4];

/// Bytes of one placement across the sections.
pub(super) const PLACEMENT_BYTES: usize = 4 * (3 + 2 + 3 + 3 + 4);

/// Each section's accessor: component type, element kind and whether it is normalized.
pub(super) const SECTION_ACCESSORS: [(u32, &str, bool); 5] = [
    (FLOAT, "VEC3", false),
    (SHORT, "VEC4", true),
    (FLOAT, "VEC3", false),
    (FLOAT, "VEC3", false),
    (FLOAT, "VEC4", false),
];

/// Floats as words.
pub(super) fn floats(values: &[f32]) -> impl Iterator<Item = u32> + '_ {
    values.iter().map(|v| v.to_bits())
}

/// A unit quaternion (x, y, z, w) as two words of normalized shorts, little-endian.
pub(super) fn rotation(q: Quat) -> [u32; 2] {
    let short = |c: f32| (c.clamp(-1.0, 1.0) * 32767.0).round() as i16 as u16 as u32;
    let [x, y, z, w] = q.normalize().to_array().map(short);
    [x | (y << 16), z | (w << 16)]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A rotation read back as glTF decodes normalized shorts (max(c / 32767, -1)) is the
    /// rotation written, within the step.
    #[test]
    fn rotations_read_back_within_a_step() {
        let q = Quat::from_rotation_y(1.234) * Quat::from_rotation_x(0.1);
        let [a, b] = rotation(q);
        let bytes: Vec<u8> = [a, b].iter().flat_map(|w| w.to_le_bytes()).collect();
        let read: Vec<f32> = bytes
            .chunks_exact(2)
            .map(|s| (f32::from(i16::from_le_bytes([s[0], s[1]])) / 32767.0).max(-1.0))
            .collect();
        let back = Quat::from_xyzw(read[0], read[1], read[2], read[3]);
        assert!(back.angle_between(q) < 1e-4, "{back} {q}");
        assert_eq!(PLACEMENT_BYTES, 60);
        assert_eq!(SECTION_WORDS.iter().sum::<usize>() * 4, PLACEMENT_BYTES);
    }
}
