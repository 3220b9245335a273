//! The CPU side of the viewer: the world, the cells of it streamed in around the camera, and
//! the camera.

use std::sync::Arc;

use sylva::terrain::glam::{Mat4, Vec3};
use sylva::terrain::{HeightField, TerrainVertex};

use sylva::forest::ForestError;

use crate::cells::{Cells, Streamed, VIEW_DISTANCE};
use crate::error::ViewerError;
use crate::world::{SceneOptions, World};

/// The world and the cells of it streamed in around the camera.
pub(crate) struct Scene {
    pub(crate) world: Arc<World>,
    pub(crate) terrain_vertices: Vec<TerrainVertex>,
    pub(crate) terrain_indices: Vec<u32>,
    pub(crate) cells: Cells,
}

impl Scene {
    /// The world with no cells streamed in yet.
    pub(crate) fn build(options: SceneOptions) -> Result<Scene, ViewerError> {
        Scene::of(World::build(options)?)
    }

    /// The scene of `world`, with no cells streamed in yet.
    pub(crate) fn of(world: World) -> Result<Scene, ViewerError> {
        let terrain = world.heightmap.mesh(1)?;
        Ok(Scene {
            world: Arc::new(world),
            terrain_vertices: terrain.vertices,
            terrain_indices: terrain.indices,
            cells: Cells::default(),
        })
    }

    /// The world's side in metres.
    pub(crate) fn side(&self) -> f32 {
        self.world.side
    }

    /// Brings the cells around `eye` in (see [`Cells::update`]).
    pub(crate) fn stream(
        &mut self,
        eye: Vec3,
        fine_everywhere: bool,
        wait: bool,
    ) -> Result<Streamed, ForestError> {
        self.cells.update(&self.world, eye, fine_everywhere, wait)
    }

    /// Ground height under (x, z).
    pub(crate) fn ground(&self, x: f32, z: f32) -> f32 {
        self.world.heightmap.height(x, z)
    }
}

/// The camera's vertical field of view.
pub(crate) const FIELD_OF_VIEW_DEGREES: f32 = 60.0;

/// A camera held `height` metres above the terrain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Camera {
    pub(crate) x: f32,
    pub(crate) z: f32,
    pub(crate) yaw: f32,
    pub(crate) pitch: f32,
    pub(crate) height: f32,
}

impl Camera {
    /// Parses `x,z,yaw_degrees,pitch_degrees[,height]`.
    pub(crate) fn parse(text: &str) -> Result<Camera, String> {
        let v: Vec<f32> = text
            .split(',')
            .map(|s| s.trim().parse::<f32>())
            .collect::<Result<_, _>>()
            .map_err(|e| format!("--camera '{text}': {e}"))?;
        if v.iter().any(|x| !x.is_finite()) {
            return Err(format!("--camera '{text}': numbers must be finite"));
        }
        match v.as_slice() {
            [x, z, yaw, pitch] => Ok(Camera {
                x: *x,
                z: *z,
                yaw: yaw.to_radians(),
                pitch: pitch.to_radians(),
                height: 1.7,
            }),
            [x, z, yaw, pitch, h] => Ok(Camera {
                x: *x,
                z: *z,
                yaw: yaw.to_radians(),
                pitch: pitch.to_radians(),
                height: *h,
            }),
            _ => Err(format!(
                "--camera '{text}': expected x,z,yaw,pitch[,height]"
            )),
        }
    }

    /// An overview from one corner of the map towards its centre, `height` above the ground.
    pub(crate) fn overview(side: f32, height: f32) -> Camera {
        let (x, z) = (side * 0.08, side * 0.08);
        let yaw = (side * 0.5 - z).atan2(side * 0.5 - x);
        Camera {
            x,
            z,
            yaw,
            pitch: -0.18,
            height,
        }
    }

    /// Walks `metres` along the heading, staying inside a world of side `side`.
    pub(crate) fn step(&mut self, metres: f32, side: f32) {
        let (s, c) = self.yaw.sin_cos();
        self.x = (self.x + c * metres).clamp(0.0, side);
        self.z = (self.z + s * metres).clamp(0.0, side);
    }

    /// The camera moved inside a world of side `side`, where it stands outside it.
    pub(crate) fn inside(self, side: f32) -> Camera {
        Camera {
            x: self.x.clamp(0.0, side),
            z: self.z.clamp(0.0, side),
            ..self
        }
    }

    pub(crate) fn forward(&self) -> Vec3 {
        Vec3::new(
            self.yaw.cos() * self.pitch.cos(),
            self.pitch.sin(),
            self.yaw.sin() * self.pitch.cos(),
        )
    }

    pub(crate) fn eye(&self, scene: &Scene) -> Vec3 {
        Vec3::new(self.x, scene.ground(self.x, self.z) + self.height, self.z)
    }

    pub(crate) fn view_proj(&self, scene: &Scene, aspect: f32) -> (Mat4, Vec3) {
        let eye = self.eye(scene);
        let view =
            sylva::terrain::glam::camera::rh::view::look_to_mat4(eye, self.forward(), Vec3::Y);
        // wgpu's clip space is Direct3D's: y up, depth from 0 to 1.
        let proj = sylva::terrain::glam::camera::rh::proj::directx::perspective(
            FIELD_OF_VIEW_DEGREES.to_radians(),
            aspect.max(1e-3),
            0.2,
            VIEW_DISTANCE * 1.2,
        );
        (proj * view, eye)
    }
}
