//! Carey's editing tool inside the viewer: the forest's species, each as its species file
//! and its grammar's text, checked and previewed as they change; undo and redo across
//! edits; saved as a project folder; autosaved and offered back after a crash; files changed
//! in the user's own editor reloaded. The panel that shows it is [`panel`].

mod document;
mod history;
pub(crate) mod in_window;
pub(crate) mod launch;
mod overlay;
mod panel;
mod project;
mod watch;

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use document::Document;
use history::{History, Snapshot};
use watch::Watch;

/// How often the project is autosaved while it has unsaved edits, unless told otherwise.
pub(crate) const AUTOSAVE_EVERY: Duration = Duration::from_secs(30);

/// The species being edited, and what the editor knows of them.
pub(crate) struct Editor {
    pub(crate) documents: Vec<Document>,
    pub(crate) selected: usize,
    history: History,
    /// The project folder saves go to.
    pub(crate) project: PathBuf,
    /// Edits since the last save.
    pub(crate) unsaved: bool,
    /// Edits since the last autosave.
    since_autosave: bool,
    last_autosave: Instant,
    /// How often edits are autosaved ([`AUTOSAVE_EVERY`] unless set).
    pub(crate) autosave_every: Duration,
    watch: Option<Watch>,
    /// What the editor last did or found ("saved", "reloaded oak.species", an error).
    pub(crate) status: String,
    /// A crashed session's autosave, offered until restored or dismissed.
    pub(crate) restorable: Option<Vec<PathBuf>>,
}

impl Editor {
    /// An editor of species files on disk (`paths`), or of the bundled species when there
    /// are none; saves go to `project`. Files on disk are watched for changes.
    pub(crate) fn open(paths: &[PathBuf], project: PathBuf) -> Result<Editor, String> {
        let documents = if paths.is_empty() {
            sylva::presets::SPECIES_FILES
                .iter()
                .map(|(path, text)| Document::open(Path::new(path), text, false))
                .collect::<Result<Vec<_>, _>>()?
        } else {
            paths
                .iter()
                .map(|p| {
                    let text = sylva::base::text_file::read(
                        p,
                        sylva::forest::limits::MAX_SPECIES_FILE_BYTES,
                    )
                    .map_err(|e| e.to_string())?;
                    Document::open(p, &text, true)
                })
                .collect::<Result<Vec<_>, _>>()?
        };
        let mut folders: Vec<PathBuf> = documents
            .iter()
            .flat_map(|d| [d.species_path.clone(), d.grammar_path.clone()])
            .flatten()
            .filter_map(|p| p.parent().map(Path::to_path_buf))
            .map(|p| {
                if p.as_os_str().is_empty() {
                    PathBuf::from(".")
                } else {
                    p
                }
            })
            .collect();
        folders.sort();
        folders.dedup();
        let (watch, status) = match Watch::new(&folders) {
            Ok(w) => (Some(w), String::new()),
            Err(e) => (None, format!("files are not watched: {e}")),
        };
        let restorable = project::offered_autosave(&project);
        Ok(Editor {
            documents,
            selected: 0,
            history: History::default(),
            project,
            unsaved: false,
            since_autosave: false,
            last_autosave: Instant::now(),
            autosave_every: AUTOSAVE_EVERY,
            watch: (!folders.is_empty()).then_some(watch).flatten(),
            status,
            restorable,
        })
    }

    /// The document being edited.
    pub(crate) fn current(&self) -> &Document {
        &self.documents[self.selected]
    }

    fn snapshot(&self, k: usize) -> Snapshot {
        snapshot_of(&self.documents, k)
    }

    /// Applies `change` to the selected document (undoably), then reads and previews it.
    pub(crate) fn edit(&mut self, change: impl FnOnce(&mut Document)) {
        let before = self.snapshot(self.selected);
        let document = &mut self.documents[self.selected];
        change(document);
        if (
            &document.species_text,
            &document.grammar_text,
            document.seed,
        ) == (&before.species_text, &before.grammar_text, before.seed)
        {
            return;
        }
        self.history.record(before, Instant::now());
        document.rebuild();
        self.unsaved = true;
        self.since_autosave = true;
    }

