//! Worlds served on demand: the Garden of Eden thesis's tree API (7.1.3) and stored
//! generation (7.1.1) as an HTTP server. A client posts a world's description and gets its
//! id, the hash of the description's canonical form; the world's 3D Tiles (the same bytes
//! `sylva tiles` writes) are generated on first request, kept in a cache folder and served
//! with `ETag`, `Cache-Control: immutable` and byte ranges.
//!
//! | request | answer |
//! |---|---|
//! | `POST /worlds` (a [`WorldDescription`] as JSON) | `201 {"id", "tileset", "page", "notes"}` |
//! | `GET /worlds/{id}` | the kept description |
//! | `GET /worlds/{id}/tileset.json`, `/shared.bin`, `/impostors/variant_K.png` | the world's root |
//! | `GET /worlds/{id}/tiles/{c_X_Y,f_X_Y}.glb` | a tile |
//! | `POST /heightmaps` (an elevation model: GeoTIFF, SRTM .hgt, ESRI ASCII grid or 16-bit PNG) | `201 {"id"}`, for `"terrain": {"heightmap": {"id": ...}}` |
//! | `GET /trees/{species}.glb?seed=S&age=A` | one tree of a bundled species |
//! | `GET /` | a page that opens a world in three.js and walks it |
//! | `GET /status` | the queue and memory |
//!
//! Work is bounded: generations run on a fixed number of workers behind a queue with a limit
//! (503 with `Retry-After` beyond it), a request waits a bounded time for its generation,
//! bodies and worlds have size limits, and every mistake is a 4xx with a JSON body saying
//! what was wrong.
//!
//! ```no_run
//! # async fn run() -> Result<(), Box<dyn std::error::Error>> {
//! use sylva_server::{ServerOptions, serve};
//! let options = ServerOptions::default().with_cache("/var/cache/sylva");
//! let listener = tokio::net::TcpListener::bind(options.address).await?;
//! serve(listener, options, std::future::pending()).await?;
//! # Ok(()) }
//! ```

mod body;
mod cache;
mod connections;
mod error;
mod files;
mod heightmaps;
mod jobs;
mod page;
mod state;
mod trees;
mod world;
mod worlds;

use std::future::Future;
use std::sync::Arc;
use std::sync::atomic::Ordering;

use axum::Router;
use axum::extract::{Request, State};
use axum::middleware::{self, Next};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};

pub use body::BODY_TIMEOUT;
pub use cache::{Cache, GENERATOR};
pub use error::ApiError;
// The description a client posts is the world layer's; named here for the server's users.
pub use state::{Server, ServerOptions};
pub use sylva::world::{SpeciesEntry, TerrainDescription, WorldDescription, WorldId};
pub use trees::MAX_AGE;

/// The server's routes over `server`'s state.
pub fn router(server: Arc<Server>) -> Router {
    Router::new()
        .route("/", get(page::page))
        .route("/status", get(page::status))
        .route("/modules/{*path}", get(page::module))
        .route("/worlds", post(worlds::create))
        .route("/worlds/{id}", get(worlds::description))
        .route("/worlds/{id}/tileset.json", get(worlds::tileset))
        .route("/worlds/{id}/shared.bin", get(worlds::shared))
        .route("/worlds/{id}/impostors/{file}", get(worlds::impostor))
        .route("/worlds/{id}/tiles/{tile}", get(worlds::tile))
        .route("/heightmaps", post(heightmaps::upload))
        .route("/trees/{species}", get(trees::tree))
        .fallback(unknown_route)
        .layer(middleware::from_fn_with_state(server.clone(), admit))
        .with_state(server)
}

/// Anything else: a 404 in JSON.
async fn unknown_route() -> ApiError {
    ApiError::not_found(
        "unknown_route",
        "no such endpoint: see GET / and the crate's docs",
    )
}

/// Admits a request unless [`ServerOptions::max_requests`] are in progress (503 `busy`).
async fn admit(State(server): State<Arc<Server>>, request: Request, next: Next) -> Response {
    let before = server.requests.fetch_add(1, Ordering::Relaxed);
    // Counted down when the answer is made or the client goes away.
    let _leave = Leave(&server);
    if before >= server.options.max_requests {
        return ApiError::unavailable(
            "busy",
            format!("{before} requests are in progress, the limit: try again shortly"),
            1,
        )
        .into_response();
    }
    next.run(request).await
}

/// Counts a request out when dropped.
struct Leave<'a>(&'a Server);

impl Drop for Leave<'_> {
    fn drop(&mut self) {
        self.0.requests.fetch_sub(1, Ordering::Relaxed);
    }
}

/// Serves on `listener` until `shutdown` completes, then finishes the requests in progress.
pub async fn serve(
    listener: tokio::net::TcpListener,
    options: ServerOptions,
    shutdown: impl Future<Output = ()> + Send + 'static,
) -> Result<(), ApiError> {
    let (max_connections, header_timeout) = (options.max_connections, options.header_timeout);
    let server = Server::new(options)?;
    connections::serve(
        listener,
        router(server),
        max_connections,
        header_timeout,
        shutdown,
    )
    .await;
    Ok(())
}
