//! The editor's panel (egui): undo, redo and save over three tabs. Species: the forest's
//! species, the selected one's grammar in an editor with its problems shown at their line
//! and column as the user types, its settings as sliders, a seed for the preview tree.
//! Forest and Tools: [`super::forest_tab`] and [`super::tools_tab`].

use egui::{Color32, RichText, ScrollArea, TextEdit, Ui};

use super::document::{set_setting, setting};
use super::{Editor, Tab};

/// Width of the panel, in points.
pub(crate) const WIDTH: f32 = 430.0;
/// Width of a slider's track, in points (egui's 100 is too short to set a value finely).
const SLIDER_WIDTH: f32 = 190.0;
/// Height of the text boxes (the grammar, the species file), in points.
const TEXT_HEIGHT: f32 = 300.0;

/// The species-file settings shown as sliders: key, range, step, and the value a species
/// file that does not give it has (the species reader's default).
const SLIDERS: &[(&str, f64, f64, f64, f64)] = &[
    ("generations", 1.0, 12.0, 1.0, 5.0),
    ("angle", 0.0, 90.0, 0.5, 22.5),
    ("step", 0.05, 5.0, 0.05, 1.0),
    ("leaf_facing", 0.0, 1.0, 0.05, 0.0),
    ("weight", 0.0, 10.0, 0.5, 1.0),
];

/// Draws the panel at the left of `ui` (the window's root) and applies what the user did
/// to `editor`.
pub(crate) fn show(ui: &mut Ui, editor: &mut Editor) {
    egui::Panel::left("species")
        .exact_size(WIDTH)
        .resizable(false)
        .show(ui, |ui| {
            ui.spacing_mut().slider_width = SLIDER_WIDTH;
            ui.horizontal(|ui| {
                for (tab, name) in [
                    (Tab::Species, "Species"),
                    (Tab::Forest, "Forest"),
                    (Tab::Tools, "Paint and walk"),
                ] {
                    if ui
                        .selectable_label(editor.tab == tab, RichText::new(name).heading())
                        .clicked()
                    {
                        editor.tab = tab;
                    }
                }
            });
            commands(ui, editor);
            restore_offer(ui, editor);
            match editor.tab {
                Tab::Species => {
                    species_tab(ui, editor);
                    preview_window(ui, editor);
                }
                Tab::Forest => super::forest_tab::show(ui, editor),
                Tab::Tools => super::tools_tab::show(ui, editor),
            }
        });
}

fn species_tab(ui: &mut Ui, editor: &mut Editor) {
    species_list(ui, editor);
    ui.separator();
    ScrollArea::vertical().show(ui, |ui| {
        grammar(ui, editor);
        ui.separator();
        settings(ui, editor);
        ui.separator();
        preview(ui, editor);
    });
}

fn restore_offer(ui: &mut Ui, editor: &mut Editor) {
    let Some(files) = &editor.restorable else {
        return;
    };
    let text = format!(
        "The last session ended without quitting; its autosave holds {} species.",
        files.len()
    );
    ui.label(RichText::new(text).color(Color32::YELLOW));
    ui.horizontal(|ui| {
        if ui.button("Restore").clicked() {
            editor.restore_autosave();
        }
        if ui.button("Discard").clicked() {
            editor.restorable = None;
        }
    });
}

fn species_list(ui: &mut Ui, editor: &mut Editor) {
    ui.horizontal_wrapped(|ui| {
        for k in 0..editor.documents.len() {
            let d = &editor.documents[k];
            let mark = if d.outcome.is_ok() { "" } else { " (!)" };
            if ui
                .selectable_label(editor.selected == k, format!("{}{mark}", d.name))
                .clicked()
            {
                editor.selected = k;
            }
        }
    });
}

fn grammar(ui: &mut Ui, editor: &mut Editor) {
    ui.label(format!("Grammar ({})", editor.current().grammar_file()));
    let mut text = editor.current().grammar_text.clone();
    if text_box(ui, "grammar", &mut text, 12).changed() {
        editor.edit(|d| d.grammar_text = text);
    }
    if let Err(problem) = &editor.current().outcome {
        ui.label(RichText::new(problem.to_string()).color(Color32::LIGHT_RED));
    }
}

