//! A specimen's world: one tree of the first species in the middle patch of a world just
//! large enough that its edge stays out of view (the turntable's, and the viewer's
//! `--turntable` world), and nothing else.

use std::sync::Arc;

use sylva::forest::{Composition, PatchDensity, Rect};
use sylva::terrain::glam::Vec2;

/// A composition that grows the first species in one square of the world and nothing
/// elsewhere: a specimen with no neighbours.
#[derive(Debug)]
pub(crate) struct Specimen {
    /// Where a tree may stand.
    pub(crate) plot: Rect,
}

impl Composition for Specimen {
    fn choose(&self, _density: &PatchDensity, p: Vec2, _draw: u64) -> Option<usize> {
        self.plot.contains(p).then_some(0)
    }

    fn species(&self) -> Option<usize> {
        None
    }
}

/// The least side of a turntable's world, metres: enough ground that its edge stays out of
/// the views.
const WORLD_SIDE: f32 = 80.0;

/// How many density patches of side `patch` a turntable's world is wide: an odd number, so
/// one patch is its middle, covering at least [`WORLD_SIDE`].
pub(crate) fn world_patches(patch: f32) -> u32 {
    let k = ((WORLD_SIDE / patch.max(1.0) - 1.0) * 0.5)
        .ceil()
        .clamp(1.0, 64.0) as u32;
    2 * k + 1
}

/// The square a specimen stands in: the middle patch of the world.
pub(crate) fn plot(patch: f32) -> Rect {
    let k = (world_patches(patch) / 2) as f32;
    Rect::new(Vec2::splat(k * patch), Vec2::splat((k + 1.0) * patch))
}

/// The composition of a turntable's world for patches of side `patch`.
pub(crate) fn specimen(patch: f32) -> Arc<dyn Composition> {
    Arc::new(Specimen { plot: plot(patch) })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The specimen's plot is the only place it grows.
    #[test]
    fn the_specimen_grows_only_in_its_plot() {
        let density = PatchDensity::new(Vec::new());
        let n = world_patches(10.0);
        assert!(n % 2 == 1 && n as f32 * 10.0 >= WORLD_SIDE, "{n}");
        let s = Specimen { plot: plot(10.0) };
        let middle = n as f32 * 10.0 * 0.5;
        assert_eq!(
            s.choose(&density, Vec2::new(middle, middle + 2.0), 7),
            Some(0)
        );
        assert_eq!(
            s.choose(&density, Vec2::new(middle - 10.0, middle), 7),
            None
        );
        assert_eq!(
            s.choose(&density, Vec2::new(middle, middle + 10.0), 7),
            None
        );
    }
}
