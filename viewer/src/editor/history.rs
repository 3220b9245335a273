//! Undo and redo across the editor's edits: snapshots of one document's texts and seed.

use std::time::{Duration, Instant};

/// Most snapshots kept each way.
const MAX_SNAPSHOTS: usize = 200;
/// Edits of one document closer together than this undo together (a burst of typing).
const BURST: Duration = Duration::from_millis(800);

/// One document as it was.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Snapshot {
    pub(crate) document: usize,
    pub(crate) species_text: String,
    pub(crate) grammar_text: String,
    pub(crate) seed: u64,
}

/// The edits that can be undone and redone.
#[derive(Debug, Default)]
pub(crate) struct History {
    undo: Vec<Snapshot>,
    redo: Vec<Snapshot>,
    /// When the last snapshot was taken, and of which document.
    last: Option<(Instant, usize)>,
}

impl History {
    /// Records `before`, the state an edit is about to change; an edit soon after another of
    /// the same document joins it. A new edit clears what could be redone.
    pub(crate) fn record(&mut self, before: Snapshot, now: Instant) {
        self.redo.clear();
        let joins = self
            .last
            .is_some_and(|(at, doc)| doc == before.document && now.duration_since(at) < BURST);
        self.last = Some((now, before.document));
        if joins {
            return;
        }
        if self.undo.len() == MAX_SNAPSHOTS {
            self.undo.remove(0);
        }
        self.undo.push(before);
    }

    /// The state to go back to, given the current one of that document (kept for redo).
    pub(crate) fn undo(&mut self, current: impl FnOnce(usize) -> Snapshot) -> Option<Snapshot> {
        let back = self.undo.pop()?;
        self.redo.push(current(back.document));
        self.last = None;
        Some(back)
    }

    /// The state an undo left, given the current one of that document (kept for undo).
    pub(crate) fn redo(&mut self, current: impl FnOnce(usize) -> Snapshot) -> Option<Snapshot> {
        let forward = self.redo.pop()?;
        self.undo.push(current(forward.document));
        self.last = None;
        Some(forward)
    }

    pub(crate) fn can_undo(&self) -> bool {
        !self.undo.is_empty()
    }

    pub(crate) fn can_redo(&self) -> bool {
        !self.redo.is_empty()
    }
}
