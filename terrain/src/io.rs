//! Heightmap import and export: 16-bit grayscale PNG, 16-bit and 32-bit little-endian RAW.
//!
//! 16-bit formats store heights quantised over a [`HeightRange`]; PNG files carry the range in
//! a `tEXt` chunk (keyword `sylva:heights`, text `min max spacing`), RAW files need it passed
//! back in. A 16-bit round trip is exact: importing and exporting again gives the same bytes.

use std::io::{BufRead, Seek, Write};

use crate::error::{TerrainError, check};
use crate::heightmap::{Heightmap, checked_len, levels_of};

/// The heights that 0 and 65535 stand for in 16-bit formats.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct HeightRange {
    /// Height of sample value 0.
    pub min: f32,
    /// Height of sample value 65535.
    pub max: f32,
}

const TEXT_KEY: &str = "sylva:heights";

impl HeightRange {
    pub(crate) fn validate(&self) -> Result<(), TerrainError> {
        check("range min", f64::from(self.min), true, "finite")?;
        check(
            "range max",
            f64::from(self.max),
            self.max > self.min,
            "finite and above min",
        )
    }

    fn quantize(&self, h: f32) -> u16 {
        let t = (f64::from(h) - f64::from(self.min)) / (f64::from(self.max) - f64::from(self.min));
        (t * 65535.0).round().clamp(0.0, 65535.0) as u16
    }

    pub(crate) fn dequantize(&self, q: u16) -> f32 {
        (f64::from(self.min) + f64::from(q) / 65535.0 * (f64::from(self.max) - f64::from(self.min)))
            as f32
    }
}

impl Heightmap {
    /// The range the map's heights span (widened by 1 when flat, so it is never empty).
    pub fn height_range(&self) -> HeightRange {
        let s = self.stats();
        HeightRange {
            min: s.min,
            max: if s.max > s.min { s.max } else { s.min + 1.0 },
        }
    }

    fn quantized(&self, range: &HeightRange) -> impl Iterator<Item = u16> + '_ {
        let r = *range;
        self.heights().iter().map(move |&h| r.quantize(h))
    }

    /// 16-bit little-endian RAW (Unity's terrain format), row-major, and the range used.
    pub fn to_raw16(&self) -> (Vec<u8>, HeightRange) {
        let range = self.height_range();
        let bytes = self.quantized(&range).flat_map(u16::to_le_bytes).collect();
        (bytes, range)
    }

    /// Reads 16-bit little-endian RAW of a (2^n + 1)-square map.
    pub fn from_raw16(
        bytes: &[u8],
        range: HeightRange,
        spacing: f32,
    ) -> Result<Heightmap, TerrainError> {
        range.validate()?;
        let size = square_side(bytes.len(), 2)?;
        let heights = bytes
            .chunks_exact(2)
            .map(|b| range.dequantize(u16::from_le_bytes([b[0], b[1]])))
            .collect();
        Heightmap::from_heights(size, spacing, heights)
    }

    /// 32-bit float little-endian RAW, row-major: exact.
    pub fn to_raw32(&self) -> Vec<u8> {
        self.heights()
            .iter()
            .flat_map(|h| h.to_le_bytes())
            .collect()
    }

    /// Reads 32-bit float little-endian RAW of a (2^n + 1)-square map.
    pub fn from_raw32(bytes: &[u8], spacing: f32) -> Result<Heightmap, TerrainError> {
        let size = square_side(bytes.len(), 4)?;
        let heights = bytes
            .chunks_exact(4)
            .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .collect();
        Heightmap::from_heights(size, spacing, heights)
    }

    /// Writes a 16-bit grayscale PNG (Unreal's heightmap format) with the range and spacing
    /// in a `tEXt` chunk, and returns the range.
    pub fn write_png16<W: Write>(&self, out: W) -> Result<HeightRange, TerrainError> {
        let range = self.height_range();
        let side = self.size() as u32;
        let mut encoder = png::Encoder::new(out, side, side);
        encoder.set_color(png::ColorType::Grayscale);
        encoder.set_depth(png::BitDepth::Sixteen);
        encoder.add_text_chunk(
            TEXT_KEY.to_string(),
            format!("{} {} {}", range.min, range.max, self.spacing()),
        )?;
        let mut writer = encoder.write_header()?;
        let data: Vec<u8> = self.quantized(&range).flat_map(u16::to_be_bytes).collect();
        writer.write_image_data(&data)?;
        writer.finish()?;
        Ok(range)
    }

    /// Reads a 16-bit grayscale PNG. The range and spacing come from the file's `sylva:heights`
    /// chunk when present, else from `fallback` (an error if neither is there).
    pub fn read_png16<R: BufRead + Seek>(
        input: R,
        fallback: Option<(HeightRange, f32)>,
    ) -> Result<Heightmap, TerrainError> {
        let png = decode_png16(input, |width, height| {
            if width != height {
                return Err(TerrainError::NotSquare { width, height });
            }
            checked_len(width as usize).map(|_| ())
        })?;
        let (range, spacing) = png.stored.or(fallback).ok_or(TerrainError::NoHeightRange)?;
        range.validate()?;
        let heights = png.samples.iter().map(|&q| range.dequantize(q)).collect();
        Heightmap::from_heights(png.width, spacing, heights)
    }
}

