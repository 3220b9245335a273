//! The server under load: 64 clients, each on its own connection, for a while (3 s here; CI
//! runs 30 s with `SYLVA_LOAD_SECONDS=30`, and `SYLVA_LOAD_SECONDS=60` is the full run) over
//! a mix of what clients ask: cached tiles, tiles never asked for before, tilesets, trees and
//! new worlds. Every request is answered (a 2xx), refused (a 503 with `Retry-After`, the
//! server's bounded queue saying "later") or unanswered (the connection failed, or no answer
//! within a minute). The test fails on any unanswered request, any 503 without `Retry-After`
//! and any other error status; memory must stay bounded. Counts, latencies and rates are
//! reported as a table, not asserted: machines here are shared and noisy.

mod common;

use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

use common::{Client, memory_mb, options, scratch, start, world};
use hyper::Method;

/// Clients, each with a connection of its own.
const CLIENTS: usize = 64;
/// Fine tiles along a side of the world.
const ROW: usize = 96;
/// One request in this many asks for a tile not generated yet.
const NEW_EVERY: usize = 8;
/// One request in this many posts a new world and asks for its tileset.
const WORLD_EVERY: usize = 256;
/// How long a client waits for an answer before counting the request unanswered.
const ANSWER_WITHIN: Duration = Duration::from_secs(60);
/// Species asked for as single trees.
const TREES: [&str; 4] = ["birch", "pine", "oak", "hazel"];

/// What clients ask for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    CachedTile,
    NewTile,
    Tileset,
    Tree,
    NewWorld,
}

const KINDS: [Kind; 5] = [
    Kind::CachedTile,
    Kind::NewTile,
    Kind::Tileset,
    Kind::Tree,
    Kind::NewWorld,
];

impl Kind {
    fn name(self) -> &'static str {
        match self {
            Kind::CachedTile => "cached tiles",
            Kind::NewTile => "new tiles (generated)",
            Kind::Tileset => "tilesets",
            Kind::Tree => "trees",
            Kind::NewWorld => "new worlds (posted, then their tileset)",
        }
    }
}

/// What the clients saw of one kind of request.
#[derive(Debug, Default)]
struct Tally {
    answered_ms: Vec<f64>,
    refused: usize,
    unanswered: usize,
    bytes: usize,
    /// Answers that are neither: their path, status and body.
    wrong: Vec<String>,
}

impl Tally {
    fn add(&mut self, other: Tally) {
        self.answered_ms.extend(other.answered_ms);
        self.refused += other.refused;
        self.unanswered += other.unanswered;
        self.bytes += other.bytes;
        self.wrong.extend(other.wrong);
    }
}

fn percentile(sorted: &[f64], p: f64) -> f64 {
    if sorted.is_empty() {
        return 0.0;
    }
    sorted[((sorted.len() - 1) as f64 * p).round() as usize]
}

