//! Heights as images: 16-bit grayscale PNG and little-endian 16-bit RAW, of any width and
//! height. Their samples stand for heights over a range: sylva's own PNGs carry it (with the
//! spacing) in a `sylva:heights` chunk; other files need it given.

use super::{ElevationModel, ReadOptions, check_size};
use crate::error::TerrainError;

/// Heights of `q` over `[low, high]`.
fn height(q: u16, [low, high]: [f32; 2]) -> f32 {
    (f64::from(low) + f64::from(q) / 65535.0 * (f64::from(high) - f64::from(low))) as f32
}

fn check_range([low, high]: [f32; 2]) -> Result<(), TerrainError> {
    crate::error::check(
        "height range",
        f64::from(high - low),
        low.is_finite() && high.is_finite() && high > low,
        "low < high, both finite",
    )
}

pub(super) fn read_png16(
    bytes: &[u8],
    range: Option<[f32; 2]>,
) -> Result<ElevationModel, TerrainError> {
    let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    let mut reader = decoder.read_info()?;
    let info = reader.info();
    if info.color_type != png::ColorType::Grayscale || info.bit_depth != png::BitDepth::Sixteen {
        return Err(TerrainError::NotGrayscale16 {
            channels: info.color_type.samples() as u8,
            bits: info.bit_depth as u8,
        });
    }
    let (width, height_rows) = check_size(u64::from(info.width), u64::from(info.height))?;
    let stored: Option<([f32; 2], f32)> = info
        .uncompressed_latin1_text
        .iter()
        .find(|t| t.keyword == "sylva:heights")
        .and_then(|t| {
            let v: Vec<f32> = t
                .text
                .split_whitespace()
                .filter_map(|s| s.parse().ok())
                .collect();
            (v.len() == 3).then(|| ([v[0], v[1]], v[2]))
        });
    let range = stored
        .map(|s| s.0)
        .or(range)
        .ok_or(TerrainError::NoHeightRange)?;
    check_range(range)?;
    let mut buf = vec![
        0u8;
        reader
            .output_buffer_size()
            .ok_or(TerrainError::BadSize(width))?
    ];
    reader.next_frame(&mut buf)?;
    let heights = buf[..width * height_rows * 2]
        .chunks_exact(2)
        .map(|b| height(u16::from_be_bytes([b[0], b[1]]), range))
        .collect();
    let spacing = stored.map(|s| s.1);
    Ok(ElevationModel {
        width,
        height: height_rows,
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
    let range = options.height_range.ok_or(TerrainError::NoHeightRange)?;
    check_range(range)?;
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
        .map(|b| height(u16::from_le_bytes([b[0], b[1]]), range))
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
