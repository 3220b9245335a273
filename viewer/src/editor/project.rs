//! The editor's project folder: species files and their grammars saved side by side with
//! the world file (`sylva::world::Project`), so that `sylva forest --project DIR` and the
//! server take them; an autosave
//! beside them, with marks that say a session is running and that the autosave holds edits
//! never saved, so that the next start (after a crash, or a quit without saving) offers the
//! autosave back.

use std::io::Write;
use std::path::{Path, PathBuf};

use sylva::world::Project;
use sylva::world::WorldDescription;

/// The autosave's folder inside a project.
const AUTOSAVE: &str = ".autosave";
/// The file that marks a session running; a clean quit removes it.
const RUNNING: &str = "running";
/// The file that marks the autosave as holding edits never saved; a save removes it.
const UNSAVED: &str = "unsaved";

/// Writes each (species name, species text, grammar file, grammar text) into `folder`, and
/// the world file of `world` (the elevation model `model` beside it), every file atomically
/// (a crash mid-save leaves the old file or the new, never half).
pub(crate) fn save(
    folder: &Path,
    documents: &[(String, String, String, String)],
    (world, model): (&WorldDescription, Option<&Path>),
) -> Result<(), String> {
    std::fs::create_dir_all(folder).map_err(|e| format!("{}: {e}", folder.display()))?;
    for (name, species, grammar_file, grammar) in documents {
        write(&folder.join(format!("{name}.species")), species)?;
        write(&folder.join(grammar_file), grammar)?;
    }
    Project::write(folder, world, model)
        .map(|_| ())
        .map_err(|e| e.to_string())
}

fn write(path: &Path, text: &str) -> Result<(), String> {
    sylva::base::file::write(path, |f| f.write_all(text.as_bytes())).map_err(|e| e.to_string())
}

/// The autosave folder of a project.
pub(crate) fn autosave_folder(project: &Path) -> PathBuf {
    project.join(AUTOSAVE)
}

/// Marks a session running in `project` (an autosave left by one that never quit is
/// offered back at the next start).
pub(crate) fn mark_running(project: &Path) -> Result<(), String> {
    let folder = autosave_folder(project);
    std::fs::create_dir_all(&folder).map_err(|e| format!("{}: {e}", folder.display()))?;
    write(&folder.join(RUNNING), &std::process::id().to_string())
}

/// Clears the running mark: the session ended as it should.
pub(crate) fn mark_quit(project: &Path) {
    let _ = std::fs::remove_file(autosave_folder(project).join(RUNNING));
}

/// Writes the autosave of `documents` and `world` and marks it as holding edits never saved.
pub(crate) fn autosave(
    project: &Path,
    documents: &[(String, String, String, String)],
    world: (&WorldDescription, Option<&Path>),
) -> Result<(), String> {
    let folder = autosave_folder(project);
    save(&folder, documents, world)?;
    write(&folder.join(UNSAVED), "")
}

/// Clears the unsaved mark: the project's own files hold every edit.
pub(crate) fn mark_saved(project: &Path) {
    let _ = std::fs::remove_file(autosave_folder(project).join(UNSAVED));
}

/// The species files of an autosave to offer back in `project`, if any: the last session
/// never quit (a crash) or quit with edits it never saved, and the autosave holds species.
pub(crate) fn offered_autosave(project: &Path) -> Option<Vec<PathBuf>> {
    let folder = autosave_folder(project);
    if !folder.join(UNSAVED).is_file() && !folder.join(RUNNING).is_file() {
        return None;
    }
    let mut species: Vec<PathBuf> = std::fs::read_dir(&folder)
        .ok()?
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|e| e == "species"))
        .collect();
    species.sort();
    (!species.is_empty()).then_some(species)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_autosave_is_offered_after_a_crash_or_unsaved_edits_only() {
        let project = std::env::temp_dir().join(format!("sylva-project-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&project);
        let docs = vec![(
            "bush".to_string(),
            "name: bush\ngrammar: bush.lsys\n".to_string(),
            "bush.lsys".to_string(),
            "axiom: F\n".to_string(),
        )];
        let world = WorldDescription::default();
        save(&project, &docs, (&world, None)).unwrap();
        assert!(project.join("bush.species").is_file() && project.join("bush.lsys").is_file());
        mark_running(&project).unwrap();
        autosave(&project, &docs, (&world, None)).unwrap();
        let offered = Some(vec![autosave_folder(&project).join("bush.species")]);
        // Still running (or killed): the autosave is there to restore.
        assert_eq!(offered_autosave(&project), offered);
        // Quit with edits never saved: still offered.
        mark_quit(&project);
        assert_eq!(offered_autosave(&project), offered);
        // Saved, and quit: nothing to offer.
        mark_saved(&project);
        assert_eq!(offered_autosave(&project), None);
        let _ = std::fs::remove_dir_all(&project);
    }
}
