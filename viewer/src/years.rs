//! The forest over time in the viewer: the world's [`Succession`], stepped by a key in the
//! window or year by year for a headless time-lapse; each year's snapshot replaces the
//! forest's trees as a repaint of the whole world does.

use std::sync::{Arc, Mutex, PoisonError};
use std::time::Instant;

use sylva::forest::succession::{Succession, SuccessionOptions};
use sylva::forest::{ForestBuilder, ForestError, Rect};
use sylva::terrain::HeightField;

use crate::error::ViewerError;
use crate::offscreen::Offscreen;
use crate::render::Mode;
use crate::scene::{Camera, Scene};
use crate::world::World;

/// Most years the viewer simulates.
pub(crate) const MAX_YEARS: u32 = 2000;

/// A world's forest over time, at the year it has reached.
pub(crate) struct Years {
    forest: Mutex<Succession>,
}

impl Years {
    /// The forest of `builder`'s species over `region`, grown from bare ground to `year`
    /// with the builder's seed; returns it and the builder drawing that year.
    pub(crate) fn grow(
        builder: &ForestBuilder,
        region: Rect,
        year: u32,
    ) -> Result<(Years, ForestBuilder), ForestError> {
        let options = SuccessionOptions::default().with_seed(builder.config().seed);
        let mut forest = Succession::new(builder.config().species.clone(), region, options)?;
        forest.run(year, |_| Ok(()))?;
        let drawn = builder.with_snapshot(Some(Arc::new(forest.snapshot())))?;
        Ok((
            Years {
                forest: Mutex::new(forest),
            },
            drawn,
        ))
    }

    /// The year reached.
    pub(crate) fn year(&self) -> u32 {
        self.forest
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .year()
    }

    /// Runs `years` more years; returns the builder drawing the year reached.
    pub(crate) fn advance(
        &self,
        builder: &ForestBuilder,
        years: u32,
    ) -> Result<ForestBuilder, ForestError> {
        let mut forest = self.forest.lock().unwrap_or_else(PoisonError::into_inner);
        forest.run(years, |_| Ok(()))?;
        builder.with_snapshot(Some(Arc::new(forest.snapshot())))
    }
}

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

impl World {
    /// The year its forest over time has reached, if it has one.
    pub(crate) fn year(&self) -> Option<u32> {
        self.years.as_ref().map(Years::year)
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
