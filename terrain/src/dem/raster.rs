//! Heights as images: 16-bit grayscale PNG and little-endian 16-bit RAW, of any width and
//! height. Their samples stand for heights over a range: sylva's own PNGs carry it (with the
//! spacing) in a `sylva:heights` chunk; other files need it given.

use super::{ElevationModel, ReadOptions, check_size};
use crate::error::TerrainError;
use crate::io::{HeightRange, decode_png16};

/// The range that samples 0 and 65535 stand for, checked.
fn range_of([min, max]: [f32; 2]) -> Result<HeightRange, TerrainError> {
    let range = HeightRange { min, max };
    range.validate()?;
    Ok(range)
}

/// A 16-bit grayscale PNG of any size; the range (and spacing) from sylva's chunk, else
/// `range`.
pub(super) fn read_png16(
    bytes: &[u8],
    range: Option<[f32; 2]>,
) -> Result<ElevationModel, TerrainError> {
    let png = decode_png16(std::io::Cursor::new(bytes), |w, h| {
        check_size(u64::from(w), u64::from(h)).map(|_| ())
    })?;
    let range = match png.stored {
        Some((stored, _)) => {
            stored.validate()?;
            stored
        }
        None => range_of(range.ok_or(TerrainError::NoHeightRange)?)?,
    };
    let heights = png.samples.iter().map(|&q| range.dequantize(q)).collect();
    let spacing = png.stored.map(|s| s.1);
    Ok(ElevationModel {
        width: png.width,
        height: png.height,
        heights,
        spacing: [spacing.unwrap_or(1.0); 2],
        nodata: 0,
        georeference: None,
        spacing_from_file: spacing.is_some(),
    })
}

pub(super) fn read_raw16(
    bytes: &[u8],
    options: &ReadOptions,
) -> Result<ElevationModel, TerrainError> {
    let range = range_of(options.height_range.ok_or(TerrainError::NoHeightRange)?)?;
    if !bytes.len().is_multiple_of(2) {
        return Err(TerrainError::PartialSample {
            bytes: bytes.len(),
            sample_bytes: 2,
        });
    }
    let samples = bytes.len() / 2;
    let [w, h] = match options.raw_size {
        Some(size) => size,
        None => {
            let side = (samples as f64).sqrt().round() as usize;
            if side * side != samples {
                return Err(TerrainError::NotSquareSamples { samples });
            }
            [side, side]
        }
    };
    let (width, height_rows) = check_size(w as u64, h as u64)?;
    if width * height_rows != samples {
        return Err(TerrainError::Dem {
            format: "RAW",
            message: format!("{samples} samples for a {width} x {height_rows} grid"),
        });
    }
    let heights = bytes
        .chunks_exact(2)
        .map(|b| range.dequantize(u16::from_le_bytes([b[0], b[1]])))
        .collect();
    Ok(ElevationModel {
        width,
        height: height_rows,
        heights,
        spacing: [options.spacing.unwrap_or(1.0); 2],
        nodata: 0,
        georeference: None,
        spacing_from_file: false,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn raw_of_any_size() {
        let bytes: Vec<u8> = (0..6u16).flat_map(|q| (q * 13107).to_le_bytes()).collect();
        let options = ReadOptions::default()
            .with_height_range(0.0, 100.0)
            .with_raw_size(3, 2)
            .with_spacing(5.0);
        let m = read_raw16(&bytes, &options).unwrap();
        assert_eq!((m.width, m.height), (3, 2));
        assert!((m.heights[5] - 100.0).abs() < 1e-3 && (m.heights[1] - 20.0).abs() < 1e-3);
        assert!(read_raw16(&bytes, &options.with_raw_size(4, 2)).is_err());
        assert!(read_raw16(&bytes, &ReadOptions::default()).is_err());
    }
}
