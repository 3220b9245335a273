//! The painting tool (Carey report 4.8): a species as the brush, trees painted onto the terrain
//! under the cursor, the streamed cells under each stroke generated again at once.

use std::path::PathBuf;
use std::time::Instant;

use sylva::forest::Rect;
use sylva::paint::{Brush, BrushAction, Change, PaintCanvas, PaintLayer, save_masks};
use sylva::terrain::HeightField;
use sylva::terrain::glam::{Mat4, Vec2, Vec3, Vec4};

use crate::cells::VIEW_DISTANCE;
use crate::error::ViewerError;
#[cfg(test)]
use crate::scene::Camera;
use crate::scene::Scene;
#[cfg(test)]
use sylva::paint::mask_file_name;

/// Largest layer side in cells: a bigger world gets coarser cells.
const MAX_LAYER_CELLS: f32 = 2048.0;

/// The tool's state: the canvas, the brush, and what the last edit cost.
pub(crate) struct Painting {
    canvas: PaintCanvas,
    brush: Brush,
    /// The species the brush paints with (index and name).
    species: usize,
    names: Vec<String>,
    /// Where Ctrl+S saves the masks.
    save_to: PathBuf,
    /// Milliseconds of the last edit (layer, forest and cells), and a message for the title.
    pub(crate) last_ms: f64,
    pub(crate) message: String,
    changed: bool,
}

/// Where the ray through pixel `(x, y)` of a `width x height` view meets the terrain.
pub(crate) fn pick(
    scene: &Scene,
    view_proj: Mat4,
    eye: Vec3,
    (x, y): (f32, f32),
    (width, height): (f32, f32),
) -> Option<Vec3> {
    let ndc = Vec2::new(2.0 * x / width - 1.0, 1.0 - 2.0 * y / height);
    let inverse = view_proj.inverse();
    let far = inverse * Vec4::new(ndc.x, ndc.y, 1.0, 1.0);
    let near = inverse * Vec4::new(ndc.x, ndc.y, 0.0, 1.0);
    let direction = (far.truncate() / far.w - near.truncate() / near.w).normalize_or_zero();
    scene
        .world
        .heightmap
        .raycast(eye, direction, VIEW_DISTANCE * 1.2)
        .map(|hit| hit.point)
}

impl Painting {
    /// The tool over `scene`'s world: starting from the layer it was painted with, or from a
    /// layer that grows the generated forest everywhere (handed to the world at once, so
    /// every cell comes from the layer the strokes edit). Masks save to `save_to`.
    pub(crate) fn new(scene: &mut Scene, save_to: PathBuf) -> Result<Painting, ViewerError> {
        let (forest, _) = scene.world.forest();
        let (lo, hi) = scene.world.heightmap.bounds();
        let bounds = Rect::new(lo, hi);
        let painted = scene.world.layer();
        let layer = match &painted {
            Some(layer) => PaintLayer::clone(layer),
            None => {
                let cell = ((hi.x - lo.x).max(hi.y - lo.y) / MAX_LAYER_CELLS).max(1.0);
                let weights: Vec<f32> = forest.config().species.iter().map(|s| s.weight).collect();
                PaintLayer::filled(bounds, cell, &weights)?
            }
        };
        let canvas = PaintCanvas::for_forest(&forest, layer)?;
        if painted.is_none() {
            let version = scene.world.repaint(canvas.shared_layer())?;
            scene.cells.repaint(&scene.world, bounds, version)?;
        }
        let names = forest
            .config()
            .species
            .iter()
            .map(|s| s.name.clone())
            .collect();
        Ok(Painting {
            canvas,
            brush: Brush::new(BrushAction::Add { species: 0 }, 12.0),
            species: 0,
            names,
            save_to,
            last_ms: 0.0,
            message: String::new(),
            changed: false,
        })
    }

