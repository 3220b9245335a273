//! What can go wrong when growing trees.

use thiserror::Error;

/// An error from the growth crate.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum GrowthError {
    /// The region and voxel size give a grid that is empty, not finite, or larger than the
    /// limit; nothing was allocated.
    #[error("voxel grid: {0}")]
    Grid(String),
    /// A parameter out of its range.
    #[error("{0}")]
    BadParameter(String),
    /// A grammar failed to derive.
    #[error("grammar: {0}")]
    Grammar(#[from] sylva_lsys::DeriveError),
    /// A mesh file has an error at a line (1-based).
    #[error("{file}:{line}: {message}")]
    MeshFile {
        /// The file.
        file: String,
        /// Line of the problem.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// A file could not be read (the message names it).
    #[error("{0}")]
    Io(String),
}
