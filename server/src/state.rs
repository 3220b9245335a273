//! What a running server holds: its options, the cache folder, the generation queue, the
//! worlds built in memory and the single trees recently made.

use std::collections::{HashMap, VecDeque};
use std::net::SocketAddr;
use std::path::PathBuf;
use std::sync::atomic::AtomicUsize;
use std::sync::{Arc, Mutex};
use std::time::Duration;

use sylva::forest::Species;

use crate::cache::Cache;
use crate::error::ApiError;
use crate::jobs::Jobs;
use crate::world::Worlds;

/// How a server runs.
#[derive(Debug, Clone, PartialEq)]
pub struct ServerOptions {
    /// Where it listens (loopback by default).
    pub address: SocketAddr,
    /// The cache folder: kept worlds, uploads and every generated file.
    pub cache: PathBuf,
    /// Generations run at once (default: the machine's cores).
    pub workers: usize,
    /// Generations started and unfinished beyond which requests get 503 `busy`.
    pub max_queued: usize,
    /// How long a request waits for its generation before a 503 asking it to retry.
    pub generation_timeout: Duration,
    /// Requests in progress beyond which new ones get 503 `busy`.
    pub max_requests: usize,
    /// Connections open at once beyond which a new one is answered 503 `busy` (with
    /// `Retry-After`) and closed.
    pub max_connections: usize,
    /// How long a client may take to send a request's head (its request line and headers)
    /// before its connection is closed.
    pub header_timeout: Duration,
    /// Worlds held built in memory (each its instance caches and terrain).
    pub worlds_in_memory: usize,
    /// Bytes of single trees kept in memory.
    pub tree_bytes: usize,
    /// A folder holding the npm packages `three` and `3d-tiles-renderer` for the page
    /// (served at `/modules/`); without it the page asks for them.
    pub web_modules: Option<PathBuf>,
}

impl Default for ServerOptions {
    fn default() -> Self {
        ServerOptions {
            address: SocketAddr::from(([127, 0, 0, 1], 8080)),
            cache: PathBuf::from("sylva-cache"),
            workers: std::thread::available_parallelism().map_or(2, |n| n.get()),
            max_queued: 256,
            generation_timeout: Duration::from_secs(120),
            max_requests: 4096,
            max_connections: 512,
            header_timeout: Duration::from_secs(10),
            worlds_in_memory: 4,
            tree_bytes: 64 << 20,
            web_modules: None,
        }
    }
}

impl ServerOptions {
    /// Sets [`ServerOptions::address`].
    #[must_use]
    pub fn with_address(mut self, address: SocketAddr) -> Self {
        self.address = address;
        self
    }
    /// Sets [`ServerOptions::cache`].
    #[must_use]
    pub fn with_cache(mut self, cache: impl Into<PathBuf>) -> Self {
        self.cache = cache.into();
        self
    }
    /// Sets [`ServerOptions::workers`].
    #[must_use]
    pub fn with_workers(mut self, workers: usize) -> Self {
        self.workers = workers;
        self
    }
    /// Sets [`ServerOptions::max_queued`].
    #[must_use]
    pub fn with_max_queued(mut self, max_queued: usize) -> Self {
        self.max_queued = max_queued;
        self
    }
    /// Sets [`ServerOptions::max_connections`].
    #[must_use]
    pub fn with_max_connections(mut self, max_connections: usize) -> Self {
        self.max_connections = max_connections;
        self
    }

    /// Sets [`ServerOptions::header_timeout`].
    #[must_use]
    pub fn with_header_timeout(mut self, timeout: Duration) -> Self {
        self.header_timeout = timeout;
        self
    }