/// Sends one request within [`ANSWER_WITHIN`] and tallies what came back; a failed
/// connection is replaced.
async fn ask(
    client: &mut Client,
    tally: &mut Tally,
    (method, path, body): (Method, &str, Vec<u8>),
) -> Option<Vec<u8>> {
    let t = Instant::now();
    let answer = tokio::time::timeout(ANSWER_WITHIN, client.send(method, path, &[], body)).await;
    match answer {
        Ok(Ok(a)) if a.status.is_success() => {
            tally.answered_ms.push(t.elapsed().as_secs_f64() * 1e3);
            tally.bytes += a.body.len();
            Some(a.body)
        }
        Ok(Ok(a)) if a.status.as_u16() == 503 && a.headers.contains_key("retry-after") => {
            tally.refused += 1;
            None
        }
        Ok(Ok(a)) => {
            tally.wrong.push(format!(
                "{path}: {} {}",
                a.status,
                String::from_utf8_lossy(&a.body)
            ));
            None
        }
        Ok(Err(_)) | Err(_) => {
            tally.unanswered += 1;
            None
        }
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn sixty_four_clients_are_answered_or_told_to_retry() {
    let seconds: u64 = std::env::var("SYLVA_LOAD_SECONDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(3)
        .clamp(1, 120);
    // A generation waited for longer than this is answered 503 "generating", to retry.
    let server =
        start(options(scratch("load")).with_generation_timeout(Duration::from_secs(20))).await;
    // 2.4 km in 25 m tiles: 9,216 fine tiles, enough never asked for to last the run.
    let id = world(
        server.address,
        r#"{"area": 2400, "tile_size": 25, "group": 4, "budget_mb": 8, "species": ["birch", "pine"], "seed": 9}"#,
    )
    .await;
    let fine = |k: usize| format!("/worlds/{id}/tiles/f_{}_{}.glb", k % ROW, k / ROW);
    // The cached set: the root and the first 24 fine tiles.
    let warm = 24;
    let mut c = Client::connect(server.address).await;
    for path in [
        format!("/worlds/{id}/tileset.json"),
        format!("/worlds/{id}/shared.bin"),
    ]
    .into_iter()
    .chain((0..warm).map(fine))
    {
        assert_eq!(c.get(&path).await.status.as_u16(), 200, "{path}");
    }
    let (rss_before, _) = memory_mb();
    let fresh = Arc::new(AtomicUsize::new(warm));
    let worlds = Arc::new(AtomicUsize::new(0));
    let deadline = Instant::now() + Duration::from_secs(seconds);
    let started = Instant::now();
    let mut tasks = Vec::new();
    for client_index in 0..CLIENTS {
        let (fresh, worlds, id) = (fresh.clone(), worlds.clone(), id.clone());
        let address = server.address;
        tasks.push(tokio::spawn(async move {
            let fine = |k: usize| format!("/worlds/{id}/tiles/f_{}_{}.glb", k % ROW, k / ROW);
            let mut client = Client::connect(address).await;
            let mut tallies: Vec<Tally> = KINDS.iter().map(|_| Tally::default()).collect();
            let mut state = client_index as u64 * 0x9e37_79b9 + 1;
            let mut n = 0usize;
            while Instant::now() < deadline {
                n += 1;
                state = state
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                let pick = (state >> 33) as usize;
                let kind = if (n + client_index).is_multiple_of(WORLD_EVERY) {
                    Kind::NewWorld
                } else if (n + client_index).is_multiple_of(NEW_EVERY) {
                    Kind::NewTile
                } else {
                    match pick % 16 {
                        0 | 1 => Kind::Tileset,
                        2 | 3 => Kind::Tree,
                        _ => Kind::CachedTile,
                    }
                };
                let tally = &mut tallies[kind as usize];
                let unanswered = tally.unanswered;
                match kind {
                    Kind::CachedTile => {
                        ask(&mut client, tally, (Method::GET, &fine(pick % warm), vec![])).await;
                    }
                    Kind::NewTile => {
                        let k = fresh.fetch_add(1, Ordering::Relaxed);
                        let path = fine(if k >= ROW * ROW { pick % warm } else { k });
                        ask(&mut client, tally, (Method::GET, &path, vec![])).await;
                    }
                    Kind::Tileset => {
                        let path = format!("/worlds/{id}/tileset.json");
                        ask(&mut client, tally, (Method::GET, &path, vec![])).await;
                    }
                    Kind::Tree => {
                        let species = TREES[pick % TREES.len()];
                        let path = format!("/trees/{species}.glb?seed={}", pick % 4);
                        ask(&mut client, tally, (Method::GET, &path, vec![])).await;
                    }
                    Kind::NewWorld => {
                        let seed = 1000 + worlds.fetch_add(1, Ordering::Relaxed);
                        let description = format!(
                            r#"{{"area": 200, "tile_size": 50, "group": 2, "budget_mb": 4, "species": ["hazel"], "seed": {seed}}}"#
                        );
                        let posted = (Method::POST, "/worlds", description.into_bytes());
                        if let Some(body) = ask(&mut client, tally, posted).await {
                            let made: serde_json::Value =
                                serde_json::from_slice(&body).unwrap_or_default();
                            let tileset = made["tileset"].as_str().unwrap_or("/").to_owned();
                            ask(&mut client, tally, (Method::GET, &tileset, vec![])).await;
                        }
                    }
                }
                if tallies[kind as usize].unanswered > unanswered {
                    client = Client::connect(address).await;
                }
            }
            tallies
        }));
    }
    let mut all: Vec<Tally> = KINDS.iter().map(|_| Tally::default()).collect();
    for t in tasks {
        for (total, tally) in all.iter_mut().zip(t.await.unwrap()) {
            total.add(tally);
        }
    }
    let elapsed = started.elapsed().as_secs_f64();
    let (rss_after, rss_peak) = memory_mb();
    let generated = fresh.load(Ordering::Relaxed).min(ROW * ROW) - warm;
    println!(
        "\n| load: {CLIENTS} clients, {elapsed:.1} s | answered | refused (503, Retry-After) | unanswered | other | answered per second | p50 ms | p90 ms | p99 ms | max ms |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for (kind, tally) in KINDS.iter().zip(&mut all) {
        tally.answered_ms.sort_by(f64::total_cmp);
        let ms = &tally.answered_ms;
        println!(
            "| {} | {} | {} | {} | {} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} |",
            kind.name(),
            ms.len(),
            tally.refused,
            tally.unanswered,
            tally.wrong.len(),
            ms.len() as f64 / elapsed,
            percentile(ms, 0.5),
            percentile(ms, 0.9),
            percentile(ms, 0.99),
            ms.last().copied().unwrap_or(0.0)
        );
    }
    let sum = |f: fn(&Tally) -> usize| all.iter().map(f).sum::<usize>();
    let (answered, refused, unanswered) = (
        sum(|t| t.answered_ms.len()),
        sum(|t| t.refused),
        sum(|t| t.unanswered),
    );
    let bytes = sum(|t| t.bytes);
    println!(
        "answered {answered}, refused {refused}, unanswered {unanswered}; served {:.1} MB ({:.1} MB/s); {generated} tiles generated ({:.2} per second), {} worlds posted; memory {rss_before:.0} MB before, {rss_after:.0} MB after, {rss_peak:.0} MB peak",
        bytes as f64 / 1e6,
        bytes as f64 / 1e6 / elapsed,
        generated as f64 / elapsed,
        worlds.load(Ordering::Relaxed)
    );
    assert_eq!(unanswered, 0, "{unanswered} requests went unanswered");
    let wrong: Vec<&String> = all.iter().flat_map(|t| &t.wrong).collect();
    assert!(
        wrong.is_empty(),
        "{} answers neither 2xx nor 503 with Retry-After, the first: {}",
        wrong.len(),
        wrong[0]
    );
    for kind in [Kind::CachedTile, Kind::Tileset, Kind::Tree] {
        assert!(
            !all[kind as usize].answered_ms.is_empty(),
            "no {} answered",
            kind.name()
        );
    }
    assert!(generated > 0, "no new tile was asked for");
    // Bounded: the worlds in memory and the connections' buffers, not the bytes served.
    assert!(
        rss_after < rss_before + 1024.0,
        "memory grew from {rss_before:.0} MB to {rss_after:.0} MB"
    );
    server.stop().await;
}
