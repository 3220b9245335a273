//! A headless time-lapse of a forest over time, and the step that moves a scene's forest on
//! (the window's Y key takes it too).

use std::time::Instant;

use sylva::forest::Rect;
use sylva::terrain::HeightField;

use crate::error::ViewerError;
use crate::offscreen::Offscreen;
use crate::render::Mode;
use crate::scene::{Camera, Scene};

impl Scene {
    /// Moves a forest over time on by `years` and regenerates every resident cell: the year
    /// reached, or `None` for a world without one.
    pub(crate) fn advance_years(&mut self, years: u32) -> Result<Option<u32>, ViewerError> {
        let Some(version) = self.world.advance_years(years)? else {
            return Ok(None);
        };
        let (lo, hi) = self.world.heightmap.bounds();
        self.cells
            .repaint(&self.world, Rect::new(lo, hi), version)?;
        Ok(self.world.year())
    }
}

/// A headless time-lapse: a frame at each of `years` (ascending), each written as
/// `PATH_YYYY.png` (by year), and a contact sheet of them (four a row, half size) at `PATH`.
pub(crate) struct TimeLapse {
    pub(crate) years: Vec<u32>,
    pub(crate) size: (u32, u32),
}

impl TimeLapse {
    /// Renders the frames; the scene must have been built at the first year.
    pub(crate) fn run(
        &self,
        scene: &mut Scene,
        offscreen: &mut Offscreen,
        camera: &Camera,
        path: &str,
        mode: Mode,
    ) -> Result<(), ViewerError> {
        let mut pictures = Vec::new();
        let mut year = self.years.first().copied().unwrap_or(0);
        for &next in &self.years {
            if next > year {
                year = scene
                    .advance_years(next - year)?
                    .ok_or(ViewerError::Usage("a time-lapse needs --years".into()))?;
            }
            let t = Instant::now();
            let (pixels, stats) = offscreen.frame(scene, camera, mode)?;
            let file = crate::numbered(path, year);
            crate::write_png(&file, self.size, &pixels)?;
            println!(
                "wrote {file}: year {year}, {} trees in the cells drawn, {} instances, {} triangles, {:.0} ms",
                stats.streamed.trees,
                stats.instances,
                stats.triangles,
                t.elapsed().as_secs_f64() * 1e3
            );
            pictures.push(pixels);
        }
        let (sheet, sheet_size) = crate::turntable::contact_sheet(&pictures, self.size, 4);
        crate::write_png(path, sheet_size, &sheet)?;
        println!("wrote {path}: the {} frames, four a row", pictures.len());
        Ok(())
    }
}
