//! What a world's build tells whoever waits for it: the stages as they begin and end, and
//! the years of a forest over time as they pass. The CLI draws bars from it, the viewer
//! prints lines, the server says nothing.

use std::time::Duration;

/// A stage of building a world.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Stage {
    /// The species' instance caches, from hero trees: seconds.
    HeroTrees,
    /// The painted masks, read and laid on the ground.
    Painting,
    /// The forest over time, grown from bare ground to its year.
    Years,
}

impl Stage {
    /// What the stage does, for a person.
    pub fn describe(self) -> &'static str {
        match self {
            Stage::HeroTrees => "building instance caches from hero trees",
            Stage::Painting => "reading the painted masks",
            Stage::Years => "years of the forest over time",
        }
    }
}

/// Hears how a world's build goes. Every method does nothing unless overridden.
pub trait Progress: Sync {
    /// `stage` begins.
    fn begin(&self, _stage: Stage) {}
    /// `stage` ended after `elapsed`.
    fn end(&self, _stage: Stage, _elapsed: Duration) {}
    /// `done` of `total` years of a forest over time have passed.
    fn years(&self, _done: u32, _total: u32) {}
}

/// Hears nothing.
#[derive(Debug, Clone, Copy, Default)]
pub struct Quiet;

impl Progress for Quiet {}

/// Runs `work` as `stage`, telling `progress`; answers its result and how long it took.
pub(crate) fn timed<T>(
    progress: &dyn Progress,
    stage: Stage,
    work: impl FnOnce() -> T,
) -> (T, Duration) {
    progress.begin(stage);
    let start = std::time::Instant::now();
    let out = work();
    let elapsed = start.elapsed();
    progress.end(stage, elapsed);
    (out, elapsed)
}
