//! The voxel space as a derivation's environment: cpfg's communication module `?E` answered
//! with the light where it stands.

use sylva_lsys::{Environment, EnvironmentError, Word};
use sylva_turtle::glam::Vec3;
use sylva_turtle::{TurtleOptions, query_frames};

use crate::grid::VoxelGrid;
use crate::light::Sky;
use crate::options::Response;

/// Answers `?E(light, ambient, ...)` modules with the light at their place: the first
/// parameter gets the light as `response` combines direct sun and sky, the second the
/// ambient (sky) share alone. The plant stands at `base` in the grid's space; its modules are
/// placed by a turtle with `turtle`.
///
/// ```
/// use sylva_growth::{LightEnvironment, Response, Sky, SunPath, VoxelGrid};
/// use sylva_lsys::{Dialect, LSystem, Limits};
/// use sylva_turtle::{TurtleOptions, glam::Vec3};
///
/// // An apex that grows only in light, under a roof 2.5 units up.
/// let plant = LSystem::parse_dialect(
///     "Lsystem: 1\nAxiom: A ?E(1,1)\nA > ?E(l,a) : l > 0.5 --> F(1) A\nendlsystem",
///     Dialect::Cpfg,
/// )?;
/// let mut grid = VoxelGrid::new(Vec3::splat(-10.0), Vec3::splat(10.0), 0.5)?;
/// for x in -12..12 {
///     for z in -12..12 {
///         if let Some(cell) = grid.cell_of(Vec3::new(x as f32 * 0.5, 2.75, z as f32 * 0.5)) {
///             grid.occupy(cell);
///         }
///     }
/// }
/// let sky = Sky::new(SunPath::Arc { positions: 7, tilt_degrees: 0.0 }, 64, 1);
/// let mut light = LightEnvironment::new(grid, sky, Response::pioneer(), &TurtleOptions::default(), Vec3::ZERO);
/// let word = plant.derive_in(10, 0, &Limits::DEFAULT, &mut light)?;
/// // It stops below the roof.
/// assert!(word.iter().filter(|m| m.name == "F").count() <= 2);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone)]
pub struct LightEnvironment {
    grid: VoxelGrid,
    sky: Sky,
    response: Response,
    turtle: TurtleOptions,
    base: Vec3,
}

impl LightEnvironment {
    /// The environment of a plant at `base` among the obstacles of `grid`, lit by `sky`.
    pub fn new(
        grid: VoxelGrid,
        sky: Sky,
        response: Response,
        turtle: &TurtleOptions,
        base: Vec3,
    ) -> LightEnvironment {
        LightEnvironment {
            grid,
            sky,
            response,
            turtle: turtle.clone(),
            base,
        }
    }
}

impl Environment for LightEnvironment {
    fn respond(&mut self, word: &mut Word, _generation: u32) -> Result<(), EnvironmentError> {
        if !word.iter().any(|m| m.name == "?E") {
            return Ok(());
        }
        let frames = query_frames(word, &self.turtle, &["?E"])
            .map_err(|e| EnvironmentError::Interpretation(e.to_string()))?;
        for (index, frame) in frames {
            let light = self.sky.light_at(&self.grid, self.base + frame.position);
            let values = [
                f64::from(light.combined(self.response.direct_weight)),
                f64::from(light.ambient),
            ];
            for (p, v) in word.params_mut(index).iter_mut().zip(values) {
                *p = v;
            }
        }
        Ok(())
    }
}