    /// Sets [`ServerOptions::generation_timeout`].
    #[must_use]
    pub fn with_generation_timeout(mut self, timeout: Duration) -> Self {
        self.generation_timeout = timeout;
        self
    }
    /// Sets [`ServerOptions::max_requests`].
    #[must_use]
    pub fn with_max_requests(mut self, max_requests: usize) -> Self {
        self.max_requests = max_requests;
        self
    }
    /// Sets [`ServerOptions::worlds_in_memory`].
    #[must_use]
    pub fn with_worlds_in_memory(mut self, worlds: usize) -> Self {
        self.worlds_in_memory = worlds;
        self
    }
    /// Sets [`ServerOptions::tree_bytes`].
    #[must_use]
    pub fn with_tree_bytes(mut self, bytes: usize) -> Self {
        self.tree_bytes = bytes;
        self
    }
    /// Sets [`ServerOptions::web_modules`].
    #[must_use]
    pub fn with_web_modules(mut self, folder: Option<PathBuf>) -> Self {
        self.web_modules = folder;
        self
    }
}

/// The kept trees by key, their keys oldest first, and their bytes.
#[derive(Debug, Default)]
struct Kept {
    trees: HashMap<String, Arc<Vec<u8>>>,
    order: VecDeque<String>,
    bytes: usize,
}

/// Single trees' GLBs, the most recently made kept within a byte budget.
#[derive(Debug, Default)]
pub(crate) struct TreeStore {
    inner: Mutex<Kept>,
    budget: usize,
}

impl TreeStore {
    /// A store of at most `budget` bytes.
    pub(crate) fn new(budget: usize) -> TreeStore {
        TreeStore {
            inner: Mutex::default(),
            budget,
        }
    }

    /// The tree under `key`, if kept.
    pub(crate) fn get(&self, key: &str) -> Option<Arc<Vec<u8>>> {
        self.inner.lock().ok()?.trees.get(key).cloned()
    }

    /// Keeps `glb` under `key`, dropping the oldest beyond the budget.
    pub(crate) fn put(&self, key: String, glb: Vec<u8>) {
        let Ok(mut inner) = self.inner.lock() else {
            return;
        };
        let Kept {
            trees: map,
            order,
            bytes,
        } = &mut *inner;
        *bytes += glb.len();
        if let Some(old) = map.insert(key.clone(), Arc::new(glb)) {
            *bytes -= old.len();
        } else {
            order.push_back(key);
        }
        while *bytes > self.budget && order.len() > 1 {
            if let Some(k) = order.pop_front()
                && let Some(old) = map.remove(&k)
            {
                *bytes -= old.len();
            }
        }
    }

    /// Bytes kept.
    pub(crate) fn bytes(&self) -> usize {
        self.inner.lock().map(|i| i.bytes).unwrap_or(0)
    }
}

/// A running server's state, shared by its handlers.
#[derive(Debug)]
pub struct Server {
    /// How it runs.
    pub options: ServerOptions,
    /// Its cache folder.
    pub(crate) cache: Cache,
    /// The generation queue.
    pub(crate) jobs: Jobs,
    /// Worlds built in memory.
    pub(crate) worlds: Worlds,
    /// Single trees recently made.
    pub(crate) trees: TreeStore,
    /// The bundled species, for `/trees/`.
    pub(crate) species: Vec<Species>,
    /// Requests in progress.
    pub(crate) requests: AtomicUsize,
}

impl Server {
    /// A server's state: opens its cache (creating it) and parses the bundled species.
    pub fn new(options: ServerOptions) -> Result<Arc<Server>, ApiError> {
        let cache = Cache::open(&options.cache)
            .map_err(|e| ApiError::internal(format!("cache {}: {e}", options.cache.display())))?;
        let species = sylva::presets::species().map_err(|e| ApiError::internal(e.to_string()))?;
        Ok(Arc::new(Server {
            jobs: Jobs::new(
                options.workers,
                options.max_queued,
                options.generation_timeout,
            ),
            worlds: Worlds::new(options.worlds_in_memory),
            trees: TreeStore::new(options.tree_bytes),
            cache,
            species,
            requests: AtomicUsize::new(0),
            options,
        }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_tree_store_keeps_within_its_budget() {
        let store = TreeStore::new(100);
        for k in 0..10 {
            store.put(format!("t{k}"), vec![0; 30]);
        }
        assert!(store.bytes() <= 100);
        assert!(store.get("t9").is_some());
        assert!(store.get("t0").is_none());
    }
}
