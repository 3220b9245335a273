//! What the server's tests share: a server on a loopback port with a scratch cache, and a
//! client holding one keep-alive HTTP/1.1 connection (hyper's own client API).

#![allow(dead_code, reason = "each test file uses its own part")]
#![allow(missing_docs, reason = "test support")]

use std::net::SocketAddr;
use std::path::PathBuf;
use std::time::Duration;

use http_body_util::{BodyExt, Full};
use hyper::body::Bytes;
use hyper::client::conn::http1::SendRequest;
use hyper::{HeaderMap, Method, Request, StatusCode};
use hyper_util::rt::TokioIo;
use sylva_server::{ServerOptions, serve};

/// A small world that builds in about a second: one species, 200 m in 50 m tiles.
pub(crate) const SMALL_WORLD: &str = r#"{"area": 200, "tile_size": 50, "group": 2, "budget_mb": 4, "species": ["birch"], "seed": 5}"#;

/// A running server.
pub(crate) struct Running {
    pub(crate) address: SocketAddr,
    pub(crate) cache: PathBuf,
    stop: Option<tokio::sync::oneshot::Sender<()>>,
    task: Option<tokio::task::JoinHandle<()>>,
}

impl Running {
    /// Stops the server, waits for it, and removes its scratch cache (a load test's is
    /// about 100 MB; left behind, runs fill the disk).
    pub(crate) async fn stop(mut self) {
        if let Some(s) = self.stop.take() {
            let _ = s.send(());
        }
        if let Some(t) = self.task.take() {
            let _ = t.await;
        }
        let _ = std::fs::remove_dir_all(&self.cache);
    }
}

/// A scratch cache folder of this name, emptied.
pub(crate) fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("sylva-server-test-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// Starts a server on 127.0.0.1 (any free port) with `options` (its address ignored).
pub(crate) async fn start(options: ServerOptions) -> Running {
    let listener = tokio::net::TcpListener::bind("127.0.0.1:0").await.unwrap();
    let address = listener.local_addr().unwrap();
    let (stop, stopped) = tokio::sync::oneshot::channel::<()>();
    let cache = options.cache.clone();
    let task = tokio::spawn(async move {
        serve(listener, options, async move {
            let _ = stopped.await;
        })
        .await
        .unwrap();
    });
    Running {
        address,
        cache,
        stop: Some(stop),
        task: Some(task),
    }
}

/// An answer.
#[derive(Debug)]
pub(crate) struct Answer {
    pub(crate) status: StatusCode,
    pub(crate) headers: HeaderMap,
    pub(crate) body: Vec<u8>,
}

impl Answer {
    /// The body as JSON.
    pub(crate) fn json(&self) -> serde_json::Value {
        serde_json::from_slice(&self.body).unwrap_or_else(|e| {
            panic!(
                "{}: not JSON ({e}): {}",
                self.status,
                String::from_utf8_lossy(&self.body)
            )
        })
    }
}

/// One keep-alive connection.
pub(crate) struct Client {
    sender: SendRequest<Full<Bytes>>,
    address: SocketAddr,
}

impl Client {
    /// Connects to `address`.
    pub(crate) async fn connect(address: SocketAddr) -> Client {
        let stream = tokio::net::TcpStream::connect(address).await.unwrap();
        let (sender, connection) = hyper::client::conn::http1::handshake(TokioIo::new(stream))
            .await
            .unwrap();
        tokio::spawn(async move {
            let _ = connection.await;
        });
        Client { sender, address }
    }

    /// Sends a request and reads the whole answer.
    pub(crate) async fn send(
        &mut self,
        method: Method,
        path: &str,
        headers: &[(&str, &str)],
        body: Vec<u8>,
    ) -> Result<Answer, String> {
        let mut request = Request::builder()
            .method(method)
            .uri(path)
            .header("host", self.address.to_string());
        for (k, v) in headers {
            request = request.header(*k, *v);
        }
        let request = request
            .body(Full::new(Bytes::from(body)))
            .map_err(|e| e.to_string())?;
        self.sender.ready().await.map_err(|e| e.to_string())?;
        let response = self
            .sender
            .send_request(request)
            .await
            .map_err(|e| e.to_string())?;
        let (parts, body) = response.into_parts();
        let body = body
            .collect()
            .await
            .map_err(|e| e.to_string())?
            .to_bytes()
            .to_vec();
        Ok(Answer {
            status: parts.status,
            headers: parts.headers,
            body,
        })
    }

    /// `GET path`.
    pub(crate) async fn get(&mut self, path: &str) -> Answer {
        self.send(Method::GET, path, &[], Vec::new()).await.unwrap()
    }

    /// `POST path` with `body`.
    pub(crate) async fn post(&mut self, path: &str, body: &[u8]) -> Answer {
        self.send(Method::POST, path, &[], body.to_vec())
            .await
            .unwrap()
    }
}

/// Posts `description` and answers the world's id.
pub(crate) async fn world(address: SocketAddr, description: &str) -> String {
    let mut c = Client::connect(address).await;
    let a = c.post("/worlds", description.as_bytes()).await;
    assert_eq!(
        a.status,
        StatusCode::CREATED,
        "{}",
        String::from_utf8_lossy(&a.body)
    );
    a.json()["id"].as_str().unwrap().to_owned()
}

/// A 100 m world of one species given inline: its species file's text and its grammar's,
/// each with `\n` escaped as JSON wants.
pub(crate) fn inline_species_world(species: &str, grammar: &str) -> String {
    format!(
        r#"{{"area": 100, "tile_size": 50, "group": 2, "budget_mb": 2, "species": [{{"file": "{species}", "grammar": "{grammar}"}}]}}"#
    )
}

/// Options for a test server over `cache`.
pub(crate) fn options(cache: PathBuf) -> ServerOptions {
    ServerOptions::default()
        .with_cache(cache)
        .with_workers(2)
        .with_generation_timeout(Duration::from_secs(300))
}

/// The process's resident memory now and at its peak, MB (Linux; zeros elsewhere).
pub(crate) fn memory_mb() -> (f64, f64) {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    let field = |name: &str| {
        status
            .lines()
            .find(|l| l.starts_with(name))
            .and_then(|l| l.split_whitespace().nth(1))
            .and_then(|kb| kb.parse::<f64>().ok())
            .map_or(0.0, |kb| kb / 1024.0)
    };
    (field("VmRSS:"), field("VmHWM:"))
}

/// Open file descriptors of the process (Linux).
pub(crate) fn open_files() -> usize {
    std::fs::read_dir("/proc/self/fd").map_or(0, |d| d.count())
}
