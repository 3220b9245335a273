//! The world built again in the background after the editor changed its species or its
//! forest settings: the new scene is made, with the cells around the camera streamed in,
//! on a thread of its own while the walk goes on in the old one; the window swaps it in
//! when it is whole.

use std::sync::Arc;
use std::sync::mpsc::{Receiver, TryRecvError, channel};
use std::time::Instant;

use sylva::forest::Species;

use crate::editor::forest::ForestSettings;
use crate::render::Renderer;
use crate::scene::{Camera, Scene};
use crate::world::{SceneOptions, World};

/// A world being built.
pub(crate) struct Rebuild {
    done: Receiver<Result<Built, String>>,
    started: Instant,
    /// The window's frame count when it started.
    pub(crate) first_frame: u64,
}

/// A finished rebuild: the new scene, with the cells around the camera in, its GPU side
/// when a device was given, and how long it took.
pub(crate) struct Rebuilt {
    pub(crate) scene: Scene,
    pub(crate) renderer: Option<Result<Renderer, String>>,
    pub(crate) seconds: f64,
}

/// A scene built, and its GPU side if one was asked for.
type Built = (Scene, Option<Result<Renderer, String>>);

/// The window's device, queue and surface format: the new scene's GPU side is made on the
/// building thread too, so the window only swaps it in.
pub(crate) type GpuHandles = (wgpu::Device, wgpu::Queue, wgpu::TextureFormat);

impl Rebuild {
    /// Starts building the world of `settings` and `species` over the viewer's `base`
    /// options, with the cells around `camera` (kept inside the new world) streamed in, and
    /// its GPU side on `gpu`; `frame` is the window's frame count now. With `reuse`, a world
    /// of the same species, seed and budget, only the ground and density are made anew (its
    /// forest kept) when it can carry them over.
    pub(crate) fn start(
        base: &SceneOptions,
        settings: ForestSettings,
        species: Vec<Species>,
        (camera, frame): (Camera, u64),
        (gpu, reuse): (Option<GpuHandles>, Option<Arc<World>>),
    ) -> Rebuild {
        let (send, done) = channel();
        let base = base.clone();
        std::thread::spawn(move || {
            let built = build(&base, &settings, species, camera, reuse).map(|scene| {
                let renderer = gpu.map(|(device, queue, format)| {
                    Renderer::new(&device, &queue, format, &scene).map_err(|e| e.to_string())
                });
                (scene, renderer)
            });
            // The window may have closed meanwhile: nobody to tell.
            let _ = send.send(built);
        });
        Rebuild {
            done,
            started: Instant::now(),
            first_frame: frame,
        }
    }

    /// The new world once it is whole; `None` while it is being built.
    pub(crate) fn poll(&self) -> Option<Result<Rebuilt, String>> {
        match self.done.try_recv() {
            Ok(built) => Some(built.map(|(scene, renderer)| Rebuilt {
                scene,
                renderer,
                seconds: self.started.elapsed().as_secs_f64(),
            })),
            Err(TryRecvError::Empty) => None,
            Err(TryRecvError::Disconnected) => Some(Err("the build stopped".into())),
        }
    }

    /// Seconds since it started.
    pub(crate) fn seconds(&self) -> f64 {
        self.started.elapsed().as_secs_f64()
    }
}

/// The scene of `settings` and `species`, with the cells around `camera` streamed in: on
/// `reuse`'s forest when it carries over to the new ground.
fn build(
    base: &SceneOptions,
    settings: &ForestSettings,
    species: Vec<Species>,
    camera: Camera,
    reuse: Option<Arc<World>>,
) -> Result<Scene, String> {
    let options = settings.scene_options(base, species)?;
    let carried = match (&reuse, &options.ground) {
        (Some(world), Some((map, _))) => world
            .on_ground(map.clone(), options.density)
            .map_err(|e| e.to_string())?,
        _ => None,
    };
    let mut scene = match carried {
        Some(world) => Scene::of(world),
        None => Scene::build(options),
    }
    .map_err(|e| e.to_string())?;
    let camera = camera.inside(scene.side());
    scene
        .stream(camera.eye(&scene), false, true)
        .map_err(|e| e.to_string())?;
    Ok(scene)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    /// Waits, a bounded while, for `rebuild` to finish.
    fn finished(rebuild: &Rebuild) -> Rebuilt {
        let until = Instant::now() + Duration::from_secs(300);
        loop {
            if let Some(done) = rebuild.poll() {
                return done.expect("the world builds");
            }
            assert!(Instant::now() < until, "the rebuild never finished");
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    /// The rebuilt world is the settings' (its side, its density), with the cells around
    /// the camera already in, the camera kept inside it.
    #[test]
    fn a_rebuild_is_the_settings_world_with_its_cells_in() {
        let base = SceneOptions::small(3, 300.0);
        let species = base.species.clone();
        let camera = Camera::parse("900,40,0,-10").expect("camera");
        let trees = |density: Option<f32>| {
            let mut settings = ForestSettings::of_flags(3, 250.0, Some(8));
            settings.description.density = density;
            let rebuilt = finished(&Rebuild::start(
                &base,
                settings,
                species.clone(),
                (camera, 0),
                (None, None),
            ));
            let scene = rebuilt.scene;
            assert!((scene.side() - 250.0).abs() < 1e-3, "{}", scene.side());
            let drawn: usize = scene.cells.drawn().map(|(_, c)| c.trees).sum();
            assert!(drawn > 0, "the cells around the camera are in");
            drawn
        };
        let sparse = trees(Some(40.0));
        let dense = trees(Some(400.0));
        assert!(
            dense > 3 * sparse,
            "{dense} trees at 400 a hectare, {sparse} at 40"
        );
    }

    /// A world carried over to new ground and density (its forest kept) is the world built
    /// whole from the same settings: the same cells, tree for tree and placement for
    /// placement.
    #[test]
    fn a_carried_over_forest_is_the_one_built_whole() {
        let base = SceneOptions::small(4, 300.0);
        let species = base.species.clone();
        let camera = Camera::parse("120,120,0,-10").expect("camera");
        let settings = |density: f32, roughness: f32| {
            let mut s = ForestSettings::of_flags(4, 250.0, Some(8));
            s.description.density = Some(density);
            if let sylva::world::TerrainDescription::Generated { roughness: r, .. } =
                &mut s.description.terrain
            {
                *r = roughness;
            }
            s
        };
        let build = |s: ForestSettings, reuse: Option<Arc<World>>| {
            finished(&Rebuild::start(
                &base,
                s,
                species.clone(),
                (camera, 0),
                (None, reuse),
            ))
            .scene
        };
        let first = build(settings(40.0, 0.75), None);
        let whole = build(settings(300.0, 0.4), None);
        let carried = build(settings(300.0, 0.4), Some(Arc::clone(&first.world)));
        assert_eq!(carried.world.heightmap, whole.world.heightmap);
        let cells = |scene: &Scene| -> Vec<(usize, Vec<[f32; 4]>)> {
            scene
                .cells
                .drawn()
                .map(|(_, c)| {
                    let firsts = (0..c.placements.len())
                        .filter_map(|k| c.placements.run(k).first())
                        .map(|p| p.translation_scale)
                        .collect();
                    (c.trees, firsts)
                })
                .collect()
        };
        assert!(!cells(&whole).is_empty());
        assert_eq!(cells(&carried), cells(&whole));
    }
}
