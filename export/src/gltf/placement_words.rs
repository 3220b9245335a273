//! How a placement is spelt in a forest's GLB: five sections of 4-byte words, 52 bytes a
//! placement. Translation, scale and tint are floats; the rotation is four normalized
//! shorts, which `EXT_mesh_gpu_instancing` allows (a step of 1/32767 of a unit
//! quaternion's component: under 0.004 degrees). The wind (`_WIND_TREE`) is four normalized
//! shorts too: the tree's base as an offset from the placement's translation in units of
//! [`WIND_TREE_REACH`] (a step of 8 mm), and the tree's phase. The all-float 68 bytes were
//! half of the default forest's file.
//!
//! The tint stays float: three.js r170 hands `_COLOR_0` to its instance colours as it finds
//! it, and normalized bytes (four, as vertex data must fill whole words) drew nothing at
//! all.

use glam::Quat;

use super::{FLOAT, SHORT};

/// Words per placement in each section: translation, rotation, scale, tint, wind.
pub(super) const SECTION_WORDS: [usize; 5] = [3, 2, 3, 3, 2];

/// Bytes of one placement across the sections.
pub(super) const PLACEMENT_BYTES: usize = 4 * (3 + 2 + 3 + 3 + 2);

/// Metres that `_WIND_TREE`'s xyz of 1 stands for: a placement's offset to its tree's base
/// is written as that offset over this reach. No tree is half as tall (the tallest trees
/// measured are about 116 m); a placement farther from its base is written at the reach.
/// Files say it as each instanced node's `extras.sylva_wind_tree_reach`.
pub const WIND_TREE_REACH: f32 = 256.0;

/// Each section's accessor: component type, element kind and whether it is normalized.
pub(super) const SECTION_ACCESSORS: [(u32, &str, bool); 5] = [
    (FLOAT, "VEC3", false),
    (SHORT, "VEC4", true),
    (FLOAT, "VEC3", false),
    (FLOAT, "VEC3", false),
    (SHORT, "VEC4", true),
];

/// Floats as words.
pub(super) fn floats(values: &[f32]) -> impl Iterator<Item = u32> + '_ {
    values.iter().map(|v| v.to_bits())
}

/// Four values in `[-1, 1]` as two words of normalized shorts, little-endian; values outside
/// are held at the ends.
fn shorts(values: [f32; 4]) -> [u32; 2] {
    let short = |c: f32| (c.clamp(-1.0, 1.0) * 32767.0).round() as i16 as u16 as u32;
    let [x, y, z, w] = values.map(short);
    [x | (y << 16), z | (w << 16)]
}

/// A unit quaternion (x, y, z, w) as two words of normalized shorts.
pub(super) fn rotation(q: Quat) -> [u32; 2] {
    shorts(q.normalize().to_array())
}

/// A placement's wind data as two words of normalized shorts: its tree's base
/// (`tree_wind`'s xyz) less the placement's `translation`, over [`WIND_TREE_REACH`], and the
/// tree's phase (`tree_wind`'s w, in `[0, 1)`).
pub(super) fn wind(tree_wind: [f32; 4], translation: [f32; 3]) -> [u32; 2] {
    let [x, y, z, phase] = tree_wind;
    let offset = |base: f32, at: f32| (base - at) / WIND_TREE_REACH;
    shorts([
        offset(x, translation[0]),
        offset(y, translation[1]),
        offset(z, translation[2]),
        phase,
    ])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Normalized shorts read back as glTF decodes them: max(c / 32767, -1).
    fn read_shorts(words: [u32; 2]) -> Vec<f32> {
        let bytes: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).collect();
        bytes
            .chunks_exact(2)
            .map(|s| (f32::from(i16::from_le_bytes([s[0], s[1]])) / 32767.0).max(-1.0))
            .collect()
    }

    /// A tree's base read back from a placement's translation and its wind words is the base
    /// written, within half a step of the reach (4 mm); the phase within half of 1/32767. A
    /// placement beyond the reach is held at it.
    #[test]
    fn tree_bases_read_back_within_a_step() {
        let base = [1234.5, 87.25, -640.125];
        let at = [1230.0, 118.0, -652.5];
        let read = read_shorts(wind([base[0], base[1], base[2], 0.625], at));
        for k in 0..3 {
            let back = at[k] + read[k] * WIND_TREE_REACH;
            assert!((back - base[k]).abs() <= 0.5 * WIND_TREE_REACH / 32767.0 + 1e-4);
        }
        assert!((read[3] - 0.625).abs() <= 0.5 / 32767.0);
        let far = read_shorts(wind(
            [0.0, 0.0, 0.0, 0.5],
            [0.0, 2.0 * WIND_TREE_REACH, 0.0],
        ));
        assert_eq!(far[1], -1.0);
    }

    /// A rotation read back as glTF decodes normalized shorts (max(c / 32767, -1)) is the
    /// rotation written, within the step.
    #[test]
    fn rotations_read_back_within_a_step() {
        let q = Quat::from_rotation_y(1.234) * Quat::from_rotation_x(0.1);
        let read = read_shorts(rotation(q));
        let back = Quat::from_xyzw(read[0], read[1], read[2], read[3]);
        assert!(back.angle_between(q) < 1e-4, "{back} {q}");
        assert_eq!(PLACEMENT_BYTES, 52);
        assert_eq!(SECTION_WORDS.iter().sum::<usize>() * 4, PLACEMENT_BYTES);
    }
}