    /// The brush and the last edit, for the window's title.
    pub(crate) fn status(&self) -> String {
        let action = match self.brush.action {
            BrushAction::Add { .. } => format!("add {}", self.names[self.species]),
            BrushAction::Species { .. } => format!("turn to {}", self.names[self.species]),
            BrushAction::Erase => "erase".into(),
        };
        let (undo, redo) = self.canvas.history();
        format!(
            "painting: {action}, radius {:.0} m, strength {:.1}; {:.1} ms; undo {undo}, redo {redo}{}",
            self.brush.radius,
            self.brush.strength,
            self.last_ms,
            if self.message.is_empty() {
                String::new()
            } else {
                format!("; {}", self.message)
            }
        )
    }

    /// Picks the species (1 to 9: add it), the action (E erase, T turn trees into the
    /// species or back to adding), the radius (`[` `]`), the strength (`-` `=`); undo (Ctrl+Z), redo (Ctrl+Y or
    /// Ctrl+Shift+Z), save (Ctrl+S). Returns whether the key was the tool's.
    pub(crate) fn key(&mut self, scene: &mut Scene, key: &str, ctrl: bool, shift: bool) -> bool {
        self.message.clear();
        match (key, ctrl) {
            ("z", true) if shift => self.edit(scene, |c| c.redo()),
            ("z", true) => self.edit(scene, |c| c.undo()),
            ("y", true) => self.edit(scene, |c| c.redo()),
            ("s", true) => {
                let folder = self.save_to.clone();
                if let Err(e) = self.save_into(&folder) {
                    self.message = format!("not saved: {e}");
                }
            }
            (digit, false) if digit.len() == 1 && ("1"..="9").contains(&digit) => {
                let s = digit.parse::<usize>().unwrap_or(1) - 1;
                if s < self.names.len() {
                    self.species = s;
                    self.brush.action = match self.brush.action {
                        BrushAction::Species { .. } => BrushAction::Species { species: s },
                        _ => BrushAction::Add { species: s },
                    };
                } else {
                    self.message = format!("no species {digit}: {} loaded", self.names.len());
                }
            }
            ("e", false) => self.brush.action = BrushAction::Erase,
            ("t", false) => {
                self.brush.action = match self.brush.action {
                    BrushAction::Species { .. } => BrushAction::Add {
                        species: self.species,
                    },
                    _ => BrushAction::Species {
                        species: self.species,
                    },
                }
            }
            ("[", false) => self.brush.radius = (self.brush.radius / 1.25).max(1.0),
            ("]", false) => self.brush.radius = (self.brush.radius * 1.25).min(200.0),
            ("-", false) => self.brush.strength = (self.brush.strength - 0.1).max(0.1),
            ("=", false) => self.brush.strength = (self.brush.strength + 0.1).min(1.0),
            _ => return false,
        }
        true
    }

    /// The button went down over `point` (or over the sky: nothing happens).
    pub(crate) fn press(&mut self, scene: &mut Scene, point: Option<Vec3>) {
        self.message.clear();
        if let Err(e) = self.canvas.begin_stroke(self.brush) {
            self.message = e.to_string();
            return;
        }
        self.drag(scene, point);
    }

    /// The cursor moved to `point` with the button down.
    pub(crate) fn drag(&mut self, scene: &mut Scene, point: Option<Vec3>) {
        let Some(p) = point.filter(|_| self.canvas.stroking()) else {
            return;
        };
        let start = Instant::now();
        match self.canvas.stroke_to(Vec2::new(p.x, p.z)) {
            Ok(Some(change)) => self.show(scene, change, start),
            Ok(None) => {}
            Err(e) => self.message = e.to_string(),
        }
    }

    /// The button came up: the stroke can be undone. Whether it was kept (it changed
    /// something).
    pub(crate) fn release(&mut self) -> bool {
        self.canvas.end_stroke()
    }

    /// Undoes the last stroke.
    pub(crate) fn undo(&mut self, scene: &mut Scene) {
        self.edit(scene, PaintCanvas::undo);
    }

