//! What can go wrong when growing trees.

use std::path::PathBuf;

use glam::Vec3;
use sylva_base::range::OutOfRange;
use sylva_base::text_file::TextFileError;
use thiserror::Error;

/// An error from the growth crate.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum GrowthError {
    /// A setting (the voxel size, …) is NaN, infinite or out of its range.
    #[error(transparent)]
    OutOfRange(#[from] OutOfRange),
    /// The region of a voxel grid is empty or not finite; nothing was allocated.
    #[error("the region {min} to {max} is empty or not finite")]
    EmptyRegion {
        /// Its lowest corner.
        min: Vec3,
        /// Its highest corner.
        max: Vec3,
    },
    /// The region and voxel size give more voxels than the limit; nothing was allocated.
    #[error(
        "{voxels:.3e} voxels of {voxel} m is more than the limit of {limit}: use larger voxels or a smaller region"
    )]
    TooManyVoxels {
        /// Voxels the grid would have.
        voxels: f64,
        /// The voxel side in metres.
        voxel: f32,
        /// The most a grid may have ([`MAX_VOXELS`](crate::MAX_VOXELS)).
        limit: u64,
    },
    /// Two voxel grids that must match do not (origin, voxel size or extent).
    #[error("the voxel grids have different shapes")]
    GridShapes,
    /// A tree's word opens more branches than growth follows.
    #[error("the word has more than {limit} branches: derive fewer generations")]
    TooManyBranches {
        /// The most branches grown.
        limit: usize,
    },
    /// The stand kept growing past the iteration limit.
    #[error(
        "growth did not finish in {limit} iterations: raise the limit or grow fewer generations"
    )]
    Unfinished {
        /// The limit ([`GrowthOptions::max_iterations`](crate::GrowthOptions::max_iterations)).
        limit: u32,
    },
    /// A grammar failed to derive.
    #[error("grammar: {0}")]
    Grammar(#[from] sylva_lsys::DeriveError),
    /// A mesh file has an error at a line (1-based).
    #[error("{}:{line}: {message}", file.display())]
    MeshFile {
        /// The file.
        file: PathBuf,
        /// Line of the problem.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// A file could not be read.
    #[error(transparent)]
    Read(#[from] TextFileError),
}
