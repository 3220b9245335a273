//! `sylva serve` killed with SIGKILL in the middle of a generation, then started again on the
//! same cache: it serves the batch writer's bytes, and nothing torn was ever in the cache
//! under a name it serves. Needs the `serve` feature (CI builds it).
#![cfg(feature = "serve")]

use std::io::{BufRead, BufReader, Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

const SYLVA: &str = env!("CARGO_BIN_EXE_sylva");
/// The world, as a description and as `sylva tiles` flags.
const WORLD: &str = r#"{"area": 600, "tile_size": 150, "seed": 3}"#;
const FLAGS: [&str; 6] = ["--area", "600", "--tile-size", "150", "--seed", "3"];

/// A scratch folder of this name, emptied.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("sylva-cli-serve-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// Starts `sylva serve` on a free loopback port over `cache`; answers it and its address.
fn start(cache: &Path) -> (Child, SocketAddr) {
    let mut child = Command::new(SYLVA)
        .args(["serve", "--port", "0", "--workers", "1", "--cache"])
        .arg(cache)
        .stdout(Stdio::piped())
        .stderr(Stdio::inherit())
        .spawn()
        .expect("sylva serve starts");
    let mut line = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    let address = line
        .split("http://")
        .nth(1)
        .and_then(|rest| rest.split('/').next())
        .and_then(|a| a.parse().ok())
        .unwrap_or_else(|| panic!("no address in {line:?}"));
    (child, address)
}

/// One request on its own connection; answers the status and body, or `None` if the
/// connection ended first.
fn request(address: SocketAddr, method: &str, path: &str, body: &str) -> Option<(u16, Vec<u8>)> {
    let mut stream = TcpStream::connect(address).ok()?;
    stream
        .set_read_timeout(Some(Duration::from_secs(600)))
        .ok()?;
    let head = format!(
        "{method} {path} HTTP/1.1\r\nhost: test\r\nconnection: close\r\ncontent-length: {}\r\n\r\n{body}",
        body.len()
    );
    stream.write_all(head.as_bytes()).ok()?;
    let mut answer = Vec::new();
    stream.read_to_end(&mut answer).ok()?;
    let split = answer.windows(4).position(|w| w == b"\r\n\r\n")?;
    let head = String::from_utf8_lossy(&answer[..split]).into_owned();
    let status = head.split_whitespace().nth(1)?.parse().ok()?;
    let length: usize = head
        .lines()
        .find_map(|l| {
            l.to_ascii_lowercase()
                .strip_prefix("content-length:")
                .map(|v| v.trim().to_owned())
        })?
        .parse()
        .ok()?;
    let body = answer[split + 4..].to_vec();
    // A body shorter than its length is a torn answer.
    (body.len() == length).then_some((status, body))
}

/// Every file under `dir`, relative, sorted.
fn files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).into_iter().flatten().flatten() {
            if e.path().is_dir() {
                stack.push(e.path());
            } else {
                out.push(e.path().strip_prefix(dir).unwrap().to_path_buf());
            }
        }
    }
    out.sort();
    out
}

#[test]
fn killed_mid_generation_it_restarts_and_serves_whole_files() {
    let (cache, batch) = (scratch("cache"), scratch("batch"));
    let made = Command::new(SYLVA)
        .args(["tiles", "--quiet", "--out"])
        .arg(&batch)
        .args(FLAGS)
        .status()
        .unwrap();
    assert!(made.success());

    let (mut server, address) = start(&cache);
    let (status, body) = request(address, "POST", "/worlds", WORLD).expect("the world is kept");
    assert_eq!(status, 201, "{}", String::from_utf8_lossy(&body));
    let answer: serde_json::Value = serde_json::from_slice(&body).unwrap();
    let id = answer["id"].as_str().unwrap().to_owned();
    let world_dir = cache.join("worlds").join(sylva_server::GENERATOR).join(&id);

    // Ask for the root (seconds of hero trees, then shared.bin, then the atlases) and kill
    // the server once it is writing.
    let asking = std::thread::spawn(move || {
        request(address, "GET", &format!("/worlds/{id}/tileset.json"), "")
    });
    let began = Instant::now();
    let writing = loop {
        let partial = files(&world_dir)
            .iter()
            .any(|f| f.to_string_lossy().contains("sylva-partial"));
        if partial || began.elapsed() > Duration::from_secs(300) {
            break partial;
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    server.kill().unwrap();
    server.wait().unwrap();
    assert!(writing, "the server never began writing the root");
    assert!(
        asking.join().unwrap().is_none(),
        "the request was answered before the kill"
    );

    // Whatever the cache holds under a served name is whole: the batch writer's bytes.
    let left = files(&world_dir);
    println!(
        "killed after {:.1} s; the cache held {left:?}",
        began.elapsed().as_secs_f64()
    );
    for f in left {
        if !f.to_string_lossy().contains("sylva-partial") {
            assert_eq!(
                std::fs::read(world_dir.join(&f)).unwrap(),
                std::fs::read(batch.join(&f)).unwrap(),
                "{} is torn",
                f.display()
            );
        }
    }

    // Started again on the same cache, it serves the world whole.
    let (mut again, address) = start(&cache);
    let id = answer["id"].as_str().unwrap();
    for file in [
        "tileset.json",
        "shared.bin",
        "impostors/variant_0.png",
        "tiles/f_2_3.glb",
        "tiles/c_0_0.glb",
    ] {
        let (status, body) =
            request(address, "GET", &format!("/worlds/{id}/{file}"), "").expect("an answer");
        assert_eq!(status, 200, "{file}: {}", String::from_utf8_lossy(&body));
        assert_eq!(
            body,
            std::fs::read(batch.join(file)).unwrap(),
            "{file} differs from sylva tiles'"
        );
    }
    again.kill().unwrap();
    again.wait().unwrap();
    let _ = std::fs::remove_dir_all(&cache);
    let _ = std::fs::remove_dir_all(&batch);
}
