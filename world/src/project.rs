//! A project folder, as the viewer's editor saves it: the world's description (the JSON the
//! server takes, species inline) in `world.json`, the elevation model its terrain names
//! beside it as `heightmap.EXT`, and the painted masks in `masks/`. `sylva forest --project`
//! reads it whole; the server takes `world.json` as posted, after `heightmap.EXT` has been
//! uploaded (its id is the file's digest either way).

use std::io::Write;
use std::path::{Path, PathBuf};

use sylva_base::file::FileError;

use crate::description::{TerrainDescription, WorldDescription};
use crate::error::WorldError;
use crate::ground::Ground;
use crate::id::{WorldId, model_id};
use crate::limits::{MAX_DESCRIPTION_BYTES, MAX_MODEL_BYTES};

/// The world's description in a project folder.
pub const WORLD_FILE: &str = "world.json";
/// The painted masks' folder in a project (as `sylva paint` and the viewer save them).
pub const MASKS_FOLDER: &str = "masks";
/// The stem of the elevation model's file in a project (`heightmap.tif`, `heightmap.png`...).
const MODEL_STEM: &str = "heightmap";

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
    /// use sylva_world::{Project, WorldDescription};
    /// let folder = std::env::temp_dir().join("sylva-project-doctest");
    /// let description = WorldDescription::parse(br#"{"seed": 4, "area": 300}"#)?;
    /// Project::write(&folder, &description, None)?;
    /// let project = Project::read(&folder)?;
    /// assert_eq!(project.description, description);
    /// assert_eq!(project.ground()?.extent, [300.0, 300.0]);
    /// # std::fs::remove_dir_all(&folder).ok();
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn read(folder: impl AsRef<Path>) -> Result<Project, WorldError> {
        let folder = folder.as_ref().to_path_buf();
        let path = folder.join(WORLD_FILE);
        let bytes = read_bounded(&path, MAX_DESCRIPTION_BYTES as u64 + 1)?;
        let description = WorldDescription::parse(&bytes).map_err(|e| WorldError::Project {
            path,
            message: e.to_string(),
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
    ) -> Result<WorldDescription, WorldError> {
        let folder = folder.as_ref();
        std::fs::create_dir_all(folder).map_err(FileError::at(folder))?;
        let mut description = description.clone();
        if let Some(model) = model {
            let bytes = read_model_bytes(model)?;
            let ext = model
                .extension()
                .map_or("dem".into(), |e| e.to_string_lossy().to_lowercase());
            let copy = folder.join(format!("{MODEL_STEM}.{ext}"));
            // Other models' files go: the folder holds the one its terrain names.
            for old in model_files(folder).into_iter().filter(|p| *p != copy) {
                let _ = std::fs::remove_file(old);
            }
            sylva_base::file::write(&copy, |f| f.write_all(&bytes))?;
            let (spacing, height_range, crop) = match &description.terrain {
                TerrainDescription::Heightmap {
                    spacing,
                    height_range,
                    crop,
                    ..
                } => (*spacing, *height_range, *crop),
                TerrainDescription::Generated { .. } => (None, None, None),
            };
            description.terrain = TerrainDescription::Heightmap {
                id: model_id(&bytes).as_str().to_owned(),
                spacing,
                height_range,
                crop,
            };
        }
        let path = folder.join(WORLD_FILE);
        let mut json = serde_json::to_string_pretty(&description).unwrap_or_default();
        json.push('\n');
        sylva_base::file::write(&path, |f| f.write_all(json.as_bytes()))?;
        Ok(description)
    }

    /// The ground: generated from the description, or read from the folder's model file
    /// whose id the terrain names ([`WorldDescription::ground`]).
    pub fn ground(&self) -> Result<Ground, WorldError> {
        self.description.ground(|id| {
            self.model_bytes(id)
                .ok_or_else(|| WorldError::UnknownModel {
                    id: id.as_str().to_owned(),
                    hint: format!(
                        "{} names it, but no {MODEL_STEM}.* file in {} holds it",
                        WORLD_FILE,
                        self.folder.display()
                    ),
                })
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
            let bytes = read_model_bytes(&p).ok()?;
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
/// have ([`MAX_MODEL_BYTES`]).
pub fn read_model_bytes(path: &Path) -> Result<Vec<u8>, FileError> {
    read_bounded(path, MAX_MODEL_BYTES as u64)
}

/// A regular file's bytes, refused beyond `limit` before and while they are read (see
/// [`sylva_base::text_file::read_bytes`]: a device or FIFO is refused unread).
fn read_bounded(path: &Path, limit: u64) -> Result<Vec<u8>, FileError> {
    use sylva_base::text_file::{TextFileError, read_bytes};
    read_bytes(path, limit).map_err(|e| match e {
        TextFileError::Io(e) => e,
        other => FileError::new(path, std::io::Error::other(other.to_string())),
    })
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
        let ground = project.ground().unwrap();
        assert!(ground.extent[0] > 10.0 && ground.map.size() > 2);
        // Without its file the project says which id it misses.
        std::fs::remove_file(dir.join("heightmap.asc")).unwrap();
        let e = Project::read(&dir).unwrap().ground().unwrap_err();
        assert_eq!(e.code(), "unknown_heightmap", "{e}");
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
        assert!(matches!(missing, WorldError::File(_)), "{missing}");
        let _ = std::fs::remove_dir_all(&dir);
    }
}
