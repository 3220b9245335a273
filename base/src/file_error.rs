//! The error of reading or writing a file: its path and the system's error, with a hint
//! for the common causes.

use std::fmt;
use std::io;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Reading or writing a file failed: the path and the system's error.
///
/// Cloneable and comparable (by path and [`io::ErrorKind`]) so that error enums holding it
/// can be too. `Display` names the file and, for the common causes, what to do.
#[derive(Debug, Clone)]
pub struct FileError {
    /// The file or folder.
    pub path: PathBuf,
    /// The system's error.
    pub source: Arc<io::Error>,
}

impl FileError {
    /// The error `source` met at `path`.
    pub fn new(path: impl Into<PathBuf>, source: io::Error) -> Self {
        FileError {
            path: path.into(),
            source: Arc::new(source),
        }
    }

    /// A closure for `map_err` that names `path`.
    pub fn at(path: &Path) -> impl Fn(io::Error) -> FileError + '_ {
        move |e| FileError::new(path, e)
    }

    /// The kind of the system's error.
    pub fn kind(&self) -> io::ErrorKind {
        self.source.kind()
    }
}

impl PartialEq for FileError {
    fn eq(&self, other: &Self) -> bool {
        self.path == other.path && self.kind() == other.kind()
    }
}

impl fmt::Display for FileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.path.display(), self.source)?;
        let hint = match self.kind() {
            io::ErrorKind::NotFound => "; check the path",
            io::ErrorKind::PermissionDenied | io::ErrorKind::ReadOnlyFilesystem => {
                "; choose a place you may write to"
            }
            io::ErrorKind::StorageFull | io::ErrorKind::QuotaExceeded => {
                "; free some space or write elsewhere (nothing was replaced)"
            }
            io::ErrorKind::UnexpectedEof => "; the file is cut short: write it again",
            _ => "",
        };
        f.write_str(hint)
    }
}

impl std::error::Error for FileError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(&*self.source)
    }
}
