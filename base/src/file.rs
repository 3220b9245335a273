//! Files written so that they cannot tear: every output goes to a temporary file beside its
//! destination and is renamed into place only once it is whole and on disk, so a full disk, a
//! crash or an interrupted run leaves the previous file (or none), never half of a new one.
//! Sets of files that belong together (a paint layer's masks) are replaced as one folder.

use std::fs::File;
use std::io::{self, BufWriter, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

pub use crate::destination::writable_destination;
pub use crate::file_error::FileError;
pub use crate::scratch::{scratch_beside, sweep_abandoned};

/// The folder holding `path` (`.` for a bare file name).
fn parent_of(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// Flushes a folder's entries (the renames into it) to disk; where folders cannot be opened
/// for that (not on Unix), the rename itself is what there is.
fn sync_folder(folder: &Path) -> io::Result<()> {
    #[cfg(unix)]
    File::open(folder)?.sync_all()?;
    #[cfg(not(unix))]
    let _ = folder;
    Ok(())
}

/// A file being written: a temporary beside its destination, renamed into place by
/// [`AtomicFile::commit`]. Dropped without a commit (an error, a panic), the temporary is
/// removed and the destination is untouched.
///
/// ```
/// use std::io::Write;
/// use sylva_base::file::AtomicFile;
///
/// let path = std::env::temp_dir().join("sylva-atomic-doctest.txt");
/// std::fs::write(&path, "old").unwrap();
/// let mut file = AtomicFile::create(&path)?;
/// file.write_all(b"new").unwrap();
/// assert_eq!(std::fs::read_to_string(&path).unwrap(), "old"); // not yet
/// file.commit()?;
/// assert_eq!(std::fs::read_to_string(&path).unwrap(), "new");
/// # std::fs::remove_file(&path).ok();
/// # Ok::<(), sylva_base::file::FileError>(())
/// ```
#[derive(Debug)]
pub struct AtomicFile {
    writer: Option<BufWriter<File>>,
    /// A flush to disk started by [`AtomicFile::start_writeback`], perhaps still running.
    writeback: Option<std::thread::JoinHandle<io::Result<()>>>,
    temporary: PathBuf,
    destination: PathBuf,
}

impl AtomicFile {
    /// Starts writing `destination`: creates the temporary beside it. Only a regular file
    /// is replaced: a new path or a regular file is written; a link to a regular file is
    /// written through (its target is replaced, atomically, and the link stays); a device,
    /// a FIFO, a socket, a folder or a link to none of these is refused, untouched.
    ///
    /// ```
    /// # #[cfg(unix)] {
    /// use sylva_base::file::AtomicFile;
    /// let refused = AtomicFile::create("/dev/null").unwrap_err();
    /// assert!(refused.to_string().contains("a device, not a regular file"), "{refused}");
    /// # }
    /// ```
    pub fn create(destination: impl AsRef<Path>) -> Result<AtomicFile, FileError> {
        let destination = writable_destination(destination.as_ref())?;
        sweep_abandoned(parent_of(&destination));
        let temporary = scratch_beside(&destination, "sylva-partial");
        let file = File::create(&temporary).map_err(|e| FileError::new(&destination, e))?;
        Ok(AtomicFile {
            writer: Some(BufWriter::with_capacity(1 << 20, file)),
            writeback: None,
            temporary,
            destination,
        })
    }

    /// The file this will become.
    pub fn destination(&self) -> &Path {
        &self.destination
    }

    /// Starts putting what was written so far on disk in the background (`sync_data` on a
    /// thread of its own), so that [`AtomicFile::commit`]'s flush has less left to wait for:
    /// for large files, called now and then while the rest is still being made. Does nothing
    /// while the previous one runs.
    ///
    /// ```
    /// use sylva_base::file::AtomicFile;
    /// let path = std::env::temp_dir().join("sylva-writeback-doctest.bin");
    /// let mut file = AtomicFile::create(&path)?;
    /// file.put(&[7; 1 << 16])?;
    /// file.start_writeback()?;
    /// file.put(&[8; 1 << 16])?;
    /// file.commit()?;
    /// assert_eq!(std::fs::metadata(&path).unwrap().len(), 2 << 16);
    /// # std::fs::remove_file(&path).ok();
    /// # Ok::<(), sylva_base::file::FileError>(())
    /// ```
    pub fn start_writeback(&mut self) -> Result<(), FileError> {
        if self.writeback.as_ref().is_some_and(|h| !h.is_finished()) {
            return Ok(());
        }
        self.finish_writeback()?;
        let file = self
            .writer()
            .and_then(|w| {
                w.flush()?;
                w.get_ref().try_clone()
            })
            .map_err(|e| FileError::new(&self.destination, e))?;
        self.writeback = Some(std::thread::spawn(move || file.sync_data()));
        Ok(())
    }

    /// Waits for a background flush and reports how it went.
    fn finish_writeback(&mut self) -> Result<(), FileError> {
        let Some(running) = self.writeback.take() else {
            return Ok(());
        };
        let done = running
            .join()
            .unwrap_or_else(|_| Err(io::Error::other("the flush to disk panicked")));
        done.map_err(|e| FileError::new(&self.destination, e))
    }

    /// Flushes the file to disk and renames it into place, replacing any file there.
    pub fn commit(mut self) -> Result<(), FileError> {
        // On an error the file is dropped uncommitted, which removes it.
        self.finish_writeback()?;
        let at = FileError::at(&self.destination);
        let writer = self.writer.take().ok_or_else(|| {
            FileError::new(&self.destination, io::Error::other("already committed"))
        })?;
        let placed = writer
            .into_inner()
            .map_err(|e| e.into_error())
            .and_then(|file| file.sync_all())
            .and_then(|()| std::fs::rename(&self.temporary, &self.destination));
        if let Err(e) = placed {
            // Not in place: the partial file must not stay behind.
            let _ = std::fs::remove_file(&self.temporary);
            return Err(at(e));
        }
        sync_folder(parent_of(&self.destination)).map_err(at)
    }

    /// Writes all of `bytes` at the current position; an error names the destination.
    pub fn put(&mut self, bytes: &[u8]) -> Result<(), FileError> {
        self.write_all(bytes)
            .map_err(|e| FileError::new(&self.destination, e))
    }

    /// Writes all of `bytes` at byte `offset` of the file (for layouts decided beforehand),
    /// in one positioned write where the platform has them. Whether the position [`put`]
    /// writes at moves is left open: call [`AtomicFile::size`] or seek before writing
    /// sequentially again.
    ///
    /// [`put`]: AtomicFile::put
    pub fn put_at(&mut self, offset: u64, bytes: &[u8]) -> Result<(), FileError> {
        #[cfg(unix)]
        let written = {
            use std::os::unix::fs::FileExt;
            // What `put` buffered goes first; then no seek and no copy into the buffer.
            self.writer().and_then(|w| {
                w.flush()?;
                w.get_ref().write_all_at(bytes, offset)
            })
        };
        #[cfg(not(unix))]
        let written = self
            .seek(SeekFrom::Start(offset))
            .and_then(|_| self.write_all(bytes));
        written.map_err(|e| FileError::new(&self.destination, e))
    }

    /// The file's size so far, in bytes.
    pub fn size(&mut self) -> Result<u64, FileError> {
        self.seek(SeekFrom::End(0))
            .map_err(|e| FileError::new(&self.destination, e))
    }

    fn writer(&mut self) -> io::Result<&mut BufWriter<File>> {
        self.writer
            .as_mut()
            .ok_or_else(|| io::Error::other("the file was committed"))
    }
}

impl Write for AtomicFile {
    fn write(&mut self, bytes: &[u8]) -> io::Result<usize> {
        self.writer()?.write(bytes)
    }

    fn write_all(&mut self, bytes: &[u8]) -> io::Result<()> {
        self.writer()?.write_all(bytes)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.writer()?.flush()
    }
}

impl Seek for AtomicFile {
    fn seek(&mut self, to: SeekFrom) -> io::Result<u64> {
        self.writer()?.seek(to)
    }
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        if self.writer.take().is_some() {
            // Not committed: the partial file must not stay behind.
            let _ = std::fs::remove_file(&self.temporary);
        }
    }
}

/// Writes `path` whole or not at all: `write` fills a temporary beside it, which replaces
/// `path` only if every byte reached the disk.
///
/// ```
/// use std::io::Write;
/// let path = std::env::temp_dir().join("sylva-write-doctest.txt");
/// sylva_base::file::write(&path, |w| w.write_all(b"axiom: F"))?;
/// assert_eq!(std::fs::read_to_string(&path).unwrap(), "axiom: F");
/// // A failed write leaves the file as it was.
/// let failed = sylva_base::file::write(&path, |_| Err(std::io::Error::other("stopped")));
/// assert!(failed.is_err());
/// assert_eq!(std::fs::read_to_string(&path).unwrap(), "axiom: F");
/// # std::fs::remove_file(&path).ok();
/// # Ok::<(), sylva_base::file::FileError>(())
/// ```
pub fn write(
    path: impl AsRef<Path>,
    write: impl FnOnce(&mut AtomicFile) -> io::Result<()>,
) -> Result<(), FileError> {
    let mut file = AtomicFile::create(path)?;
    let at = file.destination().to_path_buf();
    write(&mut file).map_err(|e| FileError::new(&at, e))?;
    file.commit()
}

/// The name a folder's previous contents have while [`replace_folder`] swaps a new set in;
/// found in place of the folder only if a replacement stopped between its two renames.
pub fn previous_folder(folder: &Path) -> PathBuf {
    let name = folder
        .file_name()
        .map_or_else(|| "folder".into(), |n| n.to_string_lossy().into_owned());
    folder.with_file_name(format!(".{name}.sylva-previous"))
}

/// Replaces the folder `folder` whole: `fill` writes the new set into an empty temporary
/// folder beside it, and only when every file is whole and on disk does the new folder take
/// the old one's place. A failure anywhere before leaves the old folder as it was.
///
/// The swap is two renames (the old folder aside to [`previous_folder`], the new one in);
/// should the process stop between them, the old set is whole at `previous_folder`, and the
/// next replacement clears it.
///
/// ```
/// use std::io::Write;
/// let dir = std::env::temp_dir().join(format!("sylva-set-doctest-{}", std::process::id()));
/// sylva_base::file::replace_folder(&dir, |new| {
///     std::fs::write(new.join("a.txt"), "1")?;
///     std::fs::write(new.join("b.txt"), "2")
/// })?;
/// let failed = sylva_base::file::replace_folder(&dir, |new| {
///     std::fs::write(new.join("a.txt"), "3")?;
///     Err(std::io::Error::other("the disk filled up"))
/// });
/// assert!(failed.is_err());
/// assert_eq!(std::fs::read_to_string(dir.join("a.txt")).unwrap(), "1");
/// # std::fs::remove_dir_all(&dir).ok();
/// # Ok::<(), sylva_base::file::FileError>(())
/// ```
pub fn replace_folder(
    folder: &Path,
    fill: impl FnOnce(&Path) -> io::Result<()>,
) -> Result<(), FileError> {
    let at = FileError::at(folder);
    let parent = parent_of(folder);
    std::fs::create_dir_all(parent).map_err(|e| FileError::new(parent, e))?;
    let staging = scratch_beside(folder, "sylva-new");
    std::fs::create_dir(&staging).map_err(&at)?;
    let filled = fill(&staging).and_then(|()| sync_files(&staging));
    if let Err(e) = filled {
        let _ = std::fs::remove_dir_all(&staging);
        return Err(at(e));
    }
    let previous = previous_folder(folder);
    if previous.exists() && folder.exists() {
        // A stale copy from a replacement that stopped after its swap.
        std::fs::remove_dir_all(&previous).map_err(FileError::at(&previous))?;
    }
    let had_old = folder.exists();
    if had_old {
        std::fs::rename(folder, &previous).map_err(&at)?;
    }
    if let Err(e) = std::fs::rename(&staging, folder) {
        if had_old {
            let _ = std::fs::rename(&previous, folder);
        }
        let _ = std::fs::remove_dir_all(&staging);
        return Err(at(e));
    }
    sync_folder(parent).map_err(&at)?;
    if previous.exists() {
        std::fs::remove_dir_all(&previous).map_err(FileError::at(&previous))?;
    }
    Ok(())
}

/// The first entry of `folder` whose name `ours` does not accept, if any (none when the
/// folder does not exist): a writer that replaces a folder's files checks with it that the
/// folder holds nobody else's.
///
/// ```
/// let dir = std::env::temp_dir().join(format!("sylva-foreign-doctest-{}", std::process::id()));
/// std::fs::create_dir_all(&dir).unwrap();
/// std::fs::write(dir.join("oak.png"), "").unwrap();
/// assert_eq!(sylva_base::file::foreign_entry(&dir, |n| n.ends_with(".png")), None);
/// std::fs::write(dir.join("notes.txt"), "").unwrap();
/// assert_eq!(sylva_base::file::foreign_entry(&dir, |n| n.ends_with(".png")).as_deref(), Some("notes.txt"));
/// # std::fs::remove_dir_all(&dir).ok();
/// ```
pub fn foreign_entry(folder: &Path, ours: impl Fn(&str) -> bool) -> Option<String> {
    std::fs::read_dir(folder)
        .ok()?
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .find(|name| !ours(name))
}

/// Flushes every file of a folder to disk.
fn sync_files(folder: &Path) -> io::Result<()> {
    for entry in std::fs::read_dir(folder)? {
        let entry = entry?;
        if entry.file_type()?.is_file() {
            File::open(entry.path())?.sync_all()?;
        }
    }
    sync_folder(folder)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("sylva-file-{name}"));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    /// Issue 60: run as root, `--out /dev/null` replaced `/dev/null` with a regular file.
    #[test]
    #[cfg(unix)]
    fn devices_fifos_and_folders_are_never_replaced() {
        let dir = scratch("special");
        for path in [Path::new("/dev/null"), dir.as_path()] {
            let err = AtomicFile::create(path).unwrap_err();
            assert!(
                err.to_string().contains("not a regular file")
                    || err.kind() == io::ErrorKind::IsADirectory,
                "{err}"
            );
        }
        let fifo = dir.join("pipe");
        if std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .is_ok_and(|s| s.success())
        {
            let err = AtomicFile::create(&fifo).unwrap_err();
            assert!(err.to_string().contains("FIFO"), "{err}");
            assert!(!std::fs::metadata(&fifo).unwrap().is_file());
        }
        // A link to a device is refused as the device is.
        let link = dir.join("null");
        std::os::unix::fs::symlink("/dev/null", &link).unwrap();
        assert!(AtomicFile::create(&link).is_err());
        // A link to nothing is refused, and says so.
        let dangling = dir.join("dangling");
        std::os::unix::fs::symlink(dir.join("nowhere"), &dangling).unwrap();
        let err = AtomicFile::create(&dangling).unwrap_err();
        assert!(err.to_string().contains("a link to nothing"), "{err}");
        std::fs::remove_dir_all(&dir).ok();
    }

    /// A link to a regular file is written through: the target changes, the link stays.
    #[test]
    #[cfg(unix)]
    fn a_link_to_a_file_is_written_through() {
        let dir = scratch("through");
        let target = dir.join("forest.glb");
        std::fs::write(&target, "old").unwrap();
        let link = dir.join("latest.glb");
        std::os::unix::fs::symlink(&target, &link).unwrap();
        write(&link, |w| w.write_all(b"new")).unwrap();
        assert!(
            std::fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink()
        );
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "new");
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn an_uncommitted_file_leaves_nothing_behind() {
        let dir = scratch("uncommitted");
        let path = dir.join("forest.glb");
        {
            let mut file = AtomicFile::create(&path).unwrap();
            file.write_all(b"half").unwrap();
        }
        assert!(!path.exists());
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
    }

    #[test]
    fn a_failed_rename_leaves_nothing_behind() {
        let dir = scratch("rename");
        let onto = dir.join("a-folder");
        std::fs::create_dir(&onto).unwrap();
        std::fs::write(onto.join("keep"), "x").unwrap();
        assert!(write(&onto, |w| w.write_all(b"glTF")).is_err());
        let names: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .flatten()
            .map(|e| e.file_name())
            .collect();
        assert_eq!(names, ["a-folder"]);
    }

    #[test]
    fn a_failed_write_keeps_the_old_file_and_names_it() {
        let dir = scratch("failed");
        let path = dir.join("tileset.json");
        std::fs::write(&path, "{}").unwrap();
        let err = write(&path, |w| {
            w.write_all(b"{\"asset\"")?;
            Err(io::Error::from(io::ErrorKind::StorageFull))
        })
        .unwrap_err();
        assert_eq!(err.path, path);
        assert!(err.to_string().contains("free some space"), "{err}");
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "{}");
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
    }

    #[test]
    fn a_folder_is_replaced_whole_and_stale_copies_are_cleared() {
        let dir = scratch("set");
        let masks = dir.join("masks");
        replace_folder(&masks, |new| std::fs::write(new.join("oak.png"), "1")).unwrap();
        // A replacement that stopped between its renames left the old set aside.
        std::fs::create_dir(previous_folder(&masks)).unwrap();
        replace_folder(&masks, |new| std::fs::write(new.join("birch.png"), "2")).unwrap();
        assert!(!masks.join("oak.png").exists());
        assert_eq!(
            std::fs::read_to_string(masks.join("birch.png")).unwrap(),
            "2"
        );
        let names: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .flatten()
            .map(|e| e.file_name())
            .collect();
        assert_eq!(names, ["masks"]);
    }

    #[test]
    fn errors_compare_by_path_and_kind() {
        let a = FileError::new("a", io::Error::from(io::ErrorKind::NotFound));
        let b = FileError::new("a", io::Error::new(io::ErrorKind::NotFound, "gone"));
        assert_eq!(a, b.clone());
        assert_ne!(
            a,
            FileError::new("b", io::Error::from(io::ErrorKind::NotFound))
        );
        assert!(a.to_string().starts_with("a: "));
    }
}
