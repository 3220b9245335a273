//! Errors of terrain generation and input/output.

use std::sync::Arc;

pub use sylva_base::range::OutOfRange;

/// Why a heightmap could not be made, read or written.
#[derive(Debug, Clone, thiserror::Error)]
#[non_exhaustive]
pub enum TerrainError {
    /// Heightmaps are (2^n + 1) samples square, n from 1 to [`MAX_LEVELS`](crate::MAX_LEVELS).
    /// Pick a size such as 257, 513, 1025 or 4097.
    #[error("size {0} is not 2^n + 1 with 1 <= n <= 14 (for example 257, 513, 1025, 4097)")]
    BadSize(usize),
    /// A setting is NaN, infinite or outside its range.
    #[error(transparent)]
    OutOfRange(#[from] OutOfRange),
    /// A PNG heightmap is not 16-bit grayscale.
    #[error(
        "the image has {channels} channel(s) of {bits} bits: a heightmap is a 16-bit grayscale PNG"
    )]
    NotGrayscale16 {
        /// Channels per pixel.
        channels: u8,
        /// Bits per channel.
        bits: u8,
    },
    /// A heightmap image is not square.
    #[error("the image is {width} x {height}: a heightmap is square")]
    NotSquare {
        /// Its width in pixels.
        width: u32,
        /// Its height in pixels.
        height: u32,
    },
    /// A PNG without sylva's `sylva:heights` chunk was read with no height range given.
    #[error(
        "the PNG does not say what heights its samples stand for (no sylva:heights chunk): give its height range and spacing"
    )]
    NoHeightRange,
    /// Raw samples do not fill a whole number of samples.
    #[error("{bytes} bytes is not a whole number of {sample_bytes}-byte samples")]
    PartialSample {
        /// Bytes given.
        bytes: usize,
        /// Bytes per sample.
        sample_bytes: usize,
    },
    /// Raw samples do not make a square map.
    #[error("{samples} samples do not make a square map")]
    NotSquareSamples {
        /// Samples given.
        samples: usize,
    },
    /// The heights given do not fill the grid.
    #[error("{heights} heights for a {size} x {size} grid")]
    HeightCount {
        /// Heights given.
        heights: usize,
        /// Samples per side of the grid.
        size: usize,
    },
    /// A height is NaN or infinite.
    #[error("height {index} (row {row}, column {column}) is not a finite number", row = index / size, column = index % size)]
    NonFiniteHeight {
        /// Index of the sample, row-major.
        index: usize,
        /// Samples per side of the grid.
        size: usize,
    },
    /// An elevation model claims more samples than are read.
    #[error("the elevation model has {what}: more than the limit of {limit}")]
    TooLarge {
        /// What it claims.
        what: String,
        /// The limit.
        limit: String,
    },
    /// An elevation model's file is not what its format says.
    #[error("{format}: {message}")]
    Dem {
        /// The format.
        format: &'static str,
        /// What is wrong.
        message: String,
    },
    /// An ESRI ASCII grid is malformed.
    #[error("ASCII grid, line {line}, column {column}: {message}")]
    AsciiGrid {
        /// Line, from 1.
        line: usize,
        /// Column, from 1.
        column: usize,
        /// What is wrong.
        message: String,
    },
    /// Reading or writing the data failed.
    #[error("reading or writing heights: {0}")]
    Io(#[source] Arc<std::io::Error>),
    /// The PNG could not be decoded.
    #[error("decoding the PNG: {0}")]
    PngDecoding(#[source] Arc<png::DecodingError>),
    /// The PNG could not be encoded.
    #[error("encoding the PNG: {0}")]
    PngEncoding(#[source] Arc<png::EncodingError>),
}

impl From<std::io::Error> for TerrainError {
    fn from(e: std::io::Error) -> Self {
        TerrainError::Io(Arc::new(e))
    }
}

impl From<png::DecodingError> for TerrainError {
    fn from(e: png::DecodingError) -> Self {
        TerrainError::PngDecoding(Arc::new(e))
    }
}

impl From<png::EncodingError> for TerrainError {
    fn from(e: png::EncodingError) -> Self {
        TerrainError::PngEncoding(Arc::new(e))
    }
}

/// An error unless `value` is finite and `ok` (see [`sylva_base::range::check`]).
pub(crate) fn check(
    name: &'static str,
    value: f64,
    ok: bool,
    expected: &'static str,
) -> Result<(), TerrainError> {
    Ok(sylva_base::range::check(name, value, ok, expected)?)
}
