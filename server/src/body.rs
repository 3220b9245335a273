//! Request bodies read within limits: a declared length over the limit is refused from the
//! head (413, nothing read), a body that grows past it is cut off (413), and one that trickles
//! in slower than [`BODY_TIMEOUT`] is dropped (408).

use std::time::Duration;

use axum::body::Bytes;
use axum::extract::Request;
use axum::http::{StatusCode, header};

use crate::error::ApiError;

/// Longest a client may take to send a body.
pub const BODY_TIMEOUT: Duration = Duration::from_secs(60);

/// Reads `request`'s body, at most `limit` bytes.
pub(crate) async fn read(request: Request, limit: usize) -> Result<Bytes, ApiError> {
    let declared = request
        .headers()
        .get(header::CONTENT_LENGTH)
        .and_then(|v| v.to_str().ok())
        .and_then(|v| v.parse::<u64>().ok());
    if let Some(n) = declared.filter(|&n| n > limit as u64) {
        return Err(ApiError::too_large(format!(
            "a body of {n} bytes is over this endpoint's limit of {limit}"
        )));
    }
    match tokio::time::timeout(
        BODY_TIMEOUT,
        axum::body::to_bytes(request.into_body(), limit),
    )
    .await
    {
        Ok(Ok(bytes)) => Ok(bytes),
        Ok(Err(_)) => Err(ApiError::too_large(format!(
            "the body is over this endpoint's limit of {limit} bytes, or was cut off"
        ))),
        Err(_) => Err(ApiError {
            status: StatusCode::REQUEST_TIMEOUT,
            code: "slow_body",
            message: format!(
                "the body took more than {} s to arrive",
                BODY_TIMEOUT.as_secs()
            ),
            retry_after: None,
        }),
    }
}
