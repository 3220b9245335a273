//! Names of a process's scratch and partial files beside their destination, unique to the
//! process and the call, and the sweep of those left by processes that are gone.

use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};

/// Distinguishes the temporary files of one process.
static NEXT_TEMPORARY: AtomicU64 = AtomicU64::new(0);

/// A hidden name beside `path` for a temporary of this process: `.NAME.TAG-PID-N`, unique
/// to the process and the call, so that two runs writing one path never share a scratch
/// file; `TAG` should start with `sylva-` for [`sweep_abandoned`] to know it.
///
/// ```
/// let a = sylva_base::file::scratch_beside(std::path::Path::new("out/forest.glb"), "sylva-scratch");
/// let b = sylva_base::file::scratch_beside(std::path::Path::new("out/forest.glb"), "sylva-scratch");
/// assert_ne!(a, b);
/// assert!(a.to_string_lossy().starts_with("out/.forest.glb.sylva-scratch-"));
/// ```
pub fn scratch_beside(path: &Path, tag: &str) -> PathBuf {
    let name = path
        .file_name()
        .map_or_else(|| "output".into(), |n| n.to_string_lossy().into_owned());
    let n = NEXT_TEMPORARY.fetch_add(1, Ordering::Relaxed);
    path.with_file_name(format!(".{name}.{tag}-{}-{n}", std::process::id()))
}

/// Folders this process has swept already (a folder is swept once, not per file: a tileset
/// writes thousands of files into one).
static SWEPT: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Removes, once per folder and process, the scratch and partial files left in `folder` by
/// runs that are gone (killed, or out of power: their drop never ran): hidden files named
/// by [`scratch_beside`] with a `sylva-` tag whose process no longer exists. Files of live
/// processes are left alone. Only where processes can be asked after (Linux's `/proc`).
pub fn sweep_abandoned(folder: &Path) {
    let Ok(mut swept) = SWEPT.lock() else {
        return;
    };
    if swept.iter().any(|f| f == folder) {
        return;
    }
    swept.push(folder.to_path_buf());
    drop(swept);
    if !Path::new("/proc/self").exists() {
        return;
    }
    let Ok(entries) = std::fs::read_dir(folder) else {
        return;
    };
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(pid) = abandoned_pid(&name.to_string_lossy()) else {
            continue;
        };
        if pid != std::process::id() && !Path::new("/proc").join(pid.to_string()).exists() {
            let _ = std::fs::remove_file(entry.path());
        }
    }
}

/// The process a scratch file's name (`.NAME.sylva-TAG-PID-N`) says made it.
fn abandoned_pid(name: &str) -> Option<u32> {
    if !name.starts_with('.') {
        return None;
    }
    let (rest, n) = name.rsplit_once('-')?;
    let (tagged, pid) = rest.rsplit_once('-')?;
    let tag = tagged.rsplit_once('.')?.1;
    (tag.starts_with("sylva-") && n.parse::<u64>().is_ok())
        .then(|| pid.parse().ok())
        .flatten()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Issue 60: interrupted runs left `.NAME.sylva-partial-PID-N` files (150+ MB) that no
    /// later run swept. A run sweeps those of processes that are gone, and only those.
    #[test]
    #[cfg(target_os = "linux")]
    fn abandoned_scratch_files_are_swept_and_live_ones_kept() {
        let dir = std::env::temp_dir().join(format!("sylva-scratch-sweep-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        // No process has this id (above Linux's pid_max).
        let gone = dir.join(".forest.glb.sylva-partial-4194305-0");
        let live = dir.join(format!(
            ".forest.glb.sylva-scratch-trees-{}-7",
            std::process::id()
        ));
        let theirs = dir.join(".forest.glb.other-4194305-0");
        for f in [&gone, &live, &theirs] {
            std::fs::write(f, b"x").unwrap();
        }
        assert_eq!(
            abandoned_pid(".my-forest.v2.glb.sylva-partial-12-3"),
            Some(12)
        );
        assert_eq!(abandoned_pid("forest.glb"), None);
        sweep_abandoned(&dir);
        assert!(!gone.exists(), "an abandoned partial file stayed");
        assert!(live.exists() && theirs.exists());
        std::fs::remove_dir_all(&dir).ok();
    }
}
