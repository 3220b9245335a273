//! Only regular files are replaced or read: the file a write to a path would replace (a
//! link's target), and the error for a path that is a device, a FIFO, a socket or a folder.

use std::io;
use std::path::{Path, PathBuf};

use crate::file_error::FileError;

/// The regular file a write to `path` would replace (see `AtomicFile::create`), or the
/// error that write would meet: for checking a run's outputs before its work.
///
/// ```
/// use std::path::Path;
/// use sylva_base::file::writable_destination;
/// let new = std::env::temp_dir().join("sylva-new-output.glb");
/// assert_eq!(writable_destination(&new)?, new);
/// # #[cfg(unix)]
/// assert!(writable_destination(Path::new("/dev/null")).is_err());
/// # Ok::<(), sylva_base::file::FileError>(())
/// ```
pub fn writable_destination(path: &Path) -> Result<PathBuf, FileError> {
    let metadata = match std::fs::symlink_metadata(path) {
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(path.to_path_buf()),
        Err(e) => return Err(FileError::new(path, e)),
        Ok(m) => m,
    };
    if metadata.is_file() {
        return Ok(path.to_path_buf());
    }
    if !metadata.file_type().is_symlink() {
        return Err(FileError::new(path, not_regular(&metadata.file_type())));
    }
    let target = std::fs::canonicalize(path).map_err(|e| {
        let cause = if e.kind() == io::ErrorKind::NotFound {
            io::Error::new(
                io::ErrorKind::NotFound,
                "a link to nothing: remove it or name another path",
            )
        } else {
            e
        };
        FileError::new(path, cause)
    })?;
    let kind = std::fs::metadata(&target)
        .map_err(FileError::at(&target))?
        .file_type();
    if kind.is_file() {
        Ok(target)
    } else {
        Err(FileError::new(path, not_regular(&kind)))
    }
}

/// The error for a path that is not a regular file, naming what it is.
pub(crate) fn not_regular(kind: &std::fs::FileType) -> io::Error {
    if kind.is_dir() {
        return io::Error::new(io::ErrorKind::IsADirectory, "a folder, not a file");
    }
    io::Error::new(
        io::ErrorKind::InvalidInput,
        format!("{}, not a regular file", special_kind(kind)),
    )
}

/// What a file that is not regular is, in words.
fn special_kind(kind: &std::fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if kind.is_fifo() {
            return "a FIFO (named pipe)";
        }
        if kind.is_socket() {
            return "a socket";
        }
        if kind.is_char_device() || kind.is_block_device() {
            return "a device";
        }
    }
    if kind.is_symlink() {
        return "a link";
    }
    "not a file"
}
