//! The editor's side of the window, once a frame: what the panel asked of the world and its
//! tools carried out, the forest built again after the species or its settings changed (in
//! the background, the walk going on meanwhile) and swapped in when whole, and the tools'
//! state shown back in the panel.

use std::sync::Arc;

use sylva::paint::BrushAction;

use super::App;
use crate::editor::{PaintAction, Request, ToolsState};
use crate::rebuild::Rebuild;
use crate::render::Renderer;

impl App {
    /// The editor's work for this frame (nothing without an editor).
    pub(super) fn tend_editor(&mut self) {
        let Some(window) = &mut self.editor else {
            return;
        };
        let requests = std::mem::take(&mut window.editor.requests);
        for request in requests {
            self.carry_out(request);
        }
        self.build_forest();
        self.show_tools();
    }

    /// Carries out one of the panel's requests.
    fn carry_out(&mut self, request: Request) {
        match request {
            Request::TogglePainting => self.toggle_painting(),
            Request::ToggleGuide => self.toggle_guide(),
            Request::UndoStroke | Request::RedoStroke => {
                if let Some(p) = &mut self.painting {
                    if request == Request::UndoStroke {
                        p.undo(&mut self.scene);
                    } else {
                        p.redo(&mut self.scene);
                    }
                }
                self.after_painting();
            }
            Request::SaveMasks => {
                let folder = self.masks_folder();
                if let (Some(p), Some(folder)) = (&mut self.painting, folder)
                    && let Err(e) = p.save_into(&folder)
                    && let Some(w) = &mut self.editor
                {
                    w.editor.status = format!("masks not saved: {e}");
                }
            }
            Request::PaintSpecies(_) | Request::PaintAction(_) | Request::Brush { .. } => {
                let Some(p) = &mut self.painting else { return };
                let (mut species, mut action, mut radius, mut strength) = p.brush();
                match request {
                    Request::PaintSpecies(k) => species = k,
                    Request::PaintAction(a) => {
                        action = match a {
                            PaintAction::Add => BrushAction::Add { species },
                            PaintAction::Turn => BrushAction::Species { species },
                            PaintAction::Erase => BrushAction::Erase,
                        }
                    }
                    Request::Brush {
                        radius: r,
                        strength: s,
                    } => (radius, strength) = (r, s),
                    _ => {}
                }
                p.set_brush(species, action, radius, strength);
            }
        }
    }

    /// The project's masks folder, with an editor.
    fn masks_folder(&self) -> Option<std::path::PathBuf> {
        let w = self.editor.as_ref()?;
        Some(w.editor.project.join(sylva::world::MASKS_FOLDER))
    }

    /// Starts a rebuild when the editor has a change and none is under way; swaps a
    /// finished one in, and starts the change that waited for it.
    fn build_forest(&mut self) {
        let Some(window) = &mut self.editor else {
            return;
        };
        if let Some(change) = window.editor.take_forest_change() {
            self.waiting_forest = Some(change);
        }
        if let Some(rebuild) = &self.rebuild {
            let Some(done) = rebuild.poll() else {
                window.editor.tools.forest =
                    format!("building the forest... {:.0} s", rebuild.seconds());
                return;
            };
            let frames = self.frames - rebuild.first_frame;
            self.rebuild = None;
            match done {
                Ok(rebuilt) => {
                    self.recipe = self.building.take();
                    let seconds = rebuilt.seconds;
                    let message = self.swap_in(rebuilt.scene, rebuilt.renderer);
                    self.rebuilds += 1;
                    let line = format!(
                        "forest built in {seconds:.1} s (build {}, {frames} frames drawn meanwhile){message}",
                        self.rebuilds
                    );
                    eprintln!("editor: {line}");
                    if let Some(w) = &mut self.editor {
                        w.editor.tools.forest = line;
                    }
                }
                Err(e) => {
                    self.building = None;
                    if let Some(w) = &mut self.editor {
                        w.editor.tools.forest = format!("the forest was not built: {e}");
                    }
                }
            }
        }
        if let Some((species, settings, recipe)) = self.waiting_forest.take() {
            let gpu = self
                .gpu
                .as_ref()
                .map(|g| (g.device.clone(), g.queue.clone(), g.config.format));
            let reuse = (self.recipe == Some(recipe)).then(|| Arc::clone(&self.scene.world));
            self.building = Some(recipe);
            self.rebuild = Some(Rebuild::start(
                &self.base,
                settings,
                species,
                (self.camera, self.frames),
                (gpu, reuse),
            ));
        }
    }

    /// Puts a new scene in the old one's place with its GPU side (made here unless the
    /// building thread made it), the camera kept inside it, the painting carried over when
    /// its masks fit, the guided walk stopped. Answers what the swap did, for the status
    /// line.
    fn swap_in(
        &mut self,
        mut scene: crate::scene::Scene,
        renderer: Option<Result<Renderer, String>>,
    ) -> String {
        let Some(gpu) = &mut self.gpu else {
            self.scene = scene;
            return String::new();
        };
        let started = std::time::Instant::now();
        let mut notes = Vec::new();
        if let Some(p) = &mut self.painting
            && let Err(e) = p.attach(&mut scene)
        {
            notes.push(format!("painting stopped: {e}"));
            self.painting = None;
            self.paint_mode = false;
        }
        let renderer = renderer.unwrap_or_else(|| {
            Renderer::new(&gpu.device, &gpu.queue, gpu.config.format, &scene)
                .map_err(|e| e.to_string())
        });
        match renderer {
            Ok(renderer) => gpu.renderer = renderer,
            Err(e) => return format!("; not shown: {e}"),
        }
        if self.guide.take().is_some() {
            notes.push("the guided walk stopped".into());
        }
        self.camera = self.camera.inside(scene.side());
        self.scene = scene;
        notes.insert(
            0,
            format!(
                "; swapped in {:.0} ms",
                started.elapsed().as_secs_f64() * 1e3
            ),
        );
        notes.join("; ")
    }

    /// Tells the panel the tools' state.
    fn show_tools(&mut self) {
        let Some(window) = &mut self.editor else {
            return;
        };
        let forest = std::mem::take(&mut window.editor.tools.forest);
        window.editor.tools = ToolsState {
            painting: self
                .painting
                .as_ref()
                .filter(|_| self.paint_mode)
                .map(crate::painting::Painting::status),
            brush: self.painting.as_ref().map(|p| {
                let (species, action, radius, strength) = p.brush();
                let action = match action {
                    BrushAction::Add { .. } => PaintAction::Add,
                    BrushAction::Species { .. } => PaintAction::Turn,
                    BrushAction::Erase => PaintAction::Erase,
                };
                (species, action, radius, strength)
            }),
            guide: self.guide.as_ref().map(crate::guide::Guide::summary),
            forest,
        };
    }
}
