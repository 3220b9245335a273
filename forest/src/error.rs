//! Errors of forest generation and export.

use std::path::PathBuf;

use sylva_instancing::InstancingError;
use sylva_lsys::ParseError;

/// Why a forest could not be built or written.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ForestError {
    /// A species file (or the grammar it names) has an error at the given place.
    #[error("{}:{line}:{column}: {message}", file.display())]
    SpeciesFile {
        /// The file.
        file: PathBuf,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// What is wrong.
        message: String,
    },
    /// A grammar given as text failed to parse.
    #[error("grammar: {0}")]
    Grammar(#[from] ParseError),
    /// Building a species' instance cache failed.
    #[error("instancing: {0}")]
    Instancing(#[from] InstancingError),
    /// A setting is out of range; the message names it and says what is allowed.
    #[error("{0}")]
    BadParameter(String),
    /// The exporter found something that would make an invalid file, and wrote nothing.
    #[error("refusing to write an invalid glTF file: {0}")]
    InvalidExport(String),
    /// Growing trees in their environment failed.
    #[error("growth: {0}")]
    Growth(#[from] sylva_growth::GrowthError),
    /// Reading or writing a file failed.
    #[error("{path}: {message}")]
    Io {
        /// The file.
        path: String,
        /// The system's message.
        message: String,
    },
}
