//! Ids of worlds and elevation models: 32 lowercase hex digits, the first 128 bits of a
//! SHA-256. Checked before they name any path, so an id can never climb out of a cache.

use std::fmt;

use sha2::{Digest, Sha256};

/// A world's or heightmap's id.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct WorldId(String);

impl WorldId {
    /// Hex digits in an id.
    pub const LEN: usize = 32;

    /// The id of a digest: its first 16 bytes in hex.
    pub fn of(digest: &[u8]) -> WorldId {
        WorldId(
            digest
                .iter()
                .take(Self::LEN / 2)
                .map(|b| format!("{b:02x}"))
                .collect(),
        )
    }

    /// Whether `s` is an id: exactly [`WorldId::LEN`] lowercase hex digits.
    pub fn is_valid(s: &str) -> bool {
        s.len() == Self::LEN && s.bytes().all(|b| matches!(b, b'0'..=b'9' | b'a'..=b'f'))
    }

    /// `s` as an id, if it is one.
    pub fn parse(s: &str) -> Option<WorldId> {
        Self::is_valid(s).then(|| WorldId(s.to_owned()))
    }

    /// The hex digits.
    pub fn as_str(&self) -> &str {
        &self.0
    }
}

/// The id of an elevation model's bytes: the one the server answers for an upload of them,
/// and the one a project's description names (the first 128 bits of their SHA-256).
///
/// ```
/// let id = sylva_world::model_id(b"not really a model");
/// assert_eq!(id.as_str().len(), 32);
/// ```
pub fn model_id(bytes: &[u8]) -> WorldId {
    WorldId::of(&Sha256::digest(bytes))
}

impl fmt::Display for WorldId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_hex_of_the_right_length_is_an_id() {
        let good = "0123456789abcdef0123456789abcdef";
        assert_eq!(WorldId::parse(good).unwrap().as_str(), good);
        for bad in [
            "",
            "..",
            "../../../../etc/passwd",
            &good[1..],
            &good.to_uppercase(),
            "0123456789abcdef0123456789abcdeg",
        ] {
            assert!(WorldId::parse(bad).is_none(), "{bad}");
        }
        assert_eq!(WorldId::of(&[0xab; 32]).as_str(), "ab".repeat(16));
    }
}
