//! Errors of terrain generation and input/output.

/// Why a heightmap could not be made, read or written.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum TerrainError {
    /// Heightmaps are (2^n + 1) samples square, n from 1 to [`MAX_LEVELS`](crate::MAX_LEVELS).
    /// Pick a size such as 257, 513, 1025 or 4097.
    #[error("size {0} is not 2^n + 1 with 1 <= n <= 14 (for example 257, 513, 1025, 4097)")]
    BadSize(usize),
    /// A parameter is NaN, infinite or outside its range; the message names it.
    #[error("{name} = {value} is invalid: {expected}")]
    BadParameter {
        /// Which parameter.
        name: &'static str,
        /// Its value.
        value: f64,
        /// What it must be.
        expected: &'static str,
    },
    /// The data given does not match the expected size or format.
    #[error("bad heightmap data: {0}")]
    BadData(String),
    /// Reading or writing failed.
    #[error("i/o: {0}")]
    Io(String),
}

pub(crate) fn check(
    name: &'static str,
    value: f64,
    ok: bool,
    expected: &'static str,
) -> Result<(), TerrainError> {
    if value.is_finite() && ok {
        Ok(())
    } else {
        Err(TerrainError::BadParameter {
            name,
            value,
            expected,
        })
    }
}