    /// Redoes the last undone stroke.
    pub(crate) fn redo(&mut self, scene: &mut Scene) {
        self.edit(scene, PaintCanvas::redo);
    }

    /// The brush: the species, its action, its radius and strength.
    pub(crate) fn brush(&self) -> (usize, BrushAction, f32, f32) {
        (
            self.species,
            self.brush.action,
            self.brush.radius,
            self.brush.strength,
        )
    }

    /// Sets the brush: species `species` (if there is one) with `action` (its species is
    /// `species`'s), radius and strength within the keys' ranges.
    pub(crate) fn set_brush(
        &mut self,
        species: usize,
        action: BrushAction,
        radius: f32,
        strength: f32,
    ) {
        if species < self.names.len() {
            self.species = species;
        }
        let s = self.species;
        self.brush.action = match action {
            BrushAction::Add { .. } => BrushAction::Add { species: s },
            BrushAction::Species { .. } => BrushAction::Species { species: s },
            BrushAction::Erase => BrushAction::Erase,
        };
        self.brush.radius = radius.clamp(1.0, 200.0);
        self.brush.strength = strength.clamp(0.1, 1.0);
    }

    /// Saves the masks into `folder`; the message says how it went.
    pub(crate) fn save_into(&mut self, folder: &std::path::Path) -> Result<(), String> {
        let names: Vec<&str> = self.names.iter().map(String::as_str).collect();
        save_masks(self.canvas.layer(), &names, folder).map_err(|e| e.to_string())?;
        self.message = format!("masks saved to {}", folder.display());
        Ok(())
    }

    /// Paints `scene` (a world built again) with the tool's layer, keeping its strokes for
    /// undo; an error when the new world's species or ground no longer fit the layer.
    pub(crate) fn attach(&mut self, scene: &mut Scene) -> Result<(), String> {
        let (forest, _) = scene.world.forest();
        let (lo, hi) = scene.world.heightmap.bounds();
        let layer = self.canvas.shared_layer();
        let names: Vec<String> = forest
            .config()
            .species
            .iter()
            .map(|s| s.name.clone())
            .collect();
        if names.len() != self.names.len() || layer.bounds() != Rect::new(lo, hi) {
            return Err("the painted masks do not fit the new species or ground".into());
        }
        let version = scene.world.repaint(layer).map_err(|e| e.to_string())?;
        scene
            .cells
            .repaint(&scene.world, Rect::new(lo, hi), version)
            .map_err(|e| e.to_string())?;
        self.names = names;
        Ok(())
    }

    fn edit(&mut self, scene: &mut Scene, edit: impl FnOnce(&mut PaintCanvas) -> Option<Change>) {
        let start = Instant::now();
        match edit(&mut self.canvas) {
            Some(change) => self.show(scene, change, start),
            None => self.message = "nothing to undo or redo".into(),
        }
    }

    /// Whether the last edit changed the forest (the walk's trunks must be generated again).
    pub(crate) fn take_changed(&mut self) -> bool {
        std::mem::take(&mut self.changed)
    }

