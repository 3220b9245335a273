//! Starting the editor from the command line: a session for the window, or the panel
//! rendered alone, headless.

use std::path::{Path, PathBuf};
use std::time::Duration;

use super::Editor;
use super::forest::ForestSettings;
use crate::error::ViewerError;
use crate::world::SceneOptions;

/// `--editor`: the editor of `species` (none: the project's, else the bundled ones) saving
/// to `project`, autosaving every `autosave_every`, its session marked running so that a
/// crash leaves its autosave to restore; and the world's options made from its species and
/// forest settings (the project's, else those of the viewer's flags in `scene`).
pub(crate) fn session(
    species: &[PathBuf],
    project: &Path,
    autosave_every: Duration,
    scene: &SceneOptions,
) -> Result<(Editor, SceneOptions), ViewerError> {
    let mut editor = Editor::open(species, project.to_path_buf(), flags_forest(scene)?)
        .map_err(ViewerError::Editor)?;
    editor.autosave_every = autosave_every;
    super::project::mark_running(project).map_err(ViewerError::Editor)?;
    let species = editor
        .documents
        .iter()
        .map(|d| {
            d.outcome
                .as_ref()
                .map(|p| p.species.clone())
                .map_err(|p| format!("{}: {p}", d.name))
        })
        .collect::<Result<Vec<_>, _>>()
        .map_err(ViewerError::Editor)?;
    let options = editor
        .forest
        .scene_options(scene, species)
        .map_err(ViewerError::Editor)?;
    Ok((editor, options))
}

/// The forest settings of the viewer's flags: its seed, side and budget, and its elevation
/// model (which a project keeps whole: a cropped one cannot be kept).
fn flags_forest(scene: &SceneOptions) -> Result<ForestSettings, ViewerError> {
    let mut settings =
        ForestSettings::of_flags(scene.seed, scene.side, scene.budget.map(|b| b >> 20));
    if let Some(file) = &scene.terrain {
        if file.crop.is_some() {
            return Err(ViewerError::Usage(
                "--editor keeps the whole elevation model in its project: crop the file itself rather than give --crop".into(),
            ));
        }
        settings
            .use_model(&file.path, file.spacing)
            .map_err(ViewerError::Editor)?;
    }
    Ok(settings)
}

/// `--editor-screenshot PATH`: the panel alone, headless, at `size`, showing `tab`; prints
/// what its preview says, and how long a preview takes.
pub(crate) fn screenshot(
    species: &[PathBuf],
    project: &Path,
    scene: &SceneOptions,
    (tab, size): (super::Tab, (u32, u32)),
    path: &str,
) -> Result<(), ViewerError> {
    let mut editor = Editor::open(species, project.to_path_buf(), flags_forest(scene)?)
        .map_err(ViewerError::Editor)?;
    editor.tab = tab;
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
