//! The guided walk through the viewer's world (Garden of Eden thesis 7.4): the camera led
//! from target to target around the trunks, for the window's walking mode and headless tours.

use std::sync::Arc;

use sylva::forest::{ForestTrunks, GuidedWalk, Rect, Trunks, WalkOptions};
use sylva::instancing::CompactTree;
use sylva::terrain::glam::Vec2;

use crate::scene::Camera;
use sylva::forest::ForestError;

use crate::world::World;

/// Trunk radii the walk keeps clear of (metres, times each tree's scale).
const CANOPY_TRUNK: f32 = 0.5;
const SEEDLING_TRUNK: f32 = 0.25;

/// Metres over which the camera's yaw catches up with the walker's heading.
const YAW_LAG: f32 = 2.0;

/// A walk under way and what it has done.
pub(crate) struct Guide {
    walk: GuidedWalk,
    trunks: ForestTrunks<'static>,
    /// The camera's yaw: the heading, smoothed.
    yaw: f32,
    options: WalkOptions,
    /// Metres walked, steps taken, steps that stood still, and the least gap kept to a trunk's
    /// clearance.
    pub(crate) walked: f32,
    pub(crate) steps: u64,
    pub(crate) stood: u64,
    pub(crate) least_gap: f32,
    near: Vec<(Vec2, f32)>,
}

impl Guide {
    /// A walk from `start` over the world, its targets drawn from `seed`.
    pub(crate) fn new(world: &Arc<World>, start: Vec2, seed: u64) -> Result<Guide, ForestError> {
        let trees_of = Arc::clone(world);
        let sizes_of = Arc::clone(world);
        let mut trunks = ForestTrunks::new(
            move |rect| trees_of.forest().0.trees(&trees_of.heightmap, rect),
            move |t: &CompactTree| {
                let young = sizes_of
                    .seedling
                    .get(usize::from(t.variant))
                    .copied()
                    .unwrap_or(false);
                t.scale * if young { SEEDLING_TRUNK } else { CANOPY_TRUNK }
            },
        );
        let options = WalkOptions::default();
        let bounds = Rect::new(Vec2::ZERO, Vec2::splat(world.side));
        let walk = GuidedWalk::new(bounds, &mut trunks, start, seed, options)?;
        let heading = walk.heading();
        Ok(Guide {
            walk,
            trunks,
            yaw: heading.y.atan2(heading.x),
            options,
            walked: 0.0,
            steps: 0,
            stood: 0,
            least_gap: f32::INFINITY,
            near: Vec::new(),
        })
    }

    /// Walks about `metres` on; `steer` (-1 to 1) bends the way a little.
    pub(crate) fn advance(&mut self, metres: f32, steer: f32) {
        let steps = (metres.max(0.0) / self.options.step).round() as u64;
        for _ in 0..steps {
            let step = self.walk.step(&mut self.trunks, steer);
            self.steps += 1;
            if step.moved {
                self.walked += self.options.step;
            } else {
                self.stood += 1;
            }
            self.near.clear();
            self.trunks.near(step.position, 2.0, &mut self.near);
            for (t, r) in &self.near {
                let gap = step.position.distance(*t) - r - self.options.body;
                self.least_gap = self.least_gap.min(gap);
            }
            let turn = Vec2::from_angle(self.yaw).angle_to(step.heading);
            self.yaw += turn * (1.0 - (-self.options.step / YAW_LAG).exp());
        }
    }

    /// The trees changed (the painting tool painted): trunks are generated again as needed.
    pub(crate) fn forget_trunks(&mut self) {
        self.trunks.forget();
    }

    /// The camera at the walker, at eye height, looking along its way turned by `look`
    /// radians, pitched by `pitch`.
    pub(crate) fn camera(&self, look: f32, pitch: f32) -> Camera {
        let p = self.walk.position();
        Camera {
            x: p.x,
            z: p.y,
            yaw: self.yaw + look,
            pitch,
            height: 1.7,
        }
    }

    /// One line on the walk so far.
    pub(crate) fn summary(&self) -> String {
        format!(
            "walked {:.0} m in {} steps ({} stood still), {} of {} targets reached, closest {:.2} m from a trunk's clearance",
            self.walked,
            self.steps,
            self.stood,
            self.walk.arrivals(),
            self.walk.targets(),
            self.least_gap
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;
    use crate::world::SceneOptions;

    /// A guided walk through a real streamed world keeps clear of every trunk, keeps moving and
    /// keeps the camera at eye height on the terrain.
    #[test]
    fn the_guide_leads_the_camera_around_the_trunks() {
        let scene = Scene::build(SceneOptions::small(6, 300.0)).expect("scene builds");
        let mut guide = Guide::new(&scene.world, Vec2::splat(150.0), 3).expect("guide");
        for _ in 0..40 {
            guide.advance(5.0, 0.0);
        }
        assert!(guide.least_gap >= -1e-4, "{}", guide.summary());
        assert!(
            guide.walked > 190.0 && guide.stood < 10,
            "{}",
            guide.summary()
        );
        let camera = guide.camera(0.3, -0.1);
        assert!((0.0..=300.0).contains(&camera.x) && (0.0..=300.0).contains(&camera.z));
        assert_eq!((camera.height, camera.pitch), (1.7, -0.1));
    }
}
