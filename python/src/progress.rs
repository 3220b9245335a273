//! Long work's reports to a Python callback: `progress(stage, done, total)`, called from the
//! work with the GIL taken back for the call. The first exception the callback raises (or a
//! Ctrl-C, `KeyboardInterrupt`) is kept, no more calls are made, and the work ends with it
//! at its next check, so a user can stop a long build from the callback.

use std::sync::{Mutex, PoisonError};
use std::time::Duration;

use pyo3::prelude::*;
use sylva::world::{Progress, Stage};

/// A callback, or none, and the exception it raised.
#[derive(Debug)]
pub(crate) struct Callback {
    callback: Option<Py<PyAny>>,
    raised: Mutex<Option<PyErr>>,
}

impl Callback {
    /// Reports to `callback` when given.
    pub(crate) fn new(callback: Option<Py<PyAny>>) -> Callback {
        Callback {
            callback,
            raised: Mutex::new(None),
        }
    }

    /// Tells the callback that `done` of `total` of `stage` are done, unless it raised
    /// before.
    pub(crate) fn tell(&self, stage: &str, done: u64, total: u64) {
        let Some(callback) = &self.callback else {
            return;
        };
        if self.failed() {
            return;
        }
        let told = Python::attach(|py| {
            py.check_signals()?;
            callback.call1(py, (stage, done, total)).map(drop)
        });
        if let Err(e) = told {
            self.raised
                .lock()
                .unwrap_or_else(PoisonError::into_inner)
                .get_or_insert(e);
        }
    }

    /// Whether the callback raised.
    fn failed(&self) -> bool {
        self.raised
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .is_some()
    }

    /// The callback's exception, if it raised: work between steps stops with it.
    pub(crate) fn check(&self) -> PyResult<()> {
        match self
            .raised
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .take()
        {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }

    /// `result`, unless the callback raised during the work that made it.
    pub(crate) fn finish<T>(&self, result: PyResult<T>) -> PyResult<T> {
        self.check()?;
        result
    }
}

impl Progress for Callback {
    fn begin(&self, stage: Stage) {
        self.tell(stage.describe(), 0, 1);
    }

    fn end(&self, stage: Stage, _elapsed: Duration) {
        self.tell(stage.describe(), 1, 1);
    }

    fn years(&self, done: u32, total: u32) {
        self.tell(Stage::Years.describe(), u64::from(done), u64::from(total));
    }
}
