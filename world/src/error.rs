//! Why a world could not be described, grounded or built: one error for the CLI, the viewer
//! and the server, each variant carrying what a person needs to mend it, and a short code
//! (`bad_description`, `bad_heightmap`...) a program can branch on.

use std::path::PathBuf;

use sylva_base::file::FileError;
use sylva_forest::ForestError;
use sylva_paint::PaintError;
use sylva_terrain::TerrainError;

/// A world could not be made.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum WorldError {
    /// A setting is out of its range or malformed; the message names it.
    #[error("{0}")]
    Invalid(String),
    /// A description or file is larger than its limit.
    #[error("{0}")]
    TooLarge(String),
    /// A species named that is not bundled.
    #[error(
        "unknown species '{name}': the bundled ones are {known}; or give a species file inline as {{\"file\": \"...\"}}"
    )]
    UnknownSpecies {
        /// The name asked for (at most 80 characters of it).
        name: String,
        /// The bundled species, comma-separated.
        known: String,
    },
    /// A species file (given inline or on disk) has a mistake; the message has its line and
    /// column.
    #[error("{0}")]
    Species(ForestError),
    /// An elevation model cannot be read or does not make a world; `name` is its file or id.
    #[error("{name}: {message}")]
    Model {
        /// The model's file or id.
        name: String,
        /// What is wrong.
        message: String,
    },
    /// An elevation model does not say how far apart its samples are.
    #[error("{name}: the file does not say how far apart its samples are: give {hint}")]
    NoSpacing {
        /// The model's file or id.
        name: String,
        /// How to give the spacing (`--spacing M`, `"spacing" in the terrain`).
        hint: String,
    },
    /// The description names an elevation model that is not at hand.
    #[error("no heightmap {id}: {hint}")]
    UnknownModel {
        /// The id named.
        id: String,
        /// Where it should have come from.
        hint: String,
    },
    /// A project folder's description is not valid.
    #[error("{}: {message}", path.display())]
    Project {
        /// The description's file.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// A file could not be read or written.
    #[error(transparent)]
    File(#[from] FileError),
    /// The forest could not be built (hero trees, a budget too small, a forest over time).
    #[error("the forest: {0}")]
    Forest(ForestError),
    /// The ground could not be made.
    #[error("the terrain: {0}")]
    Terrain(#[from] TerrainError),
    /// The painted masks could not be read or applied.
    #[error("the painted masks: {0}")]
    Paint(#[from] PaintError),
}

impl From<ForestError> for WorldError {
    fn from(e: ForestError) -> WorldError {
        WorldError::Forest(e)
    }
}

impl WorldError {
    /// A short machine-readable cause: `bad_description`, `too_large`, `unknown_species`,
    /// `bad_species`, `bad_heightmap`, `unknown_heightmap`, `file` or `cannot_generate`.
    ///
    /// ```
    /// use sylva_world::WorldDescription;
    /// let e = WorldDescription::parse(br#"{"area": -1}"#).unwrap_err();
    /// assert_eq!(e.code(), "bad_description");
    /// ```
    pub fn code(&self) -> &'static str {
        match self {
            WorldError::Invalid(_) | WorldError::Project { .. } => "bad_description",
            WorldError::TooLarge(_) => "too_large",
            WorldError::UnknownSpecies { .. } => "unknown_species",
            WorldError::Species(_) => "bad_species",
            WorldError::Model { .. } | WorldError::NoSpacing { .. } => "bad_heightmap",
            WorldError::UnknownModel { .. } => "unknown_heightmap",
            WorldError::File(_) => "file",
            WorldError::Forest(_) | WorldError::Terrain(_) | WorldError::Paint(_) => {
                "cannot_generate"
            }
        }
    }

    /// Whether the mistake is in what was asked (a description, a flag, a file given),
    /// rather than in making what was asked.
    pub fn is_user_mistake(&self) -> bool {
        !matches!(
            self,
            WorldError::File(_)
                | WorldError::Forest(_)
                | WorldError::Terrain(_)
                | WorldError::Paint(_)
        )
    }
}
