//! `GET /`: the page that opens a world in the browser; `GET /modules/...`: the npm packages
//! it imports (three.js and 3d-tiles-renderer), from the folder the server was given; and
//! `GET /status`: the queue and memory at a glance.

use std::path::{Component, PathBuf};
use std::sync::Arc;
use std::sync::atomic::Ordering;

use axum::Json;
use axum::extract::{Path, State};
use axum::http::{HeaderMap, HeaderValue, header};
use axum::response::{Html, IntoResponse, Response};
use serde_json::json;

use crate::cache::GENERATOR;
use crate::error::ApiError;
use crate::files;
use crate::state::Server;

/// The packages the page imports, the only ones `/modules/` serves.
const PACKAGES: [&str; 2] = ["three", "3d-tiles-renderer"];

/// Whether `dir` holds both packages.
fn has_modules(dir: &std::path::Path) -> bool {
    PACKAGES
        .iter()
        .all(|p| dir.join(p).join("package.json").is_file())
}

/// `GET /`.
pub(crate) async fn page(State(server): State<Arc<Server>>) -> Response {
    let modules = server
        .options
        .web_modules
        .as_deref()
        .is_some_and(has_modules);
    let html = include_str!("page.html")
        .replace("__SYLVA_MODULES__", if modules { "true" } else { "false" });
    let mut r = Html(html).into_response();
    r.headers_mut()
        .insert(header::CACHE_CONTROL, HeaderValue::from_static("no-cache"));
    r
}

/// `GET /modules/{*path}`: a file of one of [`PACKAGES`], never outside it.
pub(crate) async fn module(
    State(server): State<Arc<Server>>,
    Path(path): Path<String>,
    headers: HeaderMap,
) -> Result<Response, ApiError> {
    let missing = || ApiError::not_found("unknown_file", "no such module file");
    let base = server.options.web_modules.clone().ok_or_else(missing)?;
    let relative = PathBuf::from(&path);
    let plain = relative
        .components()
        .all(|c| matches!(c, Component::Normal(_)));
    let package = relative
        .components()
        .next()
        .and_then(|c| c.as_os_str().to_str());
    let allowed = relative
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| matches!(e, "js" | "mjs" | "json" | "wasm"));
    if !plain || !package.is_some_and(|p| PACKAGES.contains(&p)) || !allowed {
        return Err(missing());
    }
    let file = base.join(&relative);
    if !tokio::fs::metadata(&file).await.is_ok_and(|m| m.is_file()) {
        return Err(missing());
    }
    let mut r = files::send(&file, &format!("\"{GENERATOR}-module\""), &headers).await?;
    // The packages can change under the folder: clients check again rather than keep them.
    r.headers_mut()
        .insert(header::CACHE_CONTROL, HeaderValue::from_static("no-cache"));
    Ok(r)
}

/// `GET /status`.
pub(crate) async fn status(State(server): State<Arc<Server>>) -> Json<serde_json::Value> {
    Json(json!({
        "generator": GENERATOR,
        "generations_queued": server.jobs.queued(),
        "worlds_in_memory": server.worlds.len(),
        "tree_bytes": server.trees.bytes(),
        "requests": server.requests.load(Ordering::Relaxed),
    }))
}
