//! `--tour N`: frames rendered headless along the guided walk.

use std::time::Instant;

use crate::error::ViewerError;
use crate::scene::{Camera, Scene};
use crate::{guide, median, numbered, offscreen, render, write_png};

/// A headless tour: `frames` frames along a guided walk from the camera's position,
/// `spacing` metres apart, each written as a numbered PNG.
pub(crate) struct Tour {
    /// How many frames.
    pub(crate) frames: u32,
    /// Metres walked between frames.
    pub(crate) spacing: f32,
    /// The guided walk's seed.
    pub(crate) seed: u64,
    /// Each frame's width and height in pixels.
    pub(crate) size: (u32, u32),
    /// The camera's pitch, in radians, all the way.
    pub(crate) pitch: f32,
}

impl Tour {
    /// Renders the frames and prints what each showed and what the walk did.
    pub(crate) fn run(
        &self,
        scene: &mut Scene,
        offscreen: &mut offscreen::Offscreen,
        camera: Camera,
        path: &str,
        mode: render::Mode,
    ) -> Result<(), ViewerError> {
        let start = sylva::terrain::glam::Vec2::new(camera.x, camera.z);
        let mut guide = guide::Guide::new(&scene.world, start, self.seed)?;
        let pitch = self.pitch;
        let mut times = Vec::new();
        for frame in 0..self.frames {
            if frame > 0 {
                guide.advance(self.spacing, 0.0);
            }
            let t = Instant::now();
            let (pixels, stats) = offscreen.frame(scene, &guide.camera(0.0, pitch), mode)?;
            times.push(t.elapsed().as_secs_f64() * 1e3);
            let file = numbered(path, frame);
            write_png(&file, self.size, &pixels)?;
            let c = guide.camera(0.0, pitch);
            println!(
                "wrote {file}: camera {:.1},{:.1},{:.0},{:.0}; {} instances, {} triangles",
                c.x,
                c.z,
                c.yaw.to_degrees(),
                c.pitch.to_degrees(),
                stats.instances,
                stats.triangles
            );
        }
        println!(
            "tour of {} frames {} m apart on {}: {}; median frame {:.0} ms",
            self.frames,
            self.spacing,
            offscreen.adapter,
            guide.summary(),
            median(&mut times).unwrap_or(0.0)
        );
        Ok(())
    }
}
