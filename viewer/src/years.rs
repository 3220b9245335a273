//! The forest over time a world is drawn from: its [`Succession`] at the year reached,
//! stepped by a key in the window or for a headless time-lapse (`timelapse.rs`).

use std::sync::{Mutex, PoisonError};

use sylva::forest::succession::Succession;
use sylva::forest::{ForestBuilder, ForestError};

/// Most years the viewer simulates: the world's limit, the same the CLI and the server check.
pub(crate) use sylva::world::limits::MAX_YEARS;

/// A world's forest over time, at the year it has reached.
pub(crate) struct Years {
    forest: Mutex<Succession>,
}

impl Years {
    /// The forest over time the world layer grew (to the year asked for).
    pub(crate) fn of(forest: Succession) -> Years {
        Years {
            forest: Mutex::new(forest),
        }
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
        builder.drawing(&forest)
    }
}
