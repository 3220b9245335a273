//! What the server answers when it cannot give what was asked: a status and a JSON body
//! `{"error": CODE, "message": TEXT}` saying what was wrong, never a bare 500.

use std::io;

use axum::Json;
use axum::http::{HeaderValue, StatusCode, header};
use axum::response::{IntoResponse, Response};
use serde_json::json;

/// An error response.
///
/// ```
/// use sylva_server::ApiError;
/// let e = ApiError::bad_request("bad_seed", "seed 'x': expected a whole number");
/// assert_eq!(e.status.as_u16(), 400);
/// ```
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{status}: {code}: {message}")]
pub struct ApiError {
    /// The HTTP status.
    pub status: StatusCode,
    /// A short machine-readable cause (`bad_description`, `unknown_tile`, `busy`, ...).
    pub code: &'static str,
    /// What was wrong, for a person.
    pub message: String,
    /// For 503: seconds after which to try again.
    pub retry_after: Option<u32>,
}

impl ApiError {
    fn new(status: StatusCode, code: &'static str, message: impl Into<String>) -> ApiError {
        ApiError {
            status,
            code,
            message: message.into(),
            retry_after: None,
        }
    }

    /// 400: the request is malformed or a value is out of range.
    pub fn bad_request(code: &'static str, message: impl Into<String>) -> ApiError {
        Self::new(StatusCode::BAD_REQUEST, code, message)
    }

    /// 404: no such world, tile, species or file.
    pub fn not_found(code: &'static str, message: impl Into<String>) -> ApiError {
        Self::new(StatusCode::NOT_FOUND, code, message)
    }

    /// 413: a body over its limit.
    pub fn too_large(message: impl Into<String>) -> ApiError {
        Self::new(StatusCode::PAYLOAD_TOO_LARGE, "too_large", message)
    }

    /// 422: a well-formed world whose trees or terrain cannot be made (a species whose
    /// grammar draws nothing, a budget too small for its trees).
    pub fn unprocessable(message: impl Into<String>) -> ApiError {
        Self::new(StatusCode::UNPROCESSABLE_ENTITY, "cannot_generate", message)
    }

    /// 503 with `Retry-After`: the server is busy, or its cache disk is full.
    pub fn unavailable(code: &'static str, message: impl Into<String>, retry: u32) -> ApiError {
        let mut e = Self::new(StatusCode::SERVICE_UNAVAILABLE, code, message);
        e.retry_after = Some(retry);
        e
    }

    /// 500: the server's own failure (a cache file it could not read).
    pub fn internal(message: impl Into<String>) -> ApiError {
        Self::new(StatusCode::INTERNAL_SERVER_ERROR, "internal", message)
    }

    /// The answer to a failed write into the cache: 503 when the disk is full (the cache
    /// stays readable, a later try may find room), else 500.
    pub fn storage(e: &io::Error, what: &str) -> ApiError {
        if is_disk_full(e) {
            Self::unavailable(
                "cache_full",
                format!("the cache disk is full: {what} could not be stored"),
                60,
            )
        } else {
            Self::internal(format!("{what}: {e}"))
        }
    }

    /// A generation's failure: a full disk anywhere in its causes is a 503, another I/O
    /// error the server's own (500), anything else the world's (422).
    pub fn generation(e: &(dyn std::error::Error + 'static), what: &str) -> ApiError {
        let mut cause = Some(e);
        while let Some(c) = cause {
            if let Some(io) = c.downcast_ref::<io::Error>() {
                return Self::storage(io, what);
            }
            if let Some(file) = c.downcast_ref::<sylva::base::file::FileError>() {
                return Self::storage(&file.source, what);
            }
            cause = c.source();
        }
        Self::unprocessable(format!("{what}: {e}"))
    }
}

impl From<sylva::world::WorldError> for ApiError {
    /// A world's mistake in what was asked is a 400 (413 for a size), with the world
    /// layer's code; a failure to make it goes as any generation's.
    fn from(e: sylva::world::WorldError) -> ApiError {
        if e.code() == "too_large" {
            ApiError::too_large(e.to_string())
        } else if e.is_user_mistake() {
            ApiError::bad_request(e.code(), e.to_string())
        } else {
            ApiError::generation(&e, "the world")
        }
    }
}

/// Whether an I/O error is a full disk or an exhausted quota.
fn is_disk_full(e: &io::Error) -> bool {
    // ENOSPC and EDQUOT on Linux.
    e.kind() == io::ErrorKind::StorageFull || matches!(e.raw_os_error(), Some(28 | 122))
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        let body = Json(json!({"error": self.code, "message": self.message}));
        let mut response = (self.status, body).into_response();
        if let Some(seconds) = self.retry_after {
            response
                .headers_mut()
                .insert(header::RETRY_AFTER, HeaderValue::from(seconds));
        }
        response
    }
}
