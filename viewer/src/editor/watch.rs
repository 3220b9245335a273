//! Hot reload: the folders of the species and grammar files being edited are watched, so a
//! file saved from the user's own editor is read again while the viewer runs.

use std::path::PathBuf;
use std::sync::mpsc::{Receiver, channel};
use std::time::Duration;

use notify_debouncer_mini::notify::{RecommendedWatcher, RecursiveMode};
use notify_debouncer_mini::{DebounceEventResult, Debouncer, new_debouncer};

/// How long after a file's last write it is reported: editors write a save in pieces.
const SETTLE: Duration = Duration::from_millis(150);

/// Watches folders and reports the files in them that changed.
pub(crate) struct Watch {
    /// Kept alive: dropping it stops the watching.
    _debouncer: Debouncer<RecommendedWatcher>,
    events: Receiver<DebounceEventResult>,
}

impl Watch {
    /// Watches each of `folders` (not their subfolders).
    pub(crate) fn new(folders: &[PathBuf]) -> Result<Watch, String> {
        let (send, events) = channel();
        let mut debouncer = new_debouncer(SETTLE, send).map_err(|e| e.to_string())?;
        for folder in folders {
            debouncer
                .watcher()
                .watch(folder, RecursiveMode::NonRecursive)
                .map_err(|e| format!("{}: {e}", folder.display()))?;
        }
        Ok(Watch {
            _debouncer: debouncer,
            events,
        })
    }

    /// The files that changed since the last call, without waiting.
    pub(crate) fn changed(&self) -> Vec<PathBuf> {
        let mut out: Vec<PathBuf> = self
            .events
            .try_iter()
            .filter_map(Result::ok)
            .flatten()
            .map(|e| e.path)
            .collect();
        out.sort();
        out.dedup();
        out
    }
}
