//! The day of the year the viewer draws, and the year played in the window: N starts and
//! stops it (a year a minute), Shift+N moves the day on by ten.

use std::time::Instant;

/// Days the played year moves on per second: a year in a minute.
const DAYS_PER_SECOND: f32 = 365.0 / 60.0;

/// The day drawn, if any, and whether the year is playing.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct YearClock {
    /// The day when the clock last stopped or was set (`None`: the species as given).
    day: Option<f32>,
    /// When it started playing, if it is.
    playing: Option<Instant>,
}

impl YearClock {
    /// A clock standing at `day` (`None`: no season until N is pressed).
    pub(crate) fn at(day: Option<f32>) -> YearClock {
        YearClock { day, playing: None }
    }

    /// The day to draw now.
    pub(crate) fn day(&self) -> Option<f32> {
        let start = self.day?;
        Some(match self.playing {
            Some(since) => wrap(start + since.elapsed().as_secs_f32() * DAYS_PER_SECOND),
            None => start,
        })
    }

    /// Starts the year playing from the day drawn (midsummer when none), or stops it there.
    pub(crate) fn toggle(&mut self) {
        let now = self.day().unwrap_or(200.0);
        self.day = Some(now);
        self.playing = match self.playing {
            Some(_) => None,
            None => Some(Instant::now()),
        };
    }

    /// Moves the day on by `days`.
    pub(crate) fn advance(&mut self, days: f32) {
        let now = self.day().unwrap_or(200.0);
        self.day = Some(wrap(now + days));
        if self.playing.is_some() {
            self.playing = Some(Instant::now());
        }
    }

    /// What the window's title says of it.
    pub(crate) fn title(&self) -> String {
        match self.day() {
            Some(day) if self.playing.is_some() => {
                format!("day {day:.0}, the year playing (N: stop); ")
            }
            Some(day) => format!("day {day:.0} (N: play the year, Shift+N: +10 days); "),
            None => String::new(),
        }
    }
}

/// `day` taken into 1 to 365.
fn wrap(day: f32) -> f32 {
    (day - 1.0).rem_euclid(365.0) + 1.0
}

/// A headless season strip: a frame on each of the four seasons' days
/// ([`sylva::forest::SEASON_DAYS`]: spring, summer, autumn, winter), each written as
/// `PATH_DDDD.png` (by day), and a contact sheet of them, left to right, at `PATH`.
pub(crate) struct SeasonStrip {
    pub(crate) size: (u32, u32),
}

impl SeasonStrip {
    /// Renders the frames from `camera`.
    pub(crate) fn run(
        &self,
        scene: &mut crate::scene::Scene,
        offscreen: &mut crate::offscreen::Offscreen,
        camera: &crate::scene::Camera,
        path: &str,
        mode: crate::render::Mode,
    ) -> Result<(), crate::error::ViewerError> {
        let mut pictures = Vec::new();
        for (name, day) in sylva::forest::SEASON_DAYS {
            offscreen.season = Some(day);
            let (pixels, stats) = offscreen.frame(scene, camera, mode)?;
            let file = crate::numbered(path, day as u32);
            crate::write_png(&file, self.size, &pixels)?;
            println!(
                "wrote {file}: {name} (day {day}), {} instances, {} triangles",
                stats.instances, stats.triangles
            );
            pictures.push(pixels);
        }
        let (sheet, sheet_size) = crate::turntable::contact_sheet(&pictures, self.size, 4);
        crate::write_png(path, sheet_size, &sheet)?;
        println!("wrote {path}: spring, summer, autumn and winter, left to right");
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_clock_moves_on_round_the_year() {
        let mut clock = YearClock::at(Some(360.0));
        assert_eq!(clock.day(), Some(360.0));
        clock.advance(10.0);
        assert_eq!(clock.day(), Some(5.0));
        let mut none = YearClock::at(None);
        assert_eq!(none.day(), None);
        none.toggle();
        assert!(none.day().is_some_and(|d| (200.0..201.0).contains(&d)));
        none.toggle();
        let stopped = none.day();
        assert_eq!(none.day(), stopped);
    }
}
