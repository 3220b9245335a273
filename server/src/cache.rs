//! The cache folder: the only state a server keeps, and what several servers may share.
//!
//! ```text
//! CACHE/descriptions/ID.json            a kept world's canonical description
//! CACHE/heightmaps/ID.png               an uploaded heightmap (ID: its bytes' SHA-256)
//! CACHE/worlds/GENERATOR/ID/...         the world's tileset folder, as `sylva tiles` writes it
//! ```
//!
//! Every file is written whole or not at all (a temporary beside it, renamed into place), so a
//! server killed at any moment leaves complete files and, at worst, a temporary that is never
//! served. Generated files sit under the generator's version: a newer sylva draws the same
//! world afresh instead of serving bytes it would no longer make.

use std::io;
use std::path::{Path, PathBuf};
use std::time::{Duration, SystemTime};

use crate::error::ApiError;
use sylva::world::WorldDescription;
use sylva::world::WorldId;

/// The generator's version: the crate's, and a revision of the files' layout.
pub const GENERATOR: &str = concat!("sylva-", env!("CARGO_PKG_VERSION"), "-1");

/// Temporaries older than this are a killed writer's and are swept at start: far older than
/// any generation runs, so one of another live server sharing the folder is never taken.
const STALE_PARTIAL: Duration = Duration::from_secs(6 * 3600);

/// A cache folder.
#[derive(Debug, Clone)]
pub struct Cache {
    root: PathBuf,
}

impl Cache {
    /// Opens (creating) the cache at `root` and sweeps temporaries left by killed writers.
    pub fn open(root: impl Into<PathBuf>) -> io::Result<Cache> {
        let root = root.into();
        for folder in ["descriptions", "heightmaps", "worlds"] {
            std::fs::create_dir_all(root.join(folder))?;
        }
        let cache = Cache { root };
        cache.sweep_partials(&cache.root, 4);
        Ok(cache)
    }

    /// The folder.
    pub fn root(&self) -> &Path {
        &self.root
    }

    /// Where a world's description is kept.
    pub fn description_path(&self, id: &WorldId) -> PathBuf {
        self.root.join("descriptions").join(format!("{id}.json"))
    }

    /// Where an uploaded heightmap is kept.
    pub fn heightmap_path(&self, id: &WorldId) -> PathBuf {
        self.root.join("heightmaps").join(format!("{id}.png"))
    }

    /// A world's tileset folder.
    pub fn world_dir(&self, id: &WorldId) -> PathBuf {
        self.root.join("worlds").join(GENERATOR).join(id.as_str())
    }

    /// Keeps `description` under its id (once: a description already kept is the same
    /// bytes). Blocking.
    pub fn keep_description(&self, description: &WorldDescription) -> Result<WorldId, ApiError> {
        let id = description.id();
        let path = self.description_path(&id);
        let text = description.canonical();
        match std::fs::read(&path) {
            Ok(kept) if kept == text.as_bytes() => return Ok(id),
            Ok(_) => {
                return Err(ApiError::internal(format!(
                    "world {id}: a different description is kept under this id"
                )));
            }
            Err(e) if e.kind() == io::ErrorKind::NotFound => {}
            Err(e) => return Err(ApiError::storage(&e, "the world description")),
        }
        write_whole(&path, text.as_bytes())
            .map_err(|e| ApiError::storage(&e, "the world description"))?;
        Ok(id)
    }

    /// The description kept under `id`. Blocking.
    pub fn description(&self, id: &WorldId) -> Result<WorldDescription, ApiError> {
        match std::fs::read(self.description_path(id)) {
            Ok(bytes) => WorldDescription::parse(&bytes).map_err(|e| {
                ApiError::internal(format!(
                    "world {id}: its kept description no longer parses: {e}"
                ))
            }),
            Err(e) if e.kind() == io::ErrorKind::NotFound => Err(ApiError::not_found(
                "unknown_world",
                format!("no world {id}: POST its description to /worlds first"),
            )),
            Err(e) => Err(ApiError::internal(format!("world {id}: {e}"))),
        }
    }

    /// Removes temporaries older than [`STALE_PARTIAL`] under `folder`, `depth` levels down.
    fn sweep_partials(&self, folder: &Path, depth: u32) {
        let Ok(entries) = std::fs::read_dir(folder) else {
            return;
        };
        let now = SystemTime::now();
        for entry in entries.flatten() {
            let path = entry.path();
            let Ok(meta) = entry.metadata() else { continue };
            if meta.is_dir() {
                if depth > 0 {
                    self.sweep_partials(&path, depth - 1);
                }
                continue;
            }
            let partial = path
                .file_name()
                .and_then(|n| n.to_str())
                .is_some_and(|n| n.contains("sylva-partial"));
            let old = meta
                .modified()
                .ok()
                .and_then(|m| now.duration_since(m).ok())
                .is_some_and(|age| age > STALE_PARTIAL);
            if partial && old {
                let _ = std::fs::remove_file(&path);
            }
        }
    }
}

/// Writes `bytes` at `path` whole or not at all.
pub(crate) fn write_whole(path: &Path, bytes: &[u8]) -> io::Result<()> {
    sylva::base::file::write(path, |w| io::Write::write_all(w, bytes))
        .map_err(|e| io::Error::new(e.kind(), e.to_string()))
}
