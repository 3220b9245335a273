//! A project folder, as the viewer's editor saves it: the world's description (the JSON the
//! server takes, species inline) in `world.json`, the elevation model its terrain names
//! beside it as `heightmap.EXT`, and the painted masks in `masks/`. `sylva forest --project`
//! reads it whole; the server takes `world.json` as posted, after `heightmap.EXT` has been
//! uploaded (its id is the file's digest either way).

use std::io::Write;
use std::path::{Path, PathBuf};

use sylva::base::file::FileError;
use sylva::terrain::Heightmap;

use crate::description::{TerrainDescription, WorldDescription};
use crate::error::ApiError;
use crate::heightmaps::MAX_HEIGHTMAP_BYTES;
pub use crate::heightmaps::model_id;
use crate::id::WorldId;

/// The world's description in a project folder.
pub const WORLD_FILE: &str = "world.json";
/// The painted masks' folder in a project (as `sylva paint` and the viewer save them).
pub const MASKS_FOLDER: &str = "masks";
/// The stem of the elevation model's file in a project (`heightmap.tif`, `heightmap.png`...).
const MODEL_STEM: &str = "heightmap";

/// A project folder could not be read or written.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ProjectError {
    /// A file could not be read or written.
    #[error(transparent)]
    File(#[from] FileError),
    /// `world.json` is not a world description; the message names the field.
    #[error("{}: {message}", path.display())]
    Description {
        /// The description's file.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// The terrain names an elevation model no file in the folder holds.
    #[error(
        "{}: the terrain names heightmap {id}, but no {MODEL_STEM}.* file in the folder holds it",
        folder.display()
    )]
    MissingModel {
        /// The project folder.
        folder: PathBuf,
        /// The id `world.json` names.
        id: String,
    },
    /// The ground could not be made (an unreadable model, a bad spacing).
    #[error("{}: {message}", folder.display())]
    Ground {
        /// The project folder.
        folder: PathBuf,
        /// What is wrong.
        message: String,
    },
}

/// A project folder's world.
#[derive(Debug, Clone, PartialEq)]
pub struct Project {
    /// The folder.
    pub folder: PathBuf,
    /// Its world's description.
    pub description: WorldDescription,
}

impl Project {
    /// Reads `folder/world.json`, checked as the server checks a posted description.
    ///
    /// ```
    /// use sylva_server::{WorldDescription, project::Project};
    /// let folder = std::env::temp_dir().join("sylva-project-doctest");
    /// let description = WorldDescription::parse(br#"{"seed": 4, "area": 300}"#)?;
    /// Project::write(&folder, &description, None)?;
    /// let project = Project::read(&folder)?;
    /// assert_eq!(project.description, description);
    /// let (map, extent) = project.ground()?;
    /// assert_eq!(extent, [300.0, 300.0]);
    /// # std::fs::remove_dir_all(&folder).ok();
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn read(folder: impl AsRef<Path>) -> Result<Project, ProjectError> {
        let folder = folder.as_ref().to_path_buf();
        let path = folder.join(WORLD_FILE);
        let bytes = read_bounded(&path, crate::description::MAX_DESCRIPTION_BYTES as u64 + 1)?;
        let description =
            WorldDescription::parse(&bytes).map_err(|e| ProjectError::Description {
                path,
                message: e.message,
            })?;
        Ok(Project {
            folder,
            description,
        })
    }

    /// Writes `description` as `folder/world.json`, atomically; with `model` (an elevation
    /// model's file), copies it beside as `heightmap.EXT` and names it in the terrain (its
    /// spacing and height range are kept as the description gives them).
    pub fn write(
        folder: impl AsRef<Path>,
        description: &WorldDescription,
        model: Option<&Path>,
    ) -> Result<WorldDescription, ProjectError> {
        let folder = folder.as_ref();
        std::fs::create_dir_all(folder).map_err(FileError::at(folder))?;
        let mut description = description.clone();
        if let Some(model) = model {
            let bytes = read_model(model)?;
            let ext = model
                .extension()
                .map_or("dem".into(), |e| e.to_string_lossy().to_lowercase());
            let copy = folder.join(format!("{MODEL_STEM}.{ext}"));
            // Other models' files go: the folder holds the one its terrain names.
            for old in model_files(folder).into_iter().filter(|p| *p != copy) {
                let _ = std::fs::remove_file(old);
            }
            sylva::base::file::write(&copy, |f| f.write_all(&bytes))?;
            let (spacing, height_range) = match &description.terrain {
                TerrainDescription::Heightmap {
                    spacing,
                    height_range,
                    ..
                } => (*spacing, *height_range),
                TerrainDescription::Generated { .. } => (None, None),
            };
            description.terrain = TerrainDescription::Heightmap {
                id: model_id(&bytes).as_str().to_owned(),
                spacing,
                height_range,
            };
        }
        let path = folder.join(WORLD_FILE);
        let mut json = serde_json::to_string_pretty(&description).unwrap_or_default();
        json.push('\n');
        sylva::base::file::write(&path, |f| f.write_all(json.as_bytes()))?;
        Ok(description)
    }

