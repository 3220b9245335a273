//! The forest tab (Carey's forest tab): the world's seed and side, its terrain (generated,
//! with its roughness, relief, smoothing and erosion, or the user's elevation model) and its
//! density. The forest is built again around the camera once the edits pause.

use egui::{Color32, RichText, Slider, Ui};
use sylva::world::TerrainDescription;
use sylva::world::limits::{MAX_EROSION, MAX_SIDE};

use super::Editor;

/// Shown densities, canopy trees per hectare.
const DENSITY: std::ops::RangeInclusive<f32> = 10.0..=1500.0;
/// The density a world starts from when it stops taking the species' own.
const FIRST_DENSITY: f32 = 150.0;

/// Draws the tab and applies what the user did to `editor`.
pub(super) fn show(ui: &mut Ui, editor: &mut Editor) {
    let mut d = editor.forest.description.clone();
    ui.horizontal(|ui| {
        ui.label("World seed");
        ui.add(egui::DragValue::new(&mut d.seed));
    });
    let generated = matches!(d.terrain, TerrainDescription::Generated { .. });
    ui.add_enabled(
        generated,
        Slider::new(&mut d.area, 100.0..=MAX_SIDE.min(4000.0))
            .logarithmic(true)
            .suffix(" m")
            .text("side"),
    );
    ui.separator();
    ui.label("Terrain");
    // Choosing a model stays chosen while its path is typed, before it is loaded.
    let mut use_model = !generated || editor.choosing_model;
    ui.horizontal(|ui| {
        ui.radio_value(&mut use_model, false, "generated");
        ui.radio_value(&mut use_model, true, "elevation model");
    });
    editor.choosing_model = use_model;
    if let TerrainDescription::Generated {
        seed,
        roughness,
        relief,
        smoothing,
        erosion,
    } = &mut d.terrain
    {
        ui.add(Slider::new(roughness, 0.0..=1.0).text("roughness"));
        ui.add(
            Slider::new(relief, 0.0..=0.3)
                .text("relief (share of the side)")
                .step_by(0.005),
        );
        ui.add(Slider::new(smoothing, 0.0..=16.0).text("smoothing (samples)"));
        ui.add(Slider::new(erosion, 0.0..=MAX_EROSION).text("erosion (droplets a sample)"));
        ui.horizontal(|ui| {
            let mut own = seed.is_some();
            ui.checkbox(&mut own, "terrain seed of its own");
            match (own, seed.as_mut()) {
                (true, Some(s)) => {
                    ui.add(egui::DragValue::new(s));
                }
                (true, None) => *seed = Some(1),
                (false, _) => *seed = None,
            }
        });
    }
    if use_model {
        model_picker(ui, editor, generated);
    } else if !generated {
        d.terrain = TerrainDescription::default();
    }
    ui.separator();
    ui.label("Density");
    let mut own = d.density.is_none();
    ui.checkbox(&mut own, "the species' own spacing");
    if own {
        d.density = None;
    } else {
        let mut density = d.density.unwrap_or(FIRST_DENSITY);
        ui.add(
            Slider::new(&mut density, DENSITY)
                .logarithmic(true)
                .text("canopy trees a hectare"),
        );
        d.density = Some(density);
    }
    if d != editor.forest.description {
        let model = (!matches!(d.terrain, TerrainDescription::Generated { .. }))
            .then(|| editor.forest.model.clone())
            .flatten();
        editor.edit_forest(|f| {
            f.description = d;
            f.model = model;
        });
    }
    ui.separator();
    let status = &editor.tools.forest;
    if !status.is_empty() {
        ui.label(status.as_str());
    }
}

/// The elevation model's path and its Load button; the model in use shown above them.
fn model_picker(ui: &mut Ui, editor: &mut Editor, generated: bool) {
    if let (false, Some(model)) = (generated, &editor.forest.model) {
        ui.label(format!("in use: {}", model.display()));
    }
    ui.horizontal(|ui| {
        ui.label("file");
        ui.text_edit_singleline(&mut editor.model_input);
        if ui.button("Load").clicked() {
            let path = std::path::PathBuf::from(editor.model_input.trim());
            let mut trial = editor.forest.clone();
            match trial.use_model(&path, None) {
                Ok(()) => editor.edit_forest(|f| *f = trial),
                Err(e) => editor.status = e,
            }
        }
    });
    if generated {
        ui.label(
            RichText::new("GeoTIFF, SRTM .hgt, ESRI ASCII grid or 16-bit PNG").color(Color32::GRAY),
        );
    }
}
