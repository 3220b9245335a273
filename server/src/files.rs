//! Sending a stored file: a strong `ETag`, `Cache-Control: immutable` (a file is a pure
//! function of its URL and the generator), `304` for a matching `If-None-Match`, and single
//! byte ranges (`206`, or `416` past the end), streamed from disk in small chunks.

use std::path::Path;

use axum::body::Body;
use axum::http::{HeaderMap, HeaderValue, StatusCode, header};
use axum::response::{IntoResponse, Response};
use tokio::io::{AsyncReadExt, AsyncSeekExt};
use tokio_util::io::ReaderStream;

use crate::error::ApiError;

/// How long clients and CDNs may keep a file: a year, the most `max-age` means in practice.
pub(crate) const IMMUTABLE: &str = "public, max-age=31536000, immutable";

/// The content type of a stored file, by its extension.
pub(crate) fn content_type(path: &Path) -> &'static str {
    match path.extension().and_then(|e| e.to_str()) {
        Some("json") => "application/json",
        Some("glb") => "model/gltf-binary",
        Some("png") => "image/png",
        Some("js" | "mjs") => "text/javascript",
        Some("html") => "text/html; charset=utf-8",
        _ => "application/octet-stream",
    }
}

/// A byte range asked for, resolved against a file of `len` bytes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Range {
    /// No usable `Range` header: the whole file.
    Whole,
    /// Bytes `start..=end`.
    Part { start: u64, end: u64 },
    /// A range wholly past the end.
    Unsatisfiable,
}

/// Reads a `Range` header. Only one range of bytes is served; a header this does not
/// understand (several ranges, another unit, bad syntax) is ignored, as HTTP allows, and the
/// whole file is sent.
pub(crate) fn range(header: Option<&str>, len: u64) -> Range {
    let Some(spec) = header.and_then(|h| h.trim().strip_prefix("bytes=")) else {
        return Range::Whole;
    };
    if spec.contains(',') {
        return Range::Whole;
    }
    let Some((a, b)) = spec.split_once('-') else {
        return Range::Whole;
    };
    let (a, b) = (a.trim(), b.trim());
    let parsed = match (a.is_empty(), b.is_empty()) {
        // bytes=-N: the last N bytes.
        (true, false) => match b.parse::<u64>() {
            Ok(0) => return Range::Unsatisfiable,
            Ok(n) => Some((len.saturating_sub(n), len.saturating_sub(1))),
            Err(_) => None,
        },
        (false, _) => match (a.parse::<u64>(), b.parse::<u64>()) {
            (Ok(s), _) if b.is_empty() => Some((s, len.saturating_sub(1))),
            (Ok(s), Ok(e)) if e >= s => Some((s, e.min(len.saturating_sub(1)))),
            _ => None,
        },
        (true, true) => None,
    };
    match parsed {
        None => Range::Whole,
        Some((start, _)) if start >= len => Range::Unsatisfiable,
        Some((start, end)) => Range::Part { start, end },
    }
}

/// Whether `If-None-Match` names `etag` (or is `*`).
pub(crate) fn matches(request: &HeaderMap, etag: &str) -> bool {
    request
        .get(header::IF_NONE_MATCH)
        .and_then(|v| v.to_str().ok())
        .is_some_and(|v| {
            v.split(',')
                .map(|t| t.trim().trim_start_matches("W/"))
                .any(|t| t == etag || t == "*")
        })
}

/// Answers `request` with the file at `path`, tagged `etag` (quoted).
pub(crate) async fn send(
    path: &Path,
    etag: &str,
    request: &HeaderMap,
) -> Result<Response, ApiError> {
    let tag = HeaderValue::from_str(etag).map_err(|e| ApiError::internal(e.to_string()))?;
    let mut headers = HeaderMap::new();
    headers.insert(header::ETAG, tag);
    headers.insert(header::CACHE_CONTROL, HeaderValue::from_static(IMMUTABLE));
    headers.insert(header::ACCEPT_RANGES, HeaderValue::from_static("bytes"));
    if matches(request, etag) {
        return Ok((StatusCode::NOT_MODIFIED, headers).into_response());
    }
    let unreadable = |e: std::io::Error| ApiError::internal(format!("{}: {e}", path.display()));
    let mut file = tokio::fs::File::open(path).await.map_err(unreadable)?;
    let len = file.metadata().await.map_err(unreadable)?.len();
    headers.insert(
        header::CONTENT_TYPE,
        HeaderValue::from_static(content_type(path)),
    );
    let asked = request.get(header::RANGE).and_then(|v| v.to_str().ok());
    let (status, start, count) = match range(asked, len) {
        Range::Whole => (StatusCode::OK, 0, len),
        Range::Part { start, end } => {
            let content_range = format!("bytes {start}-{end}/{len}");
            headers.insert(
                header::CONTENT_RANGE,
                HeaderValue::from_str(&content_range)
                    .map_err(|e| ApiError::internal(e.to_string()))?,
            );
            (StatusCode::PARTIAL_CONTENT, start, end - start + 1)
        }
        Range::Unsatisfiable => {
            let content_range = format!("bytes */{len}");
            headers.insert(
                header::CONTENT_RANGE,
                HeaderValue::from_str(&content_range)
                    .map_err(|e| ApiError::internal(e.to_string()))?,
            );
            return Ok((StatusCode::RANGE_NOT_SATISFIABLE, headers).into_response());
        }
    };
    headers.insert(header::CONTENT_LENGTH, HeaderValue::from(count));
    if start > 0 {
        file.seek(std::io::SeekFrom::Start(start))
            .await
            .map_err(unreadable)?;
    }
    let body = Body::from_stream(ReaderStream::with_capacity(file.take(count), 64 << 10));
    Ok((status, headers, body).into_response())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_resolve_against_the_length() {
        let r = |h: &str| range(Some(h), 100);
        assert_eq!(r("bytes=0-9"), Range::Part { start: 0, end: 9 });
        assert_eq!(r("bytes=90-"), Range::Part { start: 90, end: 99 });
        assert_eq!(r("bytes=-10"), Range::Part { start: 90, end: 99 });
        assert_eq!(r("bytes=-1000"), Range::Part { start: 0, end: 99 });
        assert_eq!(r("bytes=50-1000"), Range::Part { start: 50, end: 99 });
        assert_eq!(r("bytes=100-"), Range::Unsatisfiable);
        assert_eq!(r("bytes=-0"), Range::Unsatisfiable);
        for ignored in [
            "bytes=9-0",
            "bytes=0-1,5-6",
            "items=0-1",
            "bytes=x-y",
            "bytes=-",
            "bytes=99999999999999999999999-",
        ] {
            assert_eq!(r(ignored), Range::Whole, "{ignored}");
        }
        assert_eq!(range(None, 5), Range::Whole);
    }
}
