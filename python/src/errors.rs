//! sylva's mistakes as Python exceptions: [`SylvaError`] for all of them, and [`ParseError`]
//! for text with a mistake at a place (a grammar, a species file), which carries the line
//! and column the Rust API names.

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use sylva::export::ExportError;
use sylva::forest::ForestError;
use sylva::lsys::{DeriveError, GrammarFileError};
use sylva::terrain::TerrainError;
use sylva::turtle::TurtleError;
use sylva::world::WorldError;

create_exception!(
    sylva,
    SylvaError,
    PyException,
    "Anything sylva refuses: a setting out of its range, a file it cannot read or write, a \
     limit reached. The message says what and how to put it right."
);

create_exception!(
    sylva,
    ParseError,
    SylvaError,
    "A grammar or species file with a mistake at a place: `line` and `column` (1-based) say \
     where, `path` names the file (None for text given directly) and `reason` what was \
     expected there."
);

/// A mistake, before it becomes a Python exception.
#[derive(Debug)]
pub(crate) enum Raised {
    /// Text with a mistake at a place.
    Parse {
        /// The whole message, as the Rust API prints it.
        message: String,
        /// What was expected there.
        reason: String,
        line: usize,
        column: usize,
        path: Option<String>,
    },
    /// Anything else, by its message.
    Other(String),
}

impl From<sylva::lsys::ParseError> for Raised {
    fn from(e: sylva::lsys::ParseError) -> Self {
        Raised::Parse {
            message: e.to_string(),
            reason: e.message.clone(),
            line: e.location.line,
            column: e.location.column,
            path: None,
        }
    }
}

impl From<GrammarFileError> for Raised {
    fn from(e: GrammarFileError) -> Self {
        let message = e.to_string();
        match e {
            GrammarFileError::Parse { path, error } => Raised::Parse {
                message,
                reason: error.message,
                line: error.location.line,
                column: error.location.column,
                path: Some(path.display().to_string()),
            },
            _ => Raised::Other(message),
        }
    }
}

impl From<ForestError> for Raised {
    fn from(e: ForestError) -> Self {
        match e {
            ForestError::SpeciesFile {
                ref file,
                line,
                column,
                ref message,
            } => Raised::Parse {
                message: e.to_string(),
                reason: message.clone(),
                line,
                column,
                path: Some(file.display().to_string()),
            },
            ForestError::Grammar(parse) => parse.into(),
            other => Raised::Other(other.to_string()),
        }
    }
}

impl From<WorldError> for Raised {
    fn from(e: WorldError) -> Self {
        match e {
            WorldError::Species(forest) => forest.into(),
            other => Raised::Other(other.to_string()),
        }
    }
}

/// Errors with nothing to add to their message.
macro_rules! by_message {
    ($($error:ty),*) => {
        $(impl From<$error> for Raised {
            fn from(e: $error) -> Self {
                Raised::Other(e.to_string())
            }
        })*
    };
}

by_message!(
    ExportError,
    TerrainError,
    DeriveError,
    TurtleError,
    sylva::base::file::FileError,
    String
);

impl From<Raised> for PyErr {
    fn from(raised: Raised) -> PyErr {
        match raised {
            Raised::Other(message) => SylvaError::new_err(message),
            Raised::Parse {
                message,
                reason,
                line,
                column,
                path,
            } => Python::attach(|py| {
                let err = ParseError::new_err(message);
                let value = err.value(py);
                let set = || -> PyResult<()> {
                    value.setattr("line", line)?;
                    value.setattr("column", column)?;
                    value.setattr("path", path)?;
                    value.setattr("reason", reason)
                };
                match set() {
                    Ok(()) => err,
                    Err(e) => e,
                }
            }),
        }
    }
}

/// A result whose error becomes a Python exception.
pub(crate) trait Raise<T> {
    /// The value, or the error as [`SylvaError`] or [`ParseError`].
    fn raise(self) -> PyResult<T>;
}

impl<T, E: Into<Raised>> Raise<T> for Result<T, E> {
    fn raise(self) -> PyResult<T> {
        self.map_err(|e| PyErr::from(e.into()))
    }
}

/// A [`SylvaError`] saying `message`: a setting out of its range.
pub(crate) fn invalid(message: impl Into<String>) -> PyErr {
    SylvaError::new_err(message.into())
}
