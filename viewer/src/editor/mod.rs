//! Carey's editing tool inside the viewer: the forest's species, each as its species file
//! and its grammar's text, checked and previewed as they change; the forest's terrain,
//! density and region; undo and redo across species edits, forest settings and paint
//! strokes; saved as a project folder that `sylva forest --project` and the server take;
//! autosaved and offered back after a crash; files changed in the user's own editor
//! reloaded. The panel that shows it is [`panel`]; the window carries out what it asks of
//! the world (a rebuild, a stroke undone) through [`Request`]s.

mod document;
pub(crate) mod forest;
mod forest_tab;
mod history;
pub(crate) mod in_window;
pub(crate) mod launch;
mod overlay;
mod panel;
mod preview3d;
mod project;
mod requests;
mod tools_tab;
mod watch;

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use document::Document;
use forest::ForestSettings;
use history::{History, Snapshot, Subject};
pub(crate) use requests::{PaintAction, Request, Tab, ToolsState};
use sylva::forest::Species;
use watch::Watch;

/// How often the project is autosaved while it has unsaved edits, unless told otherwise.
pub(crate) const AUTOSAVE_EVERY: Duration = Duration::from_secs(30);
/// How long the forest waits after the last edit before it is built again (a slider's drag
/// or a burst of typing is one rebuild).
const REBUILD_AFTER: Duration = Duration::from_millis(700);

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
    /// The world's settings (the forest tab).
    pub(crate) forest: ForestSettings,
    /// The tab shown.
    pub(crate) tab: Tab,
    /// When the species or the forest last changed, while the forest has not been built
    /// from the change.
    forest_changed: Option<Instant>,
    /// How long the edits must pause before the forest is built again ([`REBUILD_AFTER`]).
    pub(crate) rebuild_after: Duration,
    /// What the panel asked of the window, taken each frame.
    pub(crate) requests: Vec<Request>,
    /// What the window holds, for the tools tab.
    pub(crate) tools: ToolsState,
    /// Strokes painted since the last save (the masks are saved with the project).
    pub(crate) strokes_unsaved: bool,
    /// The elevation model's path as typed in the forest tab, and whether the tab shows
    /// the model's picker.
    pub(crate) model_input: String,
    pub(crate) choosing_model: bool,
    /// The 3D preview's image, once a window or the headless panel has registered it, and
    /// the angle it is seen from (radians round the tree; dragging the image turns it).
    pub(crate) preview_image: Option<egui::TextureId>,
    pub(crate) preview_yaw: f32,
}

