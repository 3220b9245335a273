//! The painting tool and the guided walk as a tab: the brush's species, action, radius and
//! strength; saving the masks into the project; the walk started and stopped, and how it
//! went. The window holds both tools: the tab asks it through [`Request`]s and shows what it
//! tells back.

use egui::{Slider, Ui};

use super::{Editor, PaintAction, Request};

/// Draws the tab and asks the window for what the user did.
pub(super) fn show(ui: &mut Ui, editor: &mut Editor) {
    ui.label("Painting");
    let painting = editor.tools.painting.is_some();
    if ui
        .button(if painting {
            "Stop painting (P)"
        } else {
            "Start painting (P)"
        })
        .clicked()
    {
        editor.requests.push(Request::TogglePainting);
    }
    if let Some((species, action, radius, strength)) = editor.tools.brush {
        let names: Vec<String> = editor.documents.iter().map(|d| d.name.clone()).collect();
        let mut chosen = species;
        egui::ComboBox::from_label("species")
            .selected_text(names.get(species).cloned().unwrap_or_default())
            .show_ui(ui, |ui| {
                for (k, name) in names.iter().enumerate() {
                    ui.selectable_value(&mut chosen, k, name);
                }
            });
        if chosen != species {
            editor.requests.push(Request::PaintSpecies(chosen));
        }
        let mut act = action;
        ui.horizontal(|ui| {
            ui.radio_value(&mut act, PaintAction::Add, "add");
            ui.radio_value(&mut act, PaintAction::Turn, "turn trees into it");
            ui.radio_value(&mut act, PaintAction::Erase, "erase");
        });
        if act != action {
            editor.requests.push(Request::PaintAction(act));
        }
        let (mut r, mut s) = (radius, strength);
        ui.add(
            Slider::new(&mut r, 1.0..=200.0)
                .logarithmic(true)
                .suffix(" m")
                .text("radius"),
        );
        ui.add(Slider::new(&mut s, 0.1..=1.0).text("strength"));
        if (r, s) != (radius, strength) {
            editor.requests.push(Request::Brush {
                radius: r,
                strength: s,
            });
        }
        if ui.button("Save masks").clicked() {
            editor.requests.push(Request::SaveMasks);
        }
        ui.label("The left button paints, the right one looks; Ctrl+Z and Ctrl+Y undo and redo strokes and edits in turn. Save keeps the masks with the project.");
    }
    if let Some(status) = &editor.tools.painting {
        ui.add(egui::Label::new(status.as_str()).wrap());
    }
    ui.separator();
    ui.label("Guided walk");
    let walking = editor.tools.guide.is_some();
    if ui
        .button(if walking {
            "Stop the walk (G)"
        } else {
            "Walk guided (G)"
        })
        .clicked()
    {
        editor.requests.push(Request::ToggleGuide);
    }
    if let Some(summary) = &editor.tools.guide {
        ui.add(egui::Label::new(summary.as_str()).wrap());
        ui.label("The mouse looks around; A and D lean; Shift hurries.");
    }
}