    fn restore(&mut self, s: Snapshot) {
        self.selected = s.document;
        let d = &mut self.documents[s.document];
        d.species_text = s.species_text;
        d.grammar_text = s.grammar_text;
        d.seed = s.seed;
        d.rebuild();
        self.unsaved = true;
        self.since_autosave = true;
    }

    /// Undoes the last edit (of whichever species), selecting that species.
    pub(crate) fn undo(&mut self) {
        let documents = &self.documents;
        let back = self.history.undo(|k| snapshot_of(documents, k));
        if let Some(s) = back {
            self.restore(s);
        }
    }

    /// Redoes the last undone edit.
    pub(crate) fn redo(&mut self) {
        let documents = &self.documents;
        let forward = self.history.redo(|k| snapshot_of(documents, k));
        if let Some(s) = forward {
            self.restore(s);
        }
    }

    pub(crate) fn can_undo(&self) -> bool {
        self.history.can_undo()
    }

    pub(crate) fn can_redo(&self) -> bool {
        self.history.can_redo()
    }

    fn files(&self) -> Vec<(String, String, String, String)> {
        self.documents
            .iter()
            .map(|d| {
                (
                    d.name.clone(),
                    d.species_text.clone(),
                    d.grammar_file(),
                    d.grammar_text.clone(),
                )
            })
            .collect()
    }

    /// Saves every species and grammar into the project folder.
    pub(crate) fn save(&mut self) {
        match project::save(&self.project, &self.files()) {
            Ok(()) => {
                self.unsaved = false;
                project::mark_saved(&self.project);
                self.status = format!("saved to {}", self.project.display());
            }
            Err(e) => self.status = format!("not saved: {e}"),
        }
    }

    /// Autosaves into the project's autosave folder when there are edits since the last
    /// autosave and the interval has passed (at once with `now`).
    pub(crate) fn autosave(&mut self, now: bool) {
        if !self.since_autosave || (!now && self.last_autosave.elapsed() < self.autosave_every) {
            return;
        }
        self.last_autosave = Instant::now();
        self.since_autosave = false;
        if let Err(e) = project::autosave(&self.project, &self.files()) {
            self.status = format!("autosave failed: {e}");
        }
    }

    /// Takes the crashed session's autosave in place of the documents of the same names.
    pub(crate) fn restore_autosave(&mut self) {
        let Some(files) = self.restorable.take() else {
            return;
        };
        let mut restored = 0;
        for file in files {
            let Ok(text) = std::fs::read_to_string(&file) else {
                continue;
            };
            let Ok(saved) = Document::open(&file, &text, true) else {
                continue;
            };
            if let Some(d) = self.documents.iter_mut().find(|d| d.name == saved.name) {
                d.species_text = saved.species_text;
                d.grammar_text = saved.grammar_text;
                d.rebuild();
                restored += 1;
            }
        }
        self.unsaved = restored > 0;
        self.since_autosave = self.unsaved;
        self.status = format!("restored {restored} species from the autosave");
    }

    /// Reads again every document whose species or grammar file changed on disk.
    pub(crate) fn reload_changed(&mut self) {
        let Some(watch) = &self.watch else {
            return;
        };
        let changed = watch.changed();
        if changed.is_empty() {
            return;
        }
        let same = |a: &Option<PathBuf>, b: &PathBuf| {
            a.as_ref()
                .is_some_and(|a| a.canonicalize().ok() == b.canonicalize().ok())
        };
        for k in 0..self.documents.len() {
            let d = &self.documents[k];
            if !changed
                .iter()
                .any(|c| same(&d.species_path, c) || same(&d.grammar_path, c))
            {
                continue;
            }
            let Some(path) = d.species_path.clone() else {
                continue;
            };
            let read = std::fs::read_to_string(&path)
                .map_err(|e| e.to_string())
                .and_then(|text| Document::open(&path, &text, true));
            match read {
                Ok(mut fresh) => {
                    let before = self.snapshot(k);
                    self.history.record(before, Instant::now());
                    fresh.seed = self.documents[k].seed;
                    fresh.rebuild();
                    self.status = match &fresh.outcome {
                        Ok(_) => format!("reloaded {}", path.display()),
                        Err(p) => format!("reloaded {}: {p}", path.display()),
                    };
                    self.documents[k] = fresh;
                }
                Err(e) => self.status = format!("not reloaded: {e}"),
            }
        }
    }
}

