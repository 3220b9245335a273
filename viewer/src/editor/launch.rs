//! Starting the editor from the command line: a session for the window, or the panel
//! rendered alone, headless.

use std::path::{Path, PathBuf};
use std::time::Duration;

use super::Editor;
use crate::error::ViewerError;

/// `--editor`: the editor of `species` (none: the bundled ones) saving to `project`,
/// autosaving every `autosave_every`, its session marked running so that a crash leaves its
/// autosave to restore.
pub(crate) fn session(
    species: &[PathBuf],
    project: &Path,
    autosave_every: Duration,
) -> Result<Editor, ViewerError> {
    let mut editor = Editor::open(species, project.to_path_buf()).map_err(ViewerError::Editor)?;
    editor.autosave_every = autosave_every;
    super::project::mark_running(project).map_err(ViewerError::Editor)?;
    Ok(editor)
}

/// `--editor-screenshot PATH`: the species panel alone, headless, at `size`; prints what
/// its preview says, and how long a preview takes.
pub(crate) fn screenshot(
    species: &[PathBuf],
    project: &Path,
    size: (u32, u32),
    path: &str,
) -> Result<(), ViewerError> {
    let mut editor = Editor::open(species, project.to_path_buf()).map_err(ViewerError::Editor)?;
    let pixels = super::overlay::render_panel(&mut editor, size)?;
    crate::write_png(path, size, &pixels)?;
    if let Some(files) = &editor.restorable {
        println!(
            "editor: the last session left an autosave of {} species to restore",
            files.len()
        );
    }
    // The preview's update time, as the panel sees it after an edit: every species at seeds
    // 1 to 11, the median of each.
    for k in 0..editor.documents.len() {
        let mut document = editor.documents[k].clone();
        let mut times: Vec<f64> = (1..=11)
            .filter_map(|seed| {
                document.seed = seed;
                document.rebuild();
                document.outcome.as_ref().ok().map(|p| p.millis)
            })
            .collect();
        if let Some(ms) = crate::median(&mut times) {
            println!(
                "editor: {} previews in {ms:.1} ms (median of {} seeds, {:.1} to {:.1})",
                document.name,
                times.len(),
                times[0],
                times[times.len() - 1]
            );
        }
    }
    let d = editor.current();
    match &d.outcome {
        Ok(p) => println!(
            "editor: {} species; {}: {} triangles, previewed in {:.0} ms; wrote {path}",
            editor.documents.len(),
            d.name,
            p.triangles,
            p.millis
        ),
        Err(problem) => println!("editor: {}: {problem}; wrote {path}", d.name),
    }
    Ok(())
}