impl Editor {
    /// An editor of species files on disk (`paths`); without them, of the species of the
    /// project's world file if it has one, else of the bundled species. The forest's
    /// settings are the project's, else `forest`. Saves go to `project`; files on disk are
    /// watched for changes.
    pub(crate) fn open(
        paths: &[PathBuf],
        project: PathBuf,
        forest: ForestSettings,
    ) -> Result<Editor, String> {
        let saved = ForestSettings::of_project(&project)?;
        let (forest, inline) = match saved {
            Some((settings, species)) => (settings, species),
            None => (forest, Vec::new()),
        };
        let documents = if paths.is_empty() && !inline.is_empty() {
            inline
                .iter()
                .map(|(file, grammar)| Document::inline(&project, file, grammar.as_deref()))
                .collect::<Result<Vec<_>, _>>()?
        } else if paths.is_empty() {
            sylva::presets::BUNDLED[..sylva::presets::DEFAULT_SPECIES]
                .iter()
                .map(|b| Document::open(Path::new(b.path), b.text, false))
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
            forest,
            tab: Tab::default(),
            forest_changed: None,
            rebuild_after: REBUILD_AFTER,
            requests: Vec::new(),
            tools: ToolsState::default(),
            strokes_unsaved: false,
            model_input: String::new(),
            choosing_model: false,
            preview_image: None,
            preview_yaw: 3.8,
        })
    }

    /// The document being edited.
    pub(crate) fn current(&self) -> &Document {
        &self.documents[self.selected]
    }

    fn snapshot(&self, subject: Subject) -> Snapshot {
        snapshot_of(&self.documents, &self.forest, subject)
    }

    /// Applies `change` to the selected document (undoably), then reads and previews it.
    /// A change of its texts builds the forest again once the edits pause.
    pub(crate) fn edit(&mut self, change: impl FnOnce(&mut Document)) {
        let before = self.snapshot(Subject::Species(self.selected));
        let document = &mut self.documents[self.selected];
        change(document);
        let Snapshot::Species {
            species_text,
            grammar_text,
            seed,
            ..
        } = &before
        else {
            return;
        };
        let texts =
            (species_text, grammar_text) != (&document.species_text, &document.grammar_text);
        if !texts && *seed == document.seed {
            return;
        }
        self.history.record(before, Instant::now());
        document.rebuild();
        self.changed(texts);
    }

    /// Applies `change` to the forest's settings (undoably); the forest is built again once
    /// the edits pause.
    pub(crate) fn edit_forest(&mut self, change: impl FnOnce(&mut ForestSettings)) {
        let before = self.forest.clone();
        change(&mut self.forest);
        if self.forest == before {
            return;
        }
        self.history
            .record(Snapshot::Forest(Box::new(before)), Instant::now());
        self.changed(true);
    }

    /// A stroke was painted: it undoes in turn with the edits, and the masks are unsaved.
    pub(crate) fn record_stroke(&mut self) {
        self.history.record(Snapshot::Stroke, Instant::now());
        self.strokes_unsaved = true;
        self.unsaved = true;
    }

    /// Marks unsaved edits; `forest`: the forest must be built again.
    fn changed(&mut self, forest: bool) {
        self.unsaved = true;
        self.since_autosave = true;
        if forest {
            self.forest_changed = Some(Instant::now());
        }
    }

    fn restore(&mut self, s: Snapshot) {
        match s {
            Snapshot::Species {
                document,
                species_text,
                grammar_text,
                seed,
            } => {
                self.selected = document;
                self.tab = Tab::Species;
                let d = &mut self.documents[document];
                d.species_text = species_text;
                d.grammar_text = grammar_text;
                d.seed = seed;
                d.rebuild();
                self.changed(true);
            }
            Snapshot::Forest(settings) => {
                self.forest = *settings;
                self.tab = Tab::Forest;
                self.changed(true);
            }
            // The stroke itself is the painting tool's: the window undoes or redoes it.
            Snapshot::Stroke => self.changed(false),
        }
    }

    /// Undoes the last edit (of whichever species, the forest, or a stroke), showing it.
    pub(crate) fn undo(&mut self) {
        let (documents, forest) = (&self.documents, &self.forest);
        let back = self.history.undo(|k| snapshot_of(documents, forest, k));
        if let Some(s) = back {
            if s == Snapshot::Stroke {
                self.requests.push(Request::UndoStroke);
            }
            self.restore(s);
        }
    }

    /// Redoes the last undone edit.
    pub(crate) fn redo(&mut self) {
        let (documents, forest) = (&self.documents, &self.forest);
        let forward = self.history.redo(|k| snapshot_of(documents, forest, k));
        if let Some(s) = forward {
            if s == Snapshot::Stroke {
                self.requests.push(Request::RedoStroke);
            }
            self.restore(s);
        }
    }

    /// What a world's forest (its hero trees, levels of detail and impostors) is made of: the
    /// species' texts, the seed and the budget. Worlds of equal recipes differ only in their
    /// ground and density, which a rebuild can change without building the forest again.
    pub(crate) fn recipe(&self) -> u64 {
        use std::hash::{Hash, Hasher};
        let mut h = std::collections::hash_map::DefaultHasher::new();
        for d in &self.documents {
            (&d.species_text, &d.grammar_text).hash(&mut h);
        }
        let w = &self.forest.description;
        (w.seed, w.budget_mb).hash(&mut h);
        h.finish()
    }

    /// The species and settings to build the forest from, with their [`Editor::recipe`],
    /// once the edits have paused since the last change and every species reads; the status
    /// says which does not.
    pub(crate) fn take_forest_change(&mut self) -> Option<(Vec<Species>, ForestSettings, u64)> {
        let changed = self.forest_changed?;
        if changed.elapsed() < self.rebuild_after {
            return None;
        }
        // The species as their previews read them: every one must read.
        let species: Result<Vec<Species>, &Document> = self
            .documents
            .iter()
            .map(|d| d.outcome.as_ref().map(|p| p.species.clone()).map_err(|_| d))
            .collect();
        match species {
            Ok(species) => {
                self.forest_changed = None;
                Some((species, self.forest.clone(), self.recipe()))
            }
            Err(d) => {
                self.tools.forest = format!("the forest waits for {} to read", d.name);
                None
            }
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

    /// The world's description with the species inline, as the project's world file holds
    /// it.
    pub(crate) fn description(&self) -> sylva::world::WorldDescription {
        let species = self
            .documents
            .iter()
            .map(|d| (d.species_text.clone(), d.grammar_text.clone()))
            .collect();
        self.forest.with_species(species)
    }

    /// Saves every species and grammar into the project folder, and the world file (the
    /// forest's settings, the species inline, the elevation model beside it); the window
    /// saves the painted masks.
    pub(crate) fn save(&mut self) {
        let world = self.description();
        let saved = project::save(
            &self.project,
            &self.files(),
            (&world, self.forest.model.as_deref()),
        );
        if self.strokes_unsaved {
            self.requests.push(Request::SaveMasks);
            self.strokes_unsaved = false;
        }
        match saved {
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
        let world = self.description();
        let saved = project::autosave(
            &self.project,
            &self.files(),
            (&world, self.forest.model.as_deref()),
        );
        if let Err(e) = saved {
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
        let folder = project::autosave_folder(&self.project);
        if let Ok(Some((settings, _))) = ForestSettings::of_project(&folder) {
            self.forest = settings;
        }
        self.unsaved = restored > 0;
        self.since_autosave = self.unsaved;
        self.forest_changed = Some(Instant::now());
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
                    let before = self.snapshot(Subject::Species(k));
                    self.history.record(before, Instant::now());
                    self.forest_changed = Some(Instant::now());
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

/// A subject as it stands, for the history (a free function: undo borrows the history and
/// the documents apart).
fn snapshot_of(documents: &[Document], forest: &ForestSettings, subject: Subject) -> Snapshot {
    match subject {
        Subject::Species(k) => {
            let d = &documents[k];
            Snapshot::Species {
                document: k,
                species_text: d.species_text.clone(),
                grammar_text: d.grammar_text.clone(),
                seed: d.seed,
            }
        }
        Subject::Forest => Snapshot::Forest(Box::new(forest.clone())),
        Subject::Paint => Snapshot::Stroke,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn settings() -> ForestSettings {
        ForestSettings::of_flags(1, 400.0, Some(32))
    }

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("sylva-editor-{name}"));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn edits_undo_and_redo_across_species() {
        let project = scratch("undo");
        let mut e = Editor::open(&[], project.clone(), settings()).unwrap();
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
        let mut e = Editor::open(&[], project.clone(), settings()).unwrap();
        e.edit(|d| document::set_setting(&mut d.species_text, "generations", "6"));
        let edited = e.current().outcome.as_ref().unwrap().triangles;
        e.save();
        assert!(!e.unsaved, "{}", e.status);
        // The project's species files are what sylva forest reads.
        let oak = Species::from_file(project.join("oak.species")).unwrap();
        assert_eq!(
            oak.mesh(oak.generations, 1).unwrap().triangle_count(),
            edited
        );
        let again =
            Editor::open(&[project.join("oak.species")], project.clone(), settings()).unwrap();
        assert_eq!(again.current().outcome.as_ref().unwrap().triangles, edited);
        let _ = std::fs::remove_dir_all(&project);
    }

    #[test]
    fn a_file_changed_on_disk_is_reloaded_with_its_error_shown() {
        let project = scratch("watch");
        let mut e = Editor::open(&[], project.clone(), settings()).unwrap();
        e.save();
        let file = project.join("oak.species");
        let mut watched =
            Editor::open(std::slice::from_ref(&file), project.clone(), settings()).unwrap();
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

    /// The forest's settings undo in turn with species edits; a change waits for the edits
    /// to pause, and for every species to read.
    #[test]
    fn forest_edits_undo_and_ask_for_a_rebuild() {
        let project = scratch("forest");
        let mut e = Editor::open(&[], project.clone(), settings()).unwrap();
        e.rebuild_after = Duration::from_secs(3600);
        e.edit_forest(|f| f.description.seed = 9);
        assert!(
            e.take_forest_change().is_none(),
            "the edits have not paused"
        );
        e.rebuild_after = Duration::ZERO;
        let (species, forest, recipe) = e.take_forest_change().unwrap();
        assert_eq!((species.len(), forest.description.seed), (5, 9));
        assert_eq!(recipe, e.recipe());
        assert!(e.take_forest_change().is_none(), "taken once");
        // A species that does not read holds the forest back, saying which.
        e.edit(|d| d.grammar_text.push_str("\nA -> B("));
        assert!(e.take_forest_change().is_none());
        assert!(e.tools.forest.contains("oak"), "{}", e.tools.forest);
        e.undo();
        assert!(e.take_forest_change().is_some());
        e.undo();
        assert_eq!(e.forest.description.seed, 1);
        assert_eq!(e.tab, Tab::Forest);
        e.redo();
        assert_eq!(e.forest.description.seed, 9);
        let _ = std::fs::remove_dir_all(&project);
    }

    /// The seed and the species make a forest's recipe; its ground and density do not.
    #[test]
    fn only_the_species_seed_and_budget_change_the_recipe() {
        let project = scratch("recipe");
        let mut e = Editor::open(&[], project.clone(), settings()).unwrap();
        let first = e.recipe();
        e.edit_forest(|f| {
            f.description.density = Some(90.0);
            f.description.area = 500.0;
        });
        assert_eq!(e.recipe(), first);
        e.edit_forest(|f| f.description.seed = 10);
        let seeded = e.recipe();
        assert_ne!(seeded, first);
        e.edit(|d| document::set_setting(&mut d.species_text, "generations", "6"));
        assert_ne!(e.recipe(), seeded);
        let _ = std::fs::remove_dir_all(&project);
    }

    /// A stroke undoes in turn with the edits: the window is asked to undo it.
    #[test]
    fn strokes_undo_through_the_window() {
        let project = scratch("strokes");
        let mut e = Editor::open(&[], project.clone(), settings()).unwrap();
        e.edit(|d| d.seed = 5);
        e.record_stroke();
        e.undo();
        assert_eq!(e.requests, [Request::UndoStroke]);
        e.undo();
        assert_eq!(e.current().seed, 1);
        e.redo();
        e.redo();
        assert_eq!(e.requests, [Request::UndoStroke, Request::RedoStroke]);
        // Saving asks for the masks too.
        e.save();
        assert_eq!(e.requests.last(), Some(&Request::SaveMasks));
        let _ = std::fs::remove_dir_all(&project);
    }

    /// A saved project holds the world file the server and `sylva forest --project` take;
    /// opened again, it is the same species and forest.
    #[test]
    fn a_saved_project_opens_as_it_was() {
        let project = scratch("reopen");
        let mut e = Editor::open(&[], project.clone(), settings()).unwrap();
        e.edit_forest(|f| {
            f.description.density = Some(300.0);
            f.description.area = 600.0;
        });
        e.edit(|d| document::set_setting(&mut d.species_text, "generations", "6"));
        e.save();
        let saved = sylva::world::Project::read(&project).unwrap();
        assert_eq!(saved.description, e.description());
        assert_eq!(saved.description.species.len(), 5);
        let again = Editor::open(&[], project.clone(), settings()).unwrap();
        assert_eq!(again.forest, e.forest);
        let texts = |e: &Editor| -> Vec<(String, String)> {
            e.documents
                .iter()
                .map(|d| (d.species_text.clone(), d.grammar_text.clone()))
                .collect()
        };
        assert_eq!(texts(&again), texts(&e));
        assert_eq!(
            again.documents[0].outcome.as_ref().unwrap().triangles,
            e.documents[0].outcome.as_ref().unwrap().triangles
        );
        let _ = std::fs::remove_dir_all(&project);
    }

    #[test]
    fn a_crashed_sessions_autosave_is_restored() {
        let project = scratch("crash");
        project::mark_running(&project).unwrap();
        let mut e = Editor::open(&[], project.clone(), settings()).unwrap();
        e.edit(|d| document::set_setting(&mut d.species_text, "generations", "5"));
        let edited = e.current().species_text.clone();
        e.autosave(true);
        // The session dies without quitting; the next one finds the autosave.
        drop(e);
        let mut next = Editor::open(&[], project.clone(), settings()).unwrap();
        assert!(next.restorable.is_some());
        next.restore_autosave();
        assert_eq!(next.current().species_text, edited, "{}", next.status);
        let _ = std::fs::remove_dir_all(&project);
    }
}