    /// Hands the layer to the world and generates the cells under the change again.
    fn show(&mut self, scene: &mut Scene, change: Change, start: Instant) {
        // Trees change up to the density model's reach from the cells painted.
        let region = change
            .region
            .expanded(scene.world.forest().0.density().reach());
        let shown = scene
            .world
            .repaint(self.canvas.shared_layer())
            .and_then(|version| scene.cells.repaint(&scene.world, region, version));
        if let Err(e) = shown {
            self.message = e.to_string();
        }
        self.changed = true;
        self.last_ms = start.elapsed().as_secs_f64() * 1e3;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::world::{SceneOptions, default_species};

    fn scene() -> Scene {
        Scene::build(SceneOptions::small(2, 400.0)).expect("scene builds")
    }

    /// The ray through a pixel meets the terrain on that pixel's line of sight.
    #[test]
    fn the_cursor_picks_the_ground_it_shows() {
        let scene = scene();
        let camera = Camera::parse("120,150,30,-25,40").expect("camera");
        let size = (640.0, 360.0);
        let (view_proj, eye) = camera.view_proj(&scene, size.0 / size.1);
        // The centre pixel looks along the camera's forward direction.
        let hit = pick(&scene, view_proj, eye, (320.0, 180.0), size).expect("ground in view");
        let along = (hit - eye).normalize();
        assert!(
            along.dot(camera.forward()) > 0.9999,
            "{along} vs {}",
            camera.forward()
        );
        assert!((hit.y - scene.ground(hit.x, hit.z)).abs() < 1e-2);
        // Any pixel's hit projects back onto that pixel.
        for (x, y) in [(10.0, 300.0), (600.0, 250.0), (320.0, 350.0)] {
            let hit = pick(&scene, view_proj, eye, (x, y), size).expect("ground");
            let clip = view_proj * hit.extend(1.0);
            let ndc = clip.truncate() / clip.w;
            let pixel = ((ndc.x + 1.0) * 0.5 * size.0, (1.0 - ndc.y) * 0.5 * size.1);
            assert!(
                (pixel.0 - x).abs() < 0.2 && (pixel.1 - y).abs() < 0.2,
                "{pixel:?}"
            );
        }
        // The sky picks nothing.
        let up = Camera::parse("120,150,30,40").expect("camera");
        let (view_proj, eye) = up.view_proj(&scene, size.0 / size.1);
        assert_eq!(pick(&scene, view_proj, eye, (320.0, 10.0), size), None);
    }

    /// Erasing under the cursor clears the trees there from the streamed cells; undo brings
    /// them back; bad keys and strokes off the terrain leave a message and the forest as it
    /// was.
    #[test]
    fn strokes_show_in_the_cells_and_undo() {
        let mut scene = scene();
        let eye = Vec3::new(200.0, 10.0, 200.0);
        scene.stream(eye, false, true).expect("stream");
        let trees = |scene: &Scene| scene.cells.drawn().map(|(_, c)| c.trees).sum::<usize>();
        let before = trees(&scene);
        let dir = std::env::temp_dir().join(format!("sylva-viewer-paint-{}", std::process::id()));
        let mut painting = Painting::new(&mut scene, dir.clone()).expect("painting");
        assert_eq!(trees(&scene), before);
        assert!(painting.key(&mut scene, "e", false, false));
        assert!(painting.key(&mut scene, "]", false, false));
        painting.press(&mut scene, Some(Vec3::new(200.0, 0.0, 200.0)));
        painting.drag(&mut scene, Some(Vec3::new(240.0, 0.0, 210.0)));
        painting.release();
        assert!(painting.take_changed());
        let erased = trees(&scene);
        assert!(erased < before, "{erased} of {before}");
        assert!(painting.status().contains("erase"), "{}", painting.status());
        assert!(painting.key(&mut scene, "z", true, false));
        assert_eq!(trees(&scene), before);
        assert!(painting.key(&mut scene, "y", true, false));
        assert_eq!(trees(&scene), erased);
        assert!(painting.key(&mut scene, "9", false, false));
        assert!(
            painting.message.contains("no species 9"),
            "{}",
            painting.message
        );
        painting.press(&mut scene, Some(Vec3::new(5000.0, 0.0, 5000.0)));
        assert!(
            painting.message.contains("misses the terrain"),
            "{}",
            painting.message
        );
        painting.release();
        assert_eq!(trees(&scene), erased);
        assert!(painting.key(&mut scene, "s", true, false));
        assert!(
            dir.join(mask_file_name(&default_species().expect("species")[0].name))
                .exists()
        );
        let _ = std::fs::remove_dir_all(dir);
    }
}
