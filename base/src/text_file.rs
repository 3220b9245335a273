//! Reading a text file with a size limit checked before and while reading, so that a path
//! such as `/dev/zero` or a huge file ends in an error instead of exhausting memory.

use std::io::{self, Read};
use std::path::{Path, PathBuf};

use crate::file::FileError;

/// Why a text file could not be read.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum TextFileError {
    /// The file could not be opened or read: its path and the system's error.
    #[error(transparent)]
    Io(#[from] FileError),
    /// The file holds more than the limit. Split it or check that the path is right.
    #[error("{}: larger than the limit of {limit} bytes", path.display())]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// The limit in force.
        limit: u64,
    },
    /// The file is not UTF-8 text.
    #[error("{}: not UTF-8 text", path.display())]
    NotText {
        /// The file.
        path: PathBuf,
    },
}

/// Reads `path` as UTF-8 text of at most `limit` bytes. A regular file's size is checked
/// before reading; anything else (a device, a pipe) is read at most `limit + 1` bytes.
///
/// ```
/// let dir = std::env::temp_dir().join("sylva-base-doctest.txt");
/// std::fs::write(&dir, "axiom: F").unwrap();
/// assert_eq!(sylva_base::text_file::read(&dir, 100).unwrap(), "axiom: F");
/// assert!(sylva_base::text_file::read(&dir, 4).is_err());
/// # std::fs::remove_file(&dir).ok();
/// ```
pub fn read(path: &Path, limit: u64) -> Result<String, TextFileError> {
    let io = |e: io::Error| TextFileError::Io(FileError::new(path, e));
    let too_large = || TextFileError::TooLarge {
        path: path.to_path_buf(),
        limit,
    };
    let file = std::fs::File::open(path).map_err(io)?;
    let metadata = file.metadata().map_err(io)?;
    if metadata.is_dir() {
        return Err(io(io::Error::new(
            io::ErrorKind::IsADirectory,
            "a folder, not a file",
        )));
    }
    if metadata.is_file() && metadata.len() > limit {
        return Err(too_large());
    }
    let mut bytes = Vec::new();
    file.take(limit.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(io)?;
    if bytes.len() as u64 > limit {
        return Err(too_large());
    }
    String::from_utf8(bytes).map_err(|_| TextFileError::NotText {
        path: path.to_path_buf(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Found in review: a species file naming `grammar: /dev/zero` read until killed.
    #[test]
    #[cfg(unix)]
    fn endless_devices_stop_at_the_limit() {
        let err = read(Path::new("/dev/zero"), 1 << 20).unwrap_err();
        assert!(matches!(err, TextFileError::TooLarge { limit, .. } if limit == 1 << 20));
    }

    #[test]
    fn missing_files_and_directories_are_io_errors() {
        let missing = read(Path::new("/no/such/file"), 10).unwrap_err();
        assert!(matches!(&missing, TextFileError::Io(e) if e.kind() == io::ErrorKind::NotFound));
        assert!(
            missing.to_string().ends_with("; check the path"),
            "{missing}"
        );
        let folder = read(&std::env::temp_dir(), 10).unwrap_err();
        assert!(
            matches!(&folder, TextFileError::Io(e) if e.kind() == io::ErrorKind::IsADirectory),
            "{folder}"
        );
    }
}
