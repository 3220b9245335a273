//! How a buffer's triangle indices are written: as 16-bit integers when its vertices are few
//! enough, which halves the indices of most of a forest's branch caches and of a small
//! world's terrain; as 32-bit integers otherwise.

use std::borrow::Cow;

use super::{UNSIGNED_INT, UNSIGNED_SHORT};

/// The width of a buffer's indices.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum IndexWidth {
    /// `UNSIGNED_SHORT`.
    Short,
    /// `UNSIGNED_INT`.
    Int,
}

impl IndexWidth {
    /// The width for indices into `vertices` vertices: short when every index is below
    /// 65,535 (glTF forbids a type's largest value as an index: it restarts strips).
    pub(super) fn for_vertices(vertices: usize) -> IndexWidth {
        if vertices <= usize::from(u16::MAX) {
            IndexWidth::Short
        } else {
            IndexWidth::Int
        }
    }

    /// Bytes of one index.
    pub(super) fn bytes(self) -> usize {
        match self {
            IndexWidth::Short => 2,
            IndexWidth::Int => 4,
        }
    }

    /// The accessor's component type.
    pub(super) fn component(self) -> u32 {
        match self {
            IndexWidth::Short => UNSIGNED_SHORT,
            IndexWidth::Int => UNSIGNED_INT,
        }
    }

    /// `indices` as this width's little-endian bytes (no padding).
    pub(super) fn encode(self, indices: &[u32]) -> Cow<'_, [u8]> {
        match self {
            IndexWidth::Int => Cow::Borrowed(bytemuck::cast_slice(indices)),
            IndexWidth::Short => Cow::Owned(
                indices
                    .iter()
                    .flat_map(|&i| (i.min(u32::from(u16::MAX)) as u16).to_le_bytes())
                    .collect(),
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn short_indices_hold_every_vertex_below_the_restart_value() {
        assert_eq!(IndexWidth::for_vertices(65_535), IndexWidth::Short);
        assert_eq!(IndexWidth::for_vertices(65_536), IndexWidth::Int);
        let indices = [0, 1, 65_534];
        assert_eq!(
            IndexWidth::Short.encode(&indices).as_ref(),
            &[0, 0, 1, 0, 254, 255]
        );
        assert_eq!(IndexWidth::Int.encode(&indices).len(), 12);
        assert_eq!(IndexWidth::Short.bytes() * 3, 6);
    }
}
