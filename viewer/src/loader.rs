//! The window's cell generator: a thread that generates the cells the camera asks for,
//! nearest first, while frames go on drawing what has already arrived.

use std::sync::mpsc::{Receiver, Sender, channel};
use std::sync::{Arc, Condvar, Mutex, PoisonError};
use std::thread::JoinHandle;

use sylva::forest::ForestError;

use crate::cell::{Cell, CellKey};
use crate::world::World;

/// What the thread is to do next.
#[derive(Default)]
struct Queue {
    /// Cells still to generate, nearest first; replaced whole by each request, so cells
    /// the camera has walked away from are never generated.
    wanted: Vec<CellKey>,
    /// The cell being generated.
    busy: Option<CellKey>,
    stop: bool,
}

type Shared = Arc<(Mutex<Queue>, Condvar)>;

/// A generator thread; dropping it stops the thread after the cell in hand.
pub(crate) struct Loader {
    shared: Shared,
    done: Receiver<(CellKey, Result<Cell, ForestError>)>,
    thread: Option<JoinHandle<()>>,
}

impl Loader {
    pub(crate) fn new(world: Arc<World>) -> Loader {
        let shared: Shared = Arc::default();
        let (send, done) = channel();
        let queue = shared.clone();
        let thread = std::thread::Builder::new()
            .name("sylva cells".into())
            .spawn(move || generate(&world, &queue, &send))
            .ok();
        Loader {
            shared,
            done,
            thread,
        }
    }

    /// Hands over the cells finished since the last call, and asks for `missing` (nearest
    /// first) instead of whatever was asked before.
    pub(crate) fn ask(
        &mut self,
        missing: Vec<CellKey>,
    ) -> Vec<(CellKey, Result<Cell, ForestError>)> {
        let (lock, wake) = &*self.shared;
        let mut queue = lock.lock().unwrap_or_else(PoisonError::into_inner);
        // Under the lock the thread cannot be between sending a cell and forgetting it is
        // busy, so a cell is either received here or busy, never asked for twice.
        let received: Vec<_> = self.done.try_iter().collect();
        let busy = queue.busy;
        queue.wanted = missing
            .into_iter()
            .filter(|k| Some(*k) != busy && !received.iter().any(|(r, _)| r == k))
            .collect();
        wake.notify_one();
        received
    }
}

fn generate(world: &World, shared: &Shared, send: &Sender<(CellKey, Result<Cell, ForestError>)>) {
    let (lock, wake) = &**shared;
    loop {
        let key = {
            let mut queue = lock.lock().unwrap_or_else(PoisonError::into_inner);
            while queue.wanted.is_empty() && !queue.stop {
                queue = wake.wait(queue).unwrap_or_else(PoisonError::into_inner);
            }
            if queue.stop {
                return;
            }
            let key = queue.wanted.remove(0);
            queue.busy = Some(key);
            key
        };
        let cell = world.cell(key);
        let mut queue = lock.lock().unwrap_or_else(PoisonError::into_inner);
        queue.busy = None;
        if send.send((key, cell)).is_err() {
            return;
        }
    }
}

impl Drop for Loader {
    fn drop(&mut self) {
        let (lock, wake) = &*self.shared;
        lock.lock().unwrap_or_else(PoisonError::into_inner).stop = true;
        wake.notify_one();
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}
