//! An elevation model's bytes before they become ground: which format they are, and whether
//! they are a model a world may be given (an upload, a project's file), checked before
//! memory is spent decoding a file that claims a vast image.

use std::path::Path;

use sylva_terrain::dem::{DemFormat, ElevationModel, ReadOptions};

use crate::error::WorldError;
use crate::limits::{MAX_MODEL_BYTES, MAX_MODEL_SIDE};

/// The format of an elevation model's bytes, from its first bytes (or, for SRTM `.hgt`,
/// which has none, its length).
///
/// ```
/// use sylva_terrain::dem::DemFormat;
/// assert_eq!(sylva_world::model_format(b"ncols 4\nnrows 3\n"), Some(DemFormat::AsciiGrid));
/// assert_eq!(sylva_world::model_format(b"hello"), None);
/// ```
pub fn model_format(bytes: &[u8]) -> Option<DemFormat> {
    let hgt = [2 * 1201 * 1201, 2 * 3601 * 3601].contains(&bytes.len());
    DemFormat::of(Path::new(""), &bytes[..bytes.len().min(16)]).or(hgt.then_some(DemFormat::Hgt))
}

/// The width and height a PNG's header claims, read before anything is decoded.
fn png_size(bytes: &[u8]) -> Option<(u32, u32)> {
    if bytes.len() < 24 || &bytes[..8] != b"\x89PNG\r\n\x1a\n" || &bytes[12..16] != b"IHDR" {
        return None;
    }
    let word =
        |at: usize| u32::from_be_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]);
    Some((word(16), word(20)))
}

/// Checks a model a world may be given: at most [`MAX_MODEL_BYTES`], a GeoTIFF, an SRTM
/// .hgt, an ESRI ASCII grid or a 16-bit PNG of at most [`MAX_MODEL_SIDE`] samples a side that
/// decodes whole. Blocking (decoding).
///
/// ```
/// let asc = b"ncols 3\nnrows 2\ncellsize 30\n1 2 3\n4 5 6\n";
/// sylva_world::check_model(asc)?;
/// assert_eq!(sylva_world::check_model(b"GIF89a").unwrap_err().code(), "bad_heightmap");
/// # Ok::<(), sylva_world::WorldError>(())
/// ```
pub fn check_model(bytes: &[u8]) -> Result<(), WorldError> {
    let bad = |message: String| WorldError::Model {
        name: "the heightmap".into(),
        message,
    };
    if bytes.len() > MAX_MODEL_BYTES {
        return Err(WorldError::TooLarge(format!(
            "a heightmap of {} bytes is over the limit of {MAX_MODEL_BYTES}",
            bytes.len()
        )));
    }
    let format = model_format(bytes).ok_or_else(|| {
        bad(
            "a heightmap is a GeoTIFF, an SRTM .hgt, an ESRI ASCII grid or a 16-bit grayscale PNG"
                .into(),
        )
    })?;
    if let Some((w, h)) = png_size(bytes)
        && (w > MAX_MODEL_SIDE || h > MAX_MODEL_SIDE)
    {
        return Err(bad(format!(
            "a {w} x {h} heightmap is larger than {MAX_MODEL_SIDE} a side"
        )));
    }
    // A stand-in range for 16-bit samples proves they decode; a world's own comes from the
    // file or its description.
    let options = ReadOptions::default().with_height_range(0.0, 1.0);
    let model = ElevationModel::parse(bytes, format, &options).map_err(|e| bad(e.to_string()))?;
    let side = model.width.max(model.height);
    if side > MAX_MODEL_SIDE as usize {
        return Err(bad(format!(
            "a {} x {} heightmap is larger than {MAX_MODEL_SIDE} a side",
            model.width, model.height
        )));
    }
    Ok(())
}
