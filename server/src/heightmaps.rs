//! `POST /heightmaps`: a user's elevation model (GeoTIFF, SRTM .hgt, ESRI ASCII grid or 16-bit
//! PNG, of any size), kept under the SHA-256 of its bytes for
//! worlds to stand on (`"terrain": {"heightmap": {"id": ...}}`).

use std::sync::Arc;

use axum::Json;
use axum::extract::{Request, State};
use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use serde_json::json;
use sylva::world::limits::MAX_MODEL_BYTES;
use sylva::world::{check_model, model_id};

use crate::cache::write_whole;
use crate::error::ApiError;
use crate::state::Server;

/// `POST /heightmaps`: answers `{"id": ...}` (201).
pub(crate) async fn upload(
    State(server): State<Arc<Server>>,
    request: Request,
) -> Result<Response, ApiError> {
    let body = crate::body::read(request, MAX_MODEL_BYTES).await?;
    let id = model_id(&body);
    let path = server.cache.heightmap_path(&id);
    if !tokio::fs::try_exists(&path).await.unwrap_or(false) {
        let key = format!("heightmap/{id}");
        server
            .jobs
            .run(&key, move || {
                check_model(&body)?;
                write_whole(&path, &body).map_err(|e| ApiError::storage(&e, "the heightmap"))
            })
            .await?;
    }
    Ok((StatusCode::CREATED, Json(json!({"id": id.as_str()}))).into_response())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The upload check is the world layer's: a vast PNG is refused from its header.
    #[test]
    fn vast_and_foreign_files_are_refused_before_decoding() {
        let mut png = b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR".to_vec();
        png.extend_from_slice(&100_000u32.to_be_bytes());
        png.extend_from_slice(&100_000u32.to_be_bytes());
        let e = ApiError::from(check_model(&png).unwrap_err());
        assert!(e.message.contains("100000 x 100000"), "{}", e.message);
        assert_eq!((e.status.as_u16(), e.code), (400, "bad_heightmap"));
        let mut good = Vec::new();
        sylva::presets::terrain(1, 100.0)
            .unwrap()
            .write_png16(&mut good)
            .unwrap();
        check_model(&good).unwrap();
    }
}
