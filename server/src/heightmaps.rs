//! `POST /heightmaps`: a user's 16-bit PNG heightmap, kept under the SHA-256 of its bytes for
//! worlds to stand on (`"terrain": {"heightmap": {"id": ...}}`).

use std::sync::Arc;

use axum::Json;
use axum::extract::{Request, State};
use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use serde_json::json;
use sha2::{Digest, Sha256};
use sylva::terrain::{HeightRange, Heightmap};

use crate::cache::write_whole;
use crate::error::ApiError;
use crate::id::WorldId;
use crate::state::Server;

/// Most bytes an upload may have.
pub const MAX_HEIGHTMAP_BYTES: usize = 64 << 20;
/// Most samples along a side of an uploaded heightmap.
pub const MAX_HEIGHTMAP_SIDE: u32 = 4097;

/// The width and height a PNG's header claims, read before anything is decoded, so a file
/// claiming a vast image is refused before memory is spent on it.
fn png_size(bytes: &[u8]) -> Option<(u32, u32)> {
    if bytes.len() < 24 || &bytes[..8] != b"\x89PNG\r\n\x1a\n" || &bytes[12..16] != b"IHDR" {
        return None;
    }
    let word =
        |at: usize| u32::from_be_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]);
    Some((word(16), word(20)))
}

/// Checks an upload: a PNG no larger than [`MAX_HEIGHTMAP_SIDE`] a side that decodes as a
/// 16-bit heightmap. Blocking (decoding).
fn check(bytes: &[u8]) -> Result<(), ApiError> {
    let (w, h) = png_size(bytes).ok_or_else(|| {
        ApiError::bad_request("bad_heightmap", "a heightmap is a 16-bit grayscale PNG")
    })?;
    if w > MAX_HEIGHTMAP_SIDE || h > MAX_HEIGHTMAP_SIDE {
        return Err(ApiError::bad_request(
            "bad_heightmap",
            format!("a {w} x {h} heightmap is larger than {MAX_HEIGHTMAP_SIDE} a side"),
        ));
    }
    // Decoding with a stand-in range and spacing proves the samples are whole; a world's
    // own come from the file's sylva chunk or its description.
    let stand_in = Some((HeightRange { min: 0.0, max: 1.0 }, 1.0));
    Heightmap::read_png16(std::io::Cursor::new(bytes), stand_in)
        .map_err(|e| ApiError::bad_request("bad_heightmap", format!("the heightmap: {e}")))?;
    Ok(())
}

/// `POST /heightmaps`: answers `{"id": ...}` (201).
pub(crate) async fn upload(
    State(server): State<Arc<Server>>,
    request: Request,
) -> Result<Response, ApiError> {
    let body = crate::body::read(request, MAX_HEIGHTMAP_BYTES).await?;
    let id = WorldId::of(&Sha256::digest(&body));
    let path = server.cache.heightmap_path(&id);
    if !tokio::fs::try_exists(&path).await.unwrap_or(false) {
        let key = format!("heightmap/{id}");
        server
            .jobs
            .run(&key, move || {
                check(&body)?;
                write_whole(&path, &body).map_err(|e| ApiError::storage(&e, "the heightmap"))
            })
            .await?;
    }
    Ok((StatusCode::CREATED, Json(json!({"id": id.as_str()}))).into_response())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vast_and_foreign_files_are_refused_before_decoding() {
        let mut png = b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR".to_vec();
        png.extend_from_slice(&100_000u32.to_be_bytes());
        png.extend_from_slice(&100_000u32.to_be_bytes());
        let e = check(&png).unwrap_err();
        assert!(e.message.contains("100000 x 100000"), "{}", e.message);
        assert_eq!(check(b"GIF89a").unwrap_err().code, "bad_heightmap");
        let mut good = Vec::new();
        sylva::presets::terrain(1, 100.0)
            .unwrap()
            .write_png16(&mut good)
            .unwrap();
        check(&good).unwrap();
    }
}