/// Document `k` as it stands, for the history (a free function: undo borrows the history
/// and the documents apart).
fn snapshot_of(documents: &[Document], k: usize) -> Snapshot {
    let d = &documents[k];
    Snapshot {
        document: k,
        species_text: d.species_text.clone(),
        grammar_text: d.grammar_text.clone(),
        seed: d.seed,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("sylva-editor-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn edits_undo_and_redo_across_species() {
        let project = scratch("undo");
        let mut e = Editor::open(&[], project.clone()).unwrap();
        let oak = e.current().outcome.as_ref().unwrap().triangles;
        e.edit(|d| document::set_setting(&mut d.species_text, "generations", "5"));
        let fewer = e.current().outcome.as_ref().unwrap().triangles;
        assert!(fewer < oak);
        e.selected = 1;
        e.edit(|d| d.seed = 9);
        e.undo();
        assert_eq!((e.selected, e.current().seed), (1, 1));
        e.undo();
        assert_eq!(e.selected, 0);
        assert_eq!(e.current().outcome.as_ref().unwrap().triangles, oak);
        e.redo();
        assert_eq!(e.current().outcome.as_ref().unwrap().triangles, fewer);
        assert!(e.can_redo());
        let _ = std::fs::remove_dir_all(&project);
    }

    #[test]
    fn a_saved_project_reads_back_as_the_same_trees() {
        let project = scratch("save");
        let mut e = Editor::open(&[], project.clone()).unwrap();
        e.edit(|d| document::set_setting(&mut d.species_text, "generations", "6"));
        let edited = e.current().outcome.as_ref().unwrap().triangles;
        e.save();
        assert!(!e.unsaved, "{}", e.status);
        // The project's species files are what sylva forest reads.
        let oak = sylva::forest::Species::from_file(project.join("oak.species")).unwrap();
        assert_eq!(
            oak.mesh(oak.generations, 1).unwrap().triangle_count(),
            edited
        );
        let again = Editor::open(&[project.join("oak.species")], project.clone()).unwrap();
        assert_eq!(again.current().outcome.as_ref().unwrap().triangles, edited);
        let _ = std::fs::remove_dir_all(&project);
    }

    #[test]
    fn a_file_changed_on_disk_is_reloaded_with_its_error_shown() {
        let project = scratch("watch");
        let mut e = Editor::open(&[], project.clone()).unwrap();
        e.save();
        let file = project.join("oak.species");
        let mut watched = Editor::open(std::slice::from_ref(&file), project.clone()).unwrap();
        let text = std::fs::read_to_string(&file)
            .unwrap()
            .replace("generations: 8", "generations: eight");
        std::fs::write(&file, text).unwrap();
        // The change arrives after the debounce: wait for it, a bounded while.
        let until = Instant::now() + Duration::from_secs(10);
        while watched.current().outcome.is_ok() && Instant::now() < until {
            std::thread::sleep(Duration::from_millis(50));
            watched.reload_changed();
        }
        let problem = watched.current().outcome.as_ref().unwrap_err();
        assert!(
            !problem.in_grammar && problem.at.map(|a| a.0).is_some(),
            "{problem}"
        );
        assert!(watched.status.starts_with("reloaded"), "{}", watched.status);
        let _ = std::fs::remove_dir_all(&project);
    }

    #[test]
    fn a_crashed_sessions_autosave_is_restored() {
        let project = scratch("crash");
        project::mark_running(&project).unwrap();
        let mut e = Editor::open(&[], project.clone()).unwrap();
        e.edit(|d| document::set_setting(&mut d.species_text, "generations", "5"));
        let edited = e.current().species_text.clone();
        e.autosave(true);
        // The session dies without quitting; the next one finds the autosave.
        drop(e);
        let mut next = Editor::open(&[], project.clone()).unwrap();
        assert!(next.restorable.is_some());
        next.restore_autosave();
        assert_eq!(next.current().species_text, edited, "{}", next.status);
        let _ = std::fs::remove_dir_all(&project);
    }
}