    /// The ground: generated from the description, or read from the folder's model file
    /// whose id the terrain names.
    pub fn ground(&self) -> Result<(Heightmap, [f32; 2]), ProjectError> {
        let mut missing = None;
        let ground = self.description.ground(|id| {
            self.model_bytes(id).ok_or_else(|| {
                missing = Some(id.as_str().to_owned());
                ApiError::bad_request("unknown_heightmap", "")
            })
        });
        if let Some(id) = missing {
            return Err(ProjectError::MissingModel {
                folder: self.folder.clone(),
                id,
            });
        }
        ground.map_err(|e| ProjectError::Ground {
            folder: self.folder.clone(),
            message: e.message,
        })
    }

    /// The folder's file holding the elevation model the terrain names, if the terrain
    /// names one and the folder holds it.
    pub fn model(&self) -> Option<PathBuf> {
        let TerrainDescription::Heightmap { id, .. } = &self.description.terrain else {
            return None;
        };
        Some(self.model_with(&WorldId::parse(id)?)?.0)
    }

    /// The bytes of the folder's model file whose id is `id`.
    fn model_bytes(&self, id: &WorldId) -> Option<Vec<u8>> {
        Some(self.model_with(id)?.1)
    }

    /// The folder's model file whose bytes have the id `id`, and its bytes.
    fn model_with(&self, id: &WorldId) -> Option<(PathBuf, Vec<u8>)> {
        model_files(&self.folder).into_iter().find_map(|p| {
            let bytes = read_model(&p).ok()?;
            (model_id(&bytes) == *id).then_some((p, bytes))
        })
    }

    /// The folder's painted masks, if it has them.
    pub fn masks(&self) -> Option<PathBuf> {
        let masks = self.folder.join(MASKS_FOLDER);
        masks.is_dir().then_some(masks)
    }
}

/// The elevation-model files in `folder` (`heightmap.*`), sorted.
fn model_files(folder: &Path) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(folder)
        .into_iter()
        .flatten()
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.is_file() && p.file_stem().is_some_and(|s| s == MODEL_STEM))
        .collect();
    files.sort();
    files
}

/// An elevation model's bytes, refused before they are read beyond the size an upload may
/// have ([`MAX_HEIGHTMAP_BYTES`]).
pub fn read_model(path: &Path) -> Result<Vec<u8>, FileError> {
    read_bounded(path, MAX_HEIGHTMAP_BYTES as u64)
}

/// A file's bytes, refused beyond `limit` before they are read.
fn read_bounded(path: &Path, limit: u64) -> Result<Vec<u8>, FileError> {
    let size = std::fs::metadata(path).map_err(FileError::at(path))?.len();
    if size > limit {
        return Err(FileError::new(
            path,
            std::io::Error::other(format!("{size} bytes is over the limit of {limit}")),
        ));
    }
    std::fs::read(path).map_err(FileError::at(path))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn folder(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("sylva-project-{name}"));
        let _ = std::fs::remove_dir_all(&dir);
        dir
    }

    /// A project on the user's own elevation model carries the file, named by the id the
    /// server gives the same bytes, and reads back to the same ground.
    #[test]
    fn a_model_travels_with_its_project() {
        let dir = folder("model");
        let model = Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../terrain/tests/data/dems/west_bijou_escarpment.asc"
        ));
        let bytes = std::fs::read(model).unwrap();
        let description = WorldDescription::default();
        let written = Project::write(&dir, &description, Some(model)).unwrap();
        let TerrainDescription::Heightmap { id, .. } = &written.terrain else {
            panic!("{:?}", written.terrain)
        };
        assert_eq!(*id, model_id(&bytes).as_str());
        assert!(dir.join("heightmap.asc").is_file());
        let project = Project::read(&dir).unwrap();
        assert_eq!(project.model(), Some(dir.join("heightmap.asc")));
        assert_eq!(project.description, written);
        let (map, extent) = project.ground().unwrap();
        assert!(extent[0] > 10.0 && map.size() > 2);
        // Without its file the project says which id it misses.
        std::fs::remove_file(dir.join("heightmap.asc")).unwrap();
        let e = Project::read(&dir).unwrap().ground().unwrap_err();
        assert!(matches!(e, ProjectError::MissingModel { .. }), "{e}");
        assert!(e.to_string().contains(id.as_str()), "{e}");
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_bad_description_names_its_file_and_field() {
        let dir = folder("bad");
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join(WORLD_FILE), r#"{"area": -5}"#).unwrap();
        let e = Project::read(&dir).unwrap_err().to_string();
        assert!(e.contains("world.json") && e.contains("area"), "{e}");
        let missing = Project::read(folder("none")).unwrap_err();
        assert!(matches!(missing, ProjectError::File(_)), "{missing}");
        let _ = std::fs::remove_dir_all(&dir);
    }
}
