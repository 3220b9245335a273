//! Reading a file with a size limit checked before and while reading, so that a huge file
//! ends in an error instead of exhausting memory; only regular files are read, so that a
//! path such as `/dev/zero` or a FIFO ends in an error instead of reading for ever or
//! waiting for a writer.

use std::io::{self, Read};
use std::path::{Path, PathBuf};

use crate::destination::not_regular;
use crate::file_error::FileError;

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

/// Reads `path` as UTF-8 text of at most `limit` bytes (see [`read_bytes`]).
///
/// ```
/// let dir = std::env::temp_dir().join("sylva-base-doctest.txt");
/// std::fs::write(&dir, "axiom: F").unwrap();
/// assert_eq!(sylva_base::text_file::read(&dir, 100).unwrap(), "axiom: F");
/// assert!(sylva_base::text_file::read(&dir, 4).is_err());
/// # std::fs::remove_file(&dir).ok();
/// ```
pub fn read(path: &Path, limit: u64) -> Result<String, TextFileError> {
    String::from_utf8(read_bytes(path, limit)?).map_err(|_| TextFileError::NotText {
        path: path.to_path_buf(),
    })
}

/// Reads the regular file `path` (a link is followed) if it holds at most `limit` bytes: its
/// size is checked before reading and the bytes actually read are counted (a file that grows,
/// or says it is empty as `/proc`'s do, stops at the limit too). A folder, a device, a FIFO
/// or a socket is refused before it is opened, so a FIFO never blocks.
///
/// ```
/// use std::path::Path;
/// use sylva_base::text_file::read_bytes;
/// let path = std::env::temp_dir().join("sylva-base-bytes-doctest.bin");
/// std::fs::write(&path, [1u8, 2, 3]).unwrap();
/// assert_eq!(read_bytes(&path, 3).unwrap(), [1, 2, 3]);
/// assert!(read_bytes(&path, 2).is_err());
/// # #[cfg(unix)]
/// assert!(read_bytes(Path::new("/dev/zero"), 1 << 20).is_err());
/// # std::fs::remove_file(&path).ok();
/// ```
pub fn read_bytes(path: &Path, limit: u64) -> Result<Vec<u8>, TextFileError> {
    let io = |e: io::Error| TextFileError::Io(FileError::new(path, e));
    let too_large = || TextFileError::TooLarge {
        path: path.to_path_buf(),
        limit,
    };
    let metadata = std::fs::metadata(path).map_err(io)?;
    if !metadata.is_file() {
        return Err(io(not_regular(&metadata.file_type())));
    }
    if metadata.len() > limit {
        return Err(too_large());
    }
    let file = std::fs::File::open(path).map_err(io)?;
    let mut bytes = Vec::new();
    file.take(limit.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(io)?;
    if bytes.len() as u64 > limit {
        return Err(too_large());
    }
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Found in review: a species file naming `grammar: /dev/zero` read until killed; and
    /// `--terrain /dev/zero` read 16.7 GB (issue 60).
    #[test]
    #[cfg(unix)]
    fn devices_are_refused_unread() {
        let err = read(Path::new("/dev/zero"), 1 << 20).unwrap_err();
        assert!(
            err.to_string().contains("a device, not a regular file"),
            "{err}"
        );
    }

    /// A FIFO with no writer would block `open` for ever: refused before it is opened.
    #[test]
    #[cfg(unix)]
    fn fifos_are_refused_without_blocking() {
        let path = std::env::temp_dir().join(format!("sylva-fifo-{}", std::process::id()));
        let _ = std::fs::remove_file(&path);
        let made = std::process::Command::new("mkfifo").arg(&path).status();
        if !made.is_ok_and(|s| s.success()) {
            return; // no mkfifo here: nothing to test
        }
        let err = read_bytes(&path, 10).unwrap_err();
        assert!(err.to_string().contains("FIFO"), "{err}");
        std::fs::remove_file(&path).ok();
    }

    /// `/proc` files say they are empty and are not: the bytes read are counted.
    #[test]
    #[cfg(target_os = "linux")]
    fn files_that_say_they_are_empty_stop_at_the_limit() {
        let err = read_bytes(Path::new("/proc/self/maps"), 4).unwrap_err();
        assert!(
            matches!(err, TextFileError::TooLarge { limit: 4, .. }),
            "{err}"
        );
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
