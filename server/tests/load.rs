//! The server under load: 64 connections held for a while (3 s here; CI runs 30 s with
//! `SYLVA_LOAD_SECONDS=30`) over a mix of cached tiles and tiles never asked for before.
//! Every answer must be a 200, and memory must stay bounded; the latencies and rates are
//! reported (printed as a table), not asserted: machines here are shared and noisy.

mod common;

use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

use common::{Client, memory_mb, options, scratch, start, world};

/// Connections held at once.
const CONNECTIONS: usize = 64;
/// Fine tiles along a side of the world.
const ROW: usize = 96;
/// One request in this many asks for a tile not generated yet.
const NEW_EVERY: usize = 8;

/// What one connection saw.
#[derive(Default)]
struct Seen {
    cached_ms: Vec<f64>,
    new_ms: Vec<f64>,
    bytes: usize,
    errors: Vec<String>,
}

fn percentile(sorted: &[f64], p: f64) -> f64 {
    if sorted.is_empty() {
        return 0.0;
    }
    sorted[((sorted.len() - 1) as f64 * p).round() as usize]
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn sixty_four_connections_hold_without_an_error() {
    let seconds: u64 = std::env::var("SYLVA_LOAD_SECONDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(3)
        .clamp(1, 120);
    let server = start(options(scratch("load"))).await;
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
    let deadline = Instant::now() + Duration::from_secs(seconds);
    let started = Instant::now();
    let mut tasks = Vec::new();
    for connection in 0..CONNECTIONS {
        let (fresh, id) = (fresh.clone(), id.clone());
        let address = server.address;
        tasks.push(tokio::spawn(async move {
            let fine = |k: usize| format!("/worlds/{id}/tiles/f_{}_{}.glb", k % ROW, k / ROW);
            let mut client = Client::connect(address).await;
            let mut seen = Seen::default();
            let mut state = connection as u64 * 0x9e37_79b9 + 1;
            let mut n = 0usize;
            while Instant::now() < deadline {
                n += 1;
                state = state
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                let pick = (state >> 33) as usize;
                let new_tile = (n + connection).is_multiple_of(NEW_EVERY);
                let path = if new_tile {
                    let k = fresh.fetch_add(1, Ordering::Relaxed);
                    if k >= ROW * ROW {
                        fine(pick % warm)
                    } else {
                        fine(k)
                    }
                } else if pick.is_multiple_of(8) {
                    format!("/worlds/{id}/tileset.json")
                } else {
                    fine(pick % warm)
                };
                let t = Instant::now();
                match client
                    .send(hyper::Method::GET, &path, &[], Vec::new())
                    .await
                {
                    Ok(a) if a.status.as_u16() == 200 => {
                        let ms = t.elapsed().as_secs_f64() * 1e3;
                        seen.bytes += a.body.len();
                        if new_tile {
                            seen.new_ms.push(ms)
                        } else {
                            seen.cached_ms.push(ms)
                        }
                    }
                    Ok(a) => seen.errors.push(format!(
                        "{path}: {} {}",
                        a.status,
                        String::from_utf8_lossy(&a.body)
                    )),
                    Err(e) => {
                        seen.errors.push(format!("{path}: {e}"));
                        client = Client::connect(address).await;
                    }
                }
            }
            seen
        }));
    }
    let mut all = Seen::default();
    for t in tasks {
        let s = t.await.unwrap();
        all.cached_ms.extend(s.cached_ms);
        all.new_ms.extend(s.new_ms);
        all.bytes += s.bytes;
        all.errors.extend(s.errors);
    }
    let elapsed = started.elapsed().as_secs_f64();
    let (rss_after, rss_peak) = memory_mb();
    all.cached_ms.sort_by(f64::total_cmp);
    all.new_ms.sort_by(f64::total_cmp);
    let generated = fresh.load(Ordering::Relaxed).min(ROW * ROW) - warm;
    println!(
        "\n| load: {CONNECTIONS} connections, {elapsed:.1} s | requests | per second | p50 ms | p90 ms | p99 ms | max ms |"
    );
    println!("|---|---|---|---|---|---|---|");
    for (kind, ms) in [
        ("cached tiles and tileset", &all.cached_ms),
        ("new tiles (generated)", &all.new_ms),
    ] {
        println!(
            "| {kind} | {} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} |",
            ms.len(),
            ms.len() as f64 / elapsed,
            percentile(ms, 0.5),
            percentile(ms, 0.9),
            percentile(ms, 0.99),
            ms.last().copied().unwrap_or(0.0)
        );
    }
    println!(
        "served {:.1} MB ({:.1} MB/s); {generated} tiles generated ({:.2} per second); errors {}; memory {rss_before:.0} MB before, {rss_after:.0} MB after, {rss_peak:.0} MB peak",
        all.bytes as f64 / 1e6,
        all.bytes as f64 / 1e6 / elapsed,
        generated as f64 / elapsed,
        all.errors.len()
    );
    assert!(
        all.errors.is_empty(),
        "{} errors, the first: {}",
        all.errors.len(),
        all.errors[0]
    );
    assert!(!all.cached_ms.is_empty() && !all.new_ms.is_empty());
    assert!(generated > 0, "no new tile was generated");
    // Bounded: the worlds in memory and the connections' buffers, not the bytes served.
    assert!(
        rss_after < rss_before + 1024.0,
        "memory grew from {rss_before:.0} MB to {rss_after:.0} MB"
    );
    server.stop().await;
}
