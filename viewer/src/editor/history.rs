//! Undo and redo across the editor's edits: snapshots of one species' texts and seed, of
//! the forest's settings, or the mark of a paint stroke (which the painting tool undoes).

use std::time::{Duration, Instant};

use super::forest::ForestSettings;

/// Most snapshots kept each way.
const MAX_SNAPSHOTS: usize = 200;
/// Edits of one subject closer together than this undo together (a burst of typing, a
/// slider's drag).
const BURST: Duration = Duration::from_millis(800);

/// What an edit changed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Subject {
    /// The species of this document.
    Species(usize),
    /// The forest's settings.
    Forest,
    /// The painted masks.
    Paint,
}

/// A subject as it was.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Snapshot {
    /// One species' texts and preview seed.
    Species {
        document: usize,
        species_text: String,
        grammar_text: String,
        seed: u64,
    },
    /// The forest's settings.
    Forest(Box<ForestSettings>),
    /// A paint stroke: the painting tool keeps the strokes themselves.
    Stroke,
}

impl Snapshot {
    /// What it is a snapshot of.
    pub(crate) fn subject(&self) -> Subject {
        match self {
            Snapshot::Species { document, .. } => Subject::Species(*document),
            Snapshot::Forest(_) => Subject::Forest,
            Snapshot::Stroke => Subject::Paint,
        }
    }
}

/// The edits that can be undone and redone.
#[derive(Debug, Default)]
pub(crate) struct History {
    undo: Vec<Snapshot>,
    redo: Vec<Snapshot>,
    /// When the last snapshot was taken, and of what.
    last: Option<(Instant, Subject)>,
}

impl History {
    /// Records `before`, the state an edit is about to change; an edit soon after another of
    /// the same subject joins it (never a stroke: each is its own). A new edit clears what
    /// could be redone.
    pub(crate) fn record(&mut self, before: Snapshot, now: Instant) {
        self.redo.clear();
        let subject = before.subject();
        let joins = subject != Subject::Paint
            && self
                .last
                .is_some_and(|(at, s)| s == subject && now.duration_since(at) < BURST);
        self.last = Some((now, subject));
        if joins {
            return;
        }
        if self.undo.len() == MAX_SNAPSHOTS {
            self.undo.remove(0);
        }
        self.undo.push(before);
    }

    /// The state to go back to, given the current one of that subject (kept for redo).
    pub(crate) fn undo(&mut self, current: impl FnOnce(Subject) -> Snapshot) -> Option<Snapshot> {
        let back = self.undo.pop()?;
        self.redo.push(current(back.subject()));
        self.last = None;
        Some(back)
    }

    /// The state an undo left, given the current one of that subject (kept for undo).
    pub(crate) fn redo(&mut self, current: impl FnOnce(Subject) -> Snapshot) -> Option<Snapshot> {
        let forward = self.redo.pop()?;
        self.undo.push(current(forward.subject()));
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

#[cfg(test)]
mod tests {
    use super::*;

    fn species(document: usize, text: &str) -> Snapshot {
        Snapshot::Species {
            document,
            species_text: text.into(),
            grammar_text: String::new(),
            seed: 1,
        }
    }

    /// A burst of edits to one species undoes as one; a stroke between edits stands alone.
    #[test]
    fn bursts_join_and_strokes_stand_alone() {
        let mut h = History::default();
        let t = Instant::now();
        h.record(species(0, "a"), t);
        h.record(species(0, "ab"), t + Duration::from_millis(100));
        h.record(Snapshot::Stroke, t + Duration::from_millis(200));
        h.record(Snapshot::Stroke, t + Duration::from_millis(300));
        h.record(species(0, "abc"), t + Duration::from_millis(400));
        let current = |s: Subject| match s {
            Subject::Paint => Snapshot::Stroke,
            _ => species(0, "now"),
        };
        assert_eq!(h.undo(current), Some(species(0, "abc")));
        assert_eq!(h.undo(current), Some(Snapshot::Stroke));
        assert_eq!(h.undo(current), Some(Snapshot::Stroke));
        assert_eq!(h.undo(current), Some(species(0, "a")));
        assert!(!h.can_undo());
        assert_eq!(h.redo(current), Some(species(0, "now")));
        assert_eq!(h.redo(current), Some(Snapshot::Stroke));
    }
}
