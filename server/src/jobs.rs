//! Generation jobs: a bounded queue in front of a fixed number of workers, and one flight per
//! key, so concurrent requests for one tile generate it once and all get its outcome.

use std::collections::HashMap;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use tokio::sync::{Semaphore, watch};

use crate::error::ApiError;

/// A job's outcome as its waiters see it: `None` while it runs.
type Outcome = Option<Result<(), ApiError>>;

/// The queue and the flights.
#[derive(Debug)]
pub(crate) struct Jobs {
    /// One permit per worker.
    workers: Arc<Semaphore>,
    /// Jobs started and not finished (waiting for a worker or running).
    queued: Arc<AtomicUsize>,
    max_queued: usize,
    timeout: Duration,
    flights: Arc<Mutex<HashMap<String, watch::Receiver<Outcome>>>>,
}

impl Jobs {
    /// `workers` jobs at a time, at most `max_queued` started and unfinished, a request
    /// waiting at most `timeout` for its job.
    pub(crate) fn new(workers: usize, max_queued: usize, timeout: Duration) -> Jobs {
        Jobs {
            workers: Arc::new(Semaphore::new(workers.max(1))),
            queued: Arc::new(AtomicUsize::new(0)),
            max_queued: max_queued.max(1),
            timeout,
            flights: Arc::default(),
        }
    }

    /// Jobs started and not finished.
    pub(crate) fn queued(&self) -> usize {
        self.queued.load(Ordering::Relaxed)
    }

    /// Runs `job` (blocking work, on a worker) under `key`, or joins the run already under
    /// it, and waits for its outcome. Beyond the queue's limit: 503 `busy`. Past the time
    /// limit: 503 `generating`, and the job runs on to completion (its output is stored, so
    /// the retry the answer asks for finds it); a waiter that goes away (a client that
    /// disconnects) leaves the job running for the same reason.
    pub(crate) async fn run<F>(&self, key: &str, job: F) -> Result<(), ApiError>
    where
        F: FnOnce() -> Result<(), ApiError> + Send + 'static,
    {
        let mut outcome = self.join_or_start(key, job)?;
        let finished = tokio::time::timeout(self.timeout, outcome.wait_for(Option::is_some)).await;
        match finished {
            Ok(Ok(done)) => done
                .clone()
                .unwrap_or_else(|| Err(ApiError::internal("no outcome"))),
            Ok(Err(_)) => Err(ApiError::internal("a generation ended without an outcome")),
            Err(_) => Err(ApiError::unavailable(
                "generating",
                format!(
                    "still generating after {} s; it goes on, try again shortly",
                    self.timeout.as_secs()
                ),
                5,
            )),
        }
    }

    fn join_or_start<F>(&self, key: &str, job: F) -> Result<watch::Receiver<Outcome>, ApiError>
    where
        F: FnOnce() -> Result<(), ApiError> + Send + 'static,
    {
        let mut flights = self.flights.lock().unwrap_or_else(|p| p.into_inner());
        if let Some(running) = flights.get(key) {
            return Ok(running.clone());
        }
        if self.queued.load(Ordering::Relaxed) >= self.max_queued {
            return Err(ApiError::unavailable(
                "busy",
                format!(
                    "{} generations are queued, the limit: try again shortly",
                    self.max_queued
                ),
                2,
            ));
        }
        self.queued.fetch_add(1, Ordering::Relaxed);
        let (done, outcome) = watch::channel(None);
        flights.insert(key.to_owned(), outcome.clone());
        let (workers, queued, all) = (
            self.workers.clone(),
            self.queued.clone(),
            self.flights.clone(),
        );
        let key = key.to_owned();
        tokio::spawn(async move {
            let result = match workers.acquire_owned().await {
                Ok(permit) => tokio::task::spawn_blocking(move || {
                    let _permit = permit;
                    job()
                })
                .await
                .unwrap_or_else(|e| Err(ApiError::internal(format!("a generation failed: {e}")))),
                Err(_) => Err(ApiError::internal("the workers are gone")),
            };
            // Out of the map first: a request after this finds the stored file, or starts
            // afresh (the job checks for its file before working).
            all.lock().unwrap_or_else(|p| p.into_inner()).remove(&key);
            queued.fetch_sub(1, Ordering::Relaxed);
            let _ = done.send(Some(result));
        });
        Ok(outcome)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::AtomicU32;

    #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
    async fn one_key_runs_once_for_many_waiters() {
        let jobs = Arc::new(Jobs::new(2, 8, Duration::from_secs(30)));
        let runs = Arc::new(AtomicU32::new(0));
        let mut waiters = Vec::new();
        for _ in 0..16 {
            let (jobs, runs) = (jobs.clone(), runs.clone());
            waiters.push(tokio::spawn(async move {
                jobs.run("tile", move || {
                    runs.fetch_add(1, Ordering::SeqCst);
                    std::thread::sleep(Duration::from_millis(200));
                    Ok(())
                })
                .await
            }));
        }
        for w in waiters {
            w.await.unwrap().unwrap();
        }
        assert_eq!(runs.load(Ordering::SeqCst), 1);
        assert_eq!(jobs.queued(), 0);
    }

    #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
    async fn a_full_queue_answers_busy_and_a_slow_job_times_out() {
        let jobs = Arc::new(Jobs::new(1, 1, Duration::from_millis(100)));
        let slow = {
            let jobs = jobs.clone();
            tokio::spawn(async move {
                jobs.run("a", || {
                    std::thread::sleep(Duration::from_millis(600));
                    Ok(())
                })
                .await
            })
        };
        tokio::time::sleep(Duration::from_millis(20)).await;
        let busy = jobs.run("b", || Ok(())).await.unwrap_err();
        assert_eq!(
            (busy.status.as_u16(), busy.code, busy.retry_after),
            (503, "busy", Some(2))
        );
        let late = slow.await.unwrap().unwrap_err();
        assert_eq!((late.status.as_u16(), late.code), (503, "generating"));
        // The job ran on: once it is done the queue is empty again.
        tokio::time::sleep(Duration::from_millis(700)).await;
        assert_eq!(jobs.queued(), 0);
        jobs.run("b", || Ok(())).await.unwrap();
    }

    #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
    async fn failures_reach_every_waiter_and_a_later_run_tries_again() {
        let jobs = Jobs::new(1, 4, Duration::from_secs(5));
        let e = jobs
            .run("x", || Err(ApiError::unprocessable("no trees")))
            .await
            .unwrap_err();
        assert_eq!(e.status.as_u16(), 422);
        jobs.run("x", || Ok(())).await.unwrap();
    }
}
