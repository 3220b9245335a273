//! `POST /heightmaps`: a user's elevation model (GeoTIFF, SRTM .hgt, ESRI ASCII grid or 16-bit
//! PNG, of any size), kept under the SHA-256 of its bytes for
//! worlds to stand on (`"terrain": {"heightmap": {"id": ...}}`).

use std::sync::Arc;

use axum::Json;
use axum::extract::{Request, State};
use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use serde_json::json;
use sha2::{Digest, Sha256};
use sylva::terrain::dem::{ElevationModel, ReadOptions};

use crate::cache::write_whole;
use crate::error::ApiError;
use crate::ground::model_format;
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

/// Checks an upload: an elevation model (GeoTIFF, SRTM .hgt, ESRI ASCII grid or 16-bit PNG)
/// no larger than [`MAX_HEIGHTMAP_SIDE`] a side that decodes whole. Blocking (decoding).
fn check(bytes: &[u8]) -> Result<(), ApiError> {
    let bad = |m: String| ApiError::bad_request("bad_heightmap", m);
    let format = model_format(bytes).ok_or_else(|| {
        bad(
            "a heightmap is a GeoTIFF, an SRTM .hgt, an ESRI ASCII grid or a 16-bit grayscale PNG"
                .into(),
        )
    })?;
    if let Some((w, h)) = png_size(bytes)
        && (w > MAX_HEIGHTMAP_SIDE || h > MAX_HEIGHTMAP_SIDE)
    {
        return Err(bad(format!(
            "a {w} x {h} heightmap is larger than {MAX_HEIGHTMAP_SIDE} a side"
        )));
    }
    // A stand-in range for 16-bit samples proves they decode; a world's own comes from the
    // file or its description.
    let options = ReadOptions::default().with_height_range(0.0, 1.0);
    let model = ElevationModel::parse(bytes, format, &options)
        .map_err(|e| bad(format!("the heightmap: {e}")))?;
    let side = model.width.max(model.height);
    if side > MAX_HEIGHTMAP_SIDE as usize {
        return Err(bad(format!(
            "a {} x {} heightmap is larger than {MAX_HEIGHTMAP_SIDE} a side",
            model.width, model.height
        )));
    }
    Ok(())
}

/// The id of an elevation model's bytes: the one `POST /heightmaps` answers for them (the
/// first 128 bits of their SHA-256).
///
/// ```
/// let id = sylva_server::project::model_id(b"not really a model");
/// assert_eq!(id.as_str().len(), 32);
/// ```
pub fn model_id(bytes: &[u8]) -> WorldId {
    WorldId::of(&Sha256::digest(bytes))
}

/// `POST /heightmaps`: answers `{"id": ...}` (201).
pub(crate) async fn upload(
    State(server): State<Arc<Server>>,
    request: Request,
) -> Result<Response, ApiError> {
    let body = crate::body::read(request, MAX_HEIGHTMAP_BYTES).await?;
    let id = model_id(&body);
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
        let asc = b"ncols 3\nnrows 2\ncellsize 10\n1 2 3\n4 5 6\n";
        check(asc).unwrap();
        assert_eq!(check(b"GIF89a").unwrap_err().code, "bad_heightmap");
        let mut good = Vec::new();
        sylva::presets::terrain(1, 100.0)
            .unwrap()
            .write_png16(&mut good)
            .unwrap();
        check(&good).unwrap();
    }
}
