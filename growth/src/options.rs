//! What a stand is told: the trees to grow, how each species answers light, the growth's
//! settings, and what it reports back.

use std::sync::Arc;

use glam::Vec3;
use sylva_lsys::LSystem;
use sylva_turtle::TurtleOptions;

use crate::light::SunPath;

/// How a species answers light.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Response {
    /// Weight of direct light against ambient light, 0 to 1: near 1 a pioneer that needs
    /// the sun, near 0 a shade-tolerant species content with the sky's light. Default: 0.5.
    pub direct_weight: f32,
    /// Combined light below which a branch stops growing. Default: 0.08.
    pub threshold: f32,
    /// Whether a branch that stops for want of light is shed (left out of the result).
    /// Default: false.
    pub shed: bool,
    /// Largest turn towards the light per segment, degrees. Default: 12.
    pub max_turn_degrees: f32,
    /// Shortest segment, as a fraction of its full length, that a barely lit branch grows.
    /// Default: 0.3.
    pub min_growth: f32,
}

impl Default for Response {
    fn default() -> Self {
        Response {
            direct_weight: 0.5,
            threshold: 0.08,
            shed: false,
            max_turn_degrees: 12.0,
            min_growth: 0.3,
        }
    }
}

impl Response {
    /// A pioneer: grows on direct light, stops early in shade.
    pub fn pioneer() -> Response {
        Response {
            direct_weight: 0.9,
            threshold: 0.25,
            ..Response::default()
        }
    }

    /// A shade-tolerant species: content with ambient light, grows on under a canopy.
    pub fn shade_tolerant() -> Response {
        Response {
            direct_weight: 0.1,
            threshold: 0.03,
            ..Response::default()
        }
    }
}

/// One tree to grow.
#[derive(Debug, Clone)]
pub struct TreeSpec {
    /// Where its trunk starts.
    pub base: Vec3,
    /// Its grammar.
    pub grammar: Arc<LSystem>,
    /// Generations to derive.
    pub generations: u32,
    /// Its own seed: every tree has its own derivation.
    pub seed: u64,
    /// Iteration at which it starts growing (the growth manager's stagger).
    pub start: u32,
    /// Turtle settings: symbols, angle, step, widths, tropism, leaf size.
    pub turtle: TurtleOptions,
    /// How it answers light.
    pub response: Response,
}

/// Settings of a stand's growth.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct GrowthOptions {
    /// Where the sun goes. Default: an arc of 9 positions tilted 30 degrees ([`SunPath::Arc`]).
    pub sun: SunPath,
    /// Sky rays per light sample. Default: 32.
    pub sky_rays: u32,
    /// Seed of the sky rays and of the order branches grow in. Default: 1.
    pub seed: u64,
    /// Alternative directions tried when a segment would collide. Default: 8.
    pub retries: u32,
    /// Half-angle of the cone the alternatives are drawn from, degrees. Default: 35.
    pub cone_degrees: f32,
    /// The environmental query symbol: a module with this symbol is filled with the light
    /// (combined, 0 to 1) and the free space (0 to 1) where a branch reaches it, and the
    /// grammar may test them in a production's condition (open L-systems). With queries in
    /// a grammar the stand is grown once per generation, as the environment answers. Default: `E`.
    pub query: Option<char>,
    /// Radius, metres, of the neighbourhood whose free voxels a query counts. Default: 0.5.
    pub query_radius: f32,
    /// Most growth iterations (a bound on runaway words). Default: 100,000.
    pub max_iterations: u32,
}

impl Default for GrowthOptions {
    fn default() -> Self {
        GrowthOptions {
            sun: SunPath::Arc {
                positions: 9,
                tilt_degrees: 30.0,
            },
            sky_rays: 32,
            seed: 1,
            retries: 8,
            cone_degrees: 35.0,
            query: Some('E'),
            query_radius: 0.5,
            max_iterations: 100_000,
        }
    }
}

impl GrowthOptions {
    /// Sets [`GrowthOptions::sun`].
    #[must_use]
    pub fn with_sun(mut self, sun: SunPath) -> Self {
        self.sun = sun;
        self
    }

    /// Sets [`GrowthOptions::sky_rays`].
    #[must_use]
    pub fn with_sky_rays(mut self, sky_rays: u32) -> Self {
        self.sky_rays = sky_rays;
        self
    }

    /// Sets [`GrowthOptions::seed`].
    #[must_use]
    pub fn with_seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }

    /// Sets [`GrowthOptions::retries`].
    #[must_use]
    pub fn with_retries(mut self, retries: u32) -> Self {
        self.retries = retries;
        self
    }

    /// Sets [`GrowthOptions::cone_degrees`].
    #[must_use]
    pub fn with_cone_degrees(mut self, cone_degrees: f32) -> Self {
        self.cone_degrees = cone_degrees;
        self
    }

    /// Sets [`GrowthOptions::query`].
    #[must_use]
    pub fn with_query(mut self, query: Option<char>) -> Self {
        self.query = query;
        self
    }

    /// Sets [`GrowthOptions::query_radius`].
    #[must_use]
    pub fn with_query_radius(mut self, query_radius: f32) -> Self {
        self.query_radius = query_radius;
        self
    }

    /// Sets [`GrowthOptions::max_iterations`].
    #[must_use]
    pub fn with_max_iterations(mut self, max_iterations: u32) -> Self {
        self.max_iterations = max_iterations;
        self
    }
}

/// What growing a stand cost and did.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct GrowthStats {
    /// Segments placed.
    pub segments: u64,
    /// Segments that had to turn to avoid a collision.
    pub deflected: u64,
    /// Branches aborted because no direction was free.
    pub aborted: u64,
    /// Branches stopped for want of light.
    pub stopped: u64,
    /// Light samples taken.
    pub samples: u64,
    /// Voxel steps of all light rays.
    pub ray_steps: u64,
    /// Growth iterations of the last round.
    pub iterations: u32,
    /// Rounds (derivation steps answered by the environment).
    pub rounds: u32,
}