/// A 16-bit grayscale PNG's samples, row-major, and the range and spacing of its
/// `sylva:heights` chunk if it has one.
pub(crate) struct Png16 {
    pub(crate) width: usize,
    pub(crate) height: usize,
    pub(crate) samples: Vec<u16>,
    pub(crate) stored: Option<(HeightRange, f32)>,
}

/// Decodes a 16-bit grayscale PNG, asking `check` about its width and height before its
/// pixels are allocated (a header can claim any size).
pub(crate) fn decode_png16<R: BufRead + Seek>(
    input: R,
    check: impl FnOnce(u32, u32) -> Result<(), TerrainError>,
) -> Result<Png16, TerrainError> {
    let mut reader = png::Decoder::new(input).read_info()?;
    let info = reader.info();
    if info.color_type != png::ColorType::Grayscale || info.bit_depth != png::BitDepth::Sixteen {
        return Err(TerrainError::NotGrayscale16 {
            channels: info.color_type.samples() as u8,
            bits: info.bit_depth as u8,
        });
    }
    let (width, height) = (info.width, info.height);
    check(width, height)?;
    let stored = info
        .uncompressed_latin1_text
        .iter()
        .find(|t| t.keyword == TEXT_KEY)
        .and_then(|t| {
            let v: Vec<f32> = t
                .text
                .split_whitespace()
                .filter_map(|s| s.parse().ok())
                .collect();
            (v.len() == 3).then(|| {
                (
                    HeightRange {
                        min: v[0],
                        max: v[1],
                    },
                    v[2],
                )
            })
        });
    let (width, height) = (width as usize, height as usize);
    let mut buf = vec![
        0u8;
        reader
            .output_buffer_size()
            .ok_or(TerrainError::BadSize(width))?
    ];
    reader.next_frame(&mut buf)?;
    let samples = buf[..width * height * 2]
        .chunks_exact(2)
        .map(|b| u16::from_be_bytes([b[0], b[1]]))
        .collect();
    Ok(Png16 {
        width,
        height,
        samples,
        stored,
    })
}

/// Side of a square map stored in `len` bytes at `bytes_per_sample`.
fn square_side(len: usize, bytes_per_sample: usize) -> Result<usize, TerrainError> {
    if !len.is_multiple_of(bytes_per_sample) {
        return Err(TerrainError::PartialSample {
            bytes: len,
            sample_bytes: bytes_per_sample,
        });
    }
    let samples = len / bytes_per_sample;
    let side = (samples as f64).sqrt().round() as usize;
    if side * side != samples {
        return Err(TerrainError::NotSquareSamples { samples });
    }
    levels_of(side)?;
    Ok(side)
}