/// A code editor of `rows` rows at least for `text`, scrolling in a box of its own so that
/// what stands below it stays in view.
pub(super) fn text_box(ui: &mut Ui, id: &str, text: &mut String, rows: usize) -> egui::Response {
    ScrollArea::vertical()
        .id_salt(format!("{id} scroll"))
        .max_height(TEXT_HEIGHT)
        .show(ui, |ui| {
            ui.add(
                TextEdit::multiline(text)
                    .id_salt(id)
                    .code_editor()
                    .desired_rows(rows)
                    .desired_width(f32::INFINITY),
            )
        })
        .inner
}

fn settings(ui: &mut Ui, editor: &mut Editor) {
    ui.label("Settings");
    for &(key, low, high, step, default) in SLIDERS {
        let text = &editor.current().species_text;
        let given = setting(text, key);
        let Some(mut value) = given
            .as_deref()
            .map_or(Some(default), |v| v.parse::<f64>().ok())
        else {
            // A setting given as something other than a number: shown as it stands.
            ui.label(format!("{key}: {}", given.unwrap_or_default()));
            continue;
        };
        // A canopy tree grows past its seedlings: generations start above them.
        let low = match key {
            "generations" => setting(text, "seedling_generations")
                .and_then(|s| s.parse::<f64>().ok())
                .map_or(low, |s| (s + 1.0).clamp(low, high)),
            _ => low,
        };
        let slider = egui::Slider::new(&mut value, low..=high)
            .step_by(step)
            .text(key);
        if ui.add(slider).changed() {
            let value = if step >= 1.0 {
                format!("{}", value.round())
            } else {
                format!("{value}")
            };
            editor.edit(|d| set_setting(&mut d.species_text, key, &value));
        }
    }
    ui.collapsing("Species file", |ui| {
        let mut text = editor.current().species_text.clone();
        if text_box(ui, "species", &mut text, 8).changed() {
            editor.edit(|d| d.species_text = text);
        }
    });
}

fn preview(ui: &mut Ui, editor: &mut Editor) {
    ui.horizontal(|ui| {
        let mut seed = editor.current().seed;
        ui.label("Seed");
        if ui.add(egui::DragValue::new(&mut seed)).changed() {
            editor.edit(|d| d.seed = seed);
        }
        if ui.button("Next seed").clicked() {
            editor.edit(|d| d.seed = d.seed.wrapping_add(1));
        }
    });
    let line = match &editor.current().outcome {
        Ok(p) => format!(
            "Preview: {} triangles, built in {:.0} ms",
            p.triangles, p.millis
        ),
        Err(_) => "Preview: none while the texts do not read".to_string(),
    };
    ui.label(line);
}

/// The preview tree in 3D, in a window of its own at the top right of the view beside the
/// panel (where it hides no control); dragging it turns the tree.
fn preview_window(ui: &mut Ui, editor: &mut Editor) {
    let Some(id) = editor.preview_image else {
        return;
    };
    let (w, h) = super::preview3d::SIZE;
    egui::Window::new(format!(
        "{} (seed {})",
        editor.current().name,
        editor.current().seed
    ))
    .id(egui::Id::unique("preview"))
    .anchor(egui::Align2::RIGHT_TOP, [-8.0, 8.0])
    .resizable(false)
    .collapsible(true)
    .show(ui.ctx(), |ui| {
        if editor.current().outcome.is_err() {
            ui.label("No tree while the texts do not read.");
            return;
        }
        let image = egui::Image::new(egui::load::SizedTexture::new(id, [w as f32, h as f32]))
            .sense(egui::Sense::drag());
        let response = ui.add(image).on_hover_text("drag to turn the tree");
        // Half a turn across the image.
        editor.preview_yaw += response.drag_delta().x * std::f32::consts::PI / w as f32;
    });
}

fn commands(ui: &mut Ui, editor: &mut Editor) {
    ui.horizontal(|ui| {
        if ui
            .add_enabled(editor.can_undo(), egui::Button::new("Undo"))
            .clicked()
        {
            editor.undo();
        }
        if ui
            .add_enabled(editor.can_redo(), egui::Button::new("Redo"))
            .clicked()
        {
            editor.redo();
        }
        if ui.button("Save").clicked() {
            editor.save();
        }
        // One line, truncated, so that the controls below never move.
        let status = if editor.unsaved && editor.status.is_empty() {
            "unsaved edits".to_string()
        } else if editor.unsaved {
            format!("unsaved edits; {}", editor.status)
        } else {
            editor.status.clone()
        };
        ui.add(egui::Label::new(status).truncate());
    });
}
