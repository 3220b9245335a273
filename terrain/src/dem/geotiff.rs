//! GeoTIFF elevation models through the `tiff` crate: one band of 8, 16 or 32-bit integers or
//! 32 or 64-bit floats, stripped or tiled, uncompressed, PackBits, LZW or Deflate (with the
//! horizontal and floating-point predictors). The pixel scale and tie point give the spacing
//! and the corner; a geographic model's degrees are turned into metres at its middle
//! latitude; `GDAL_NODATA` marks the empty cells.

use std::io::Cursor;

use tiff::decoder::{Decoder, DecodingResult, Limits};
use tiff::tags::Tag;

use super::{ElevationModel, Georeference, MAX_SAMPLES, check_size, metres_per_degree};
use crate::error::TerrainError;

fn bad(message: impl Into<String>) -> TerrainError {
    TerrainError::Dem {
        format: "GeoTIFF",
        message: message.into(),
    }
}

/// The GeoKeys that say how to read the pixel scale and tie point: the model type
/// (1 projected, 2 geographic), the raster type (1 a pixel is an area, tied at its corner;
/// 2 a pixel is a point, tied at itself), the projected CRS's EPSG code and its linear unit.
#[derive(Debug, Default, Clone, Copy, PartialEq)]
struct Keys {
    model: Option<u16>,
    raster: Option<u16>,
    projection: Option<u16>,
    linear_unit: Option<u16>,
}

/// Reads the keys held in the directory itself (location 0).
fn keys(directory: &[u16]) -> Keys {
    let mut k = Keys::default();
    let count = directory.get(3).copied().unwrap_or(0) as usize;
    for entry in directory
        .get(4..)
        .unwrap_or(&[])
        .chunks_exact(4)
        .take(count)
    {
        let (id, location, value) = (entry[0], entry[1], entry[3]);
        if location != 0 {
            continue;
        }
        match id {
            1024 => k.model = Some(value),
            1025 => k.raster = Some(value),
            3072 => k.projection = Some(value),
            3076 => k.linear_unit = Some(value),
            _ => {}
        }
    }
    k
}

/// GTRasterTypeGeoKey's value for rasters whose pixels are points.
const PIXEL_IS_POINT: u16 = 2;

/// Metres in one of the file's linear units (EPSG unit codes).
fn unit_metres(unit: Option<u16>) -> f64 {
    match unit {
        Some(9002) => 0.3048,
        Some(9003) => 1200.0 / 3937.0,
        _ => 1.0,
    }
}

/// A tag's values as numbers of `T`, if the file has it.
fn tag<T>(
    decoder: &mut Decoder<Cursor<&[u8]>>,
    tag: Tag,
    values: impl Fn(tiff::decoder::ifd::Value) -> tiff::TiffResult<Vec<T>>,
) -> Result<Option<Vec<T>>, TerrainError> {
    let tiff = |e: tiff::TiffError| bad(e.to_string());
    decoder
        .find_tag(tag)
        .map_err(tiff)?
        .map(values)
        .transpose()
        .map_err(tiff)
}

pub(super) fn read(bytes: &[u8]) -> Result<ElevationModel, TerrainError> {
    let tiff = |e: tiff::TiffError| bad(e.to_string());
    let mut limits = Limits::default();
    limits.decoding_buffer_size = (MAX_SAMPLES * 8) as usize;
    limits.intermediate_buffer_size = 512 << 20;
    let mut decoder = Decoder::new(Cursor::new(bytes))
        .map_err(tiff)?
        .with_limits(limits);
    let (w, h) = decoder.dimensions().map_err(tiff)?;
    // The header's claim is checked before a pixel is read.
    let (width, height) = check_size(u64::from(w), u64::from(h))?;
    let scale = tag(&mut decoder, Tag::ModelPixelScaleTag, |v| v.into_f64_vec())?;
    let tie = tag(&mut decoder, Tag::ModelTiepointTag, |v| v.into_f64_vec())?;
    let directory = tag(&mut decoder, Tag::GeoKeyDirectoryTag, |v| v.into_u16_vec())?;
    let nodata: Option<f64> = decoder
        .find_tag(Tag::GdalNodata)
        .map_err(tiff)?
        .and_then(|v| v.into_string().ok())
        .and_then(|s| s.trim().trim_end_matches('\0').parse().ok());
    let samples: Vec<f64> = match decoder.read_image().map_err(tiff)? {
        DecodingResult::U8(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::I8(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::U16(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::I16(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::U32(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::I32(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::F32(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::F64(v) => v,
        other => return Err(bad(format!("samples of {} are not heights", kind(&other)))),
    };
    if samples.len() != width * height {
        return Err(bad(format!(
            "{} samples for {width} x {height}: only single-band models are read",
            samples.len()
        )));
    }
    let heights = samples
        .into_iter()
        .map(|v| {
            if Some(v) == nodata || !v.is_finite() {
                f32::NAN
            } else {
                v as f32
            }
        })
        .collect();
    let k = directory.as_deref().map(keys).unwrap_or_default();
    let (spacing, georeference) = match (scale.as_deref(), tie.as_deref()) {
        (Some([sx, sy, ..]), tie) if *sx > 0.0 && *sy > 0.0 => {
            // The tie point maps raster (i, j) to model (x, y). Where a pixel is an area (the
            // default), (0, 0) is its north-west corner and its sample half a cell in; where
            // a pixel is a point, (0, 0) is the sample itself.
            let inset = if k.raster == Some(PIXEL_IS_POINT) {
                0.0
            } else {
                0.5
            };
            let (x0, y0) = match tie {
                Some([i, j, _, x, y, ..]) => (x - i * sx + inset * sx, y + j * sy - inset * sy),
                _ => (0.0, 0.0),
            };
            let geographic = k.model == Some(2)
                || (k.model.is_none() && *sx < 0.1 && x0.abs() <= 180.0 && y0.abs() <= 90.0);
            if geographic {
                let middle = y0 - 0.5 * height as f64 * sy;
                let (per_lon, per_lat) = metres_per_degree(middle);
                (
                    Some([(sx * per_lon) as f32, (sy * per_lat) as f32]),
                    Some(Georeference::Geographic {
                        longitude: x0,
                        latitude: y0,
                        step: [*sx, *sy],
                    }),
                )
            } else {
                let m = unit_metres(k.linear_unit);
                (
                    Some([(sx * m) as f32, (sy * m) as f32]),
                    Some(Georeference::Projected {
                        x: x0,
                        y: y0,
                        step: [*sx, *sy],
                        epsg: k.projection,
                    }),
                )
            }
        }
        _ => (None, None),
    };
    Ok(ElevationModel {
        width,
        height,
        heights,
        spacing: spacing.unwrap_or([1.0, 1.0]),
        nodata: 0,
        georeference,
        spacing_from_file: spacing.is_some(),
    })
}

/// A decoded sample type's name, for errors.
fn kind(result: &DecodingResult) -> &'static str {
    match result {
        DecodingResult::F16(_) => "16-bit floats",
        DecodingResult::U64(_) | DecodingResult::I64(_) => "64-bit integers",
        _ => "this type",
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use tiff::encoder::{Compression, DeflateLevel, TiffEncoder, colortype};

    /// A GeoTIFF of `w` x `h` float heights at 30 m in UTM zone 33N, Deflate-compressed.
    fn projected(w: u32, h: u32, nodata: f32) -> Vec<u8> {
        let data: Vec<f32> = (0..w * h)
            .map(|i| if i == 5 { nodata } else { (i % w) as f32 * 2.0 })
            .collect();
        let mut buf = Cursor::new(Vec::new());
        let mut enc = TiffEncoder::new(&mut buf)
            .unwrap()
            .with_compression(Compression::Deflate(DeflateLevel::Balanced));
        let mut image = enc.new_image::<colortype::Gray32Float>(w, h).unwrap();
        let d = image.encoder();
        d.write_tag(Tag::ModelPixelScaleTag, &[30.0f64, 30.0, 0.0][..])
            .unwrap();
        d.write_tag(
            Tag::ModelTiepointTag,
            &[0.0f64, 0.0, 0.0, 500_000.0, 4_000_000.0, 0.0][..],
        )
        .unwrap();
        d.write_tag(
            Tag::GeoKeyDirectoryTag,
            &[1u16, 1, 0, 2, 1024, 0, 1, 1, 3072, 0, 1, 32633][..],
        )
        .unwrap();
        d.write_tag(Tag::GdalNodata, "-9999").unwrap();
        image.write_data(&data).unwrap();
        buf.into_inner()
    }

    #[test]
    fn a_projected_float_model_with_nodata() {
        let m = read(&projected(7, 5, -9999.0)).unwrap();
        assert_eq!((m.width, m.height, m.spacing), (7, 5, [30.0, 30.0]));
        assert!(m.heights[5].is_nan());
        assert_eq!(m.heights[3], 6.0);
        assert_eq!(
            m.georeference,
            Some(Georeference::Projected {
                x: 500_015.0,
                y: 3_999_985.0,
                step: [30.0, 30.0],
                epsg: Some(32633)
            })
        );
    }

    #[test]
    fn a_geographic_integer_model_in_degrees() {
        let mut buf = Cursor::new(Vec::new());
        let mut enc = TiffEncoder::new(&mut buf)
            .unwrap()
            .with_compression(Compression::Lzw);
        let mut image = enc.new_image::<colortype::GrayI16>(4, 4).unwrap();
        let d = image.encoder();
        d.write_tag(
            Tag::ModelPixelScaleTag,
            &[1.0f64 / 1200.0, 1.0 / 1200.0, 0.0][..],
        )
        .unwrap();
        d.write_tag(
            Tag::ModelTiepointTag,
            &[0.0f64, 0.0, 0.0, 8.0, 47.0, 0.0][..],
        )
        .unwrap();
        d.write_tag(Tag::GeoKeyDirectoryTag, &[1u16, 1, 0, 1, 1024, 0, 1, 2][..])
            .unwrap();
        image.write_data(&[100i16; 16]).unwrap();
        let m = read(&buf.into_inner()).unwrap();
        // 3 arc-seconds at 47 degrees north: about 63 m east-west and 92.6 m north-south.
        assert!(
            (m.spacing[0] - 63.3).abs() < 0.3 && (m.spacing[1] - 92.6).abs() < 0.2,
            "{:?}",
            m.spacing
        );
        assert!(matches!(
            m.georeference,
            Some(Georeference::Geographic { .. })
        ));
    }

    /// A 3 x 3 geographic model tied at (8 E, 47 N) with the raster type `raster`.
    fn tied(raster: u16) -> ElevationModel {
        let mut buf = Cursor::new(Vec::new());
        let mut enc = TiffEncoder::new(&mut buf).unwrap();
        let mut image = enc.new_image::<colortype::GrayI16>(3, 3).unwrap();
        let d = image.encoder();
        d.write_tag(Tag::ModelPixelScaleTag, &[0.001f64, 0.001, 0.0][..])
            .unwrap();
        d.write_tag(
            Tag::ModelTiepointTag,
            &[0.0f64, 0.0, 0.0, 8.0, 47.0, 0.0][..],
        )
        .unwrap();
        d.write_tag(
            Tag::GeoKeyDirectoryTag,
            &[1u16, 1, 0, 2, 1024, 0, 1, 2, 1025, 0, 1, raster][..],
        )
        .unwrap();
        image.write_data(&[7i16; 9]).unwrap();
        read(&buf.into_inner()).unwrap()
    }

    #[test]
    fn a_point_is_tied_at_itself_and_an_area_at_its_corner() {
        let at = |m: ElevationModel| match m.georeference {
            Some(Georeference::Geographic {
                longitude,
                latitude,
                ..
            }) => (longitude, latitude),
            other => panic!("{other:?}"),
        };
        let (lon, lat) = at(tied(PIXEL_IS_POINT));
        assert_eq!((lon, lat), (8.0, 47.0));
        let (lon, lat) = at(tied(1));
        assert!((lon - 8.0005).abs() < 1e-12 && (lat - 46.9995).abs() < 1e-12);
    }

    #[test]
    fn broken_and_vast_files_are_errors() {
        assert!(read(b"II*\0garbage").is_err());
        let mut bytes = projected(4, 4, -9999.0);
        bytes.truncate(bytes.len() / 2);
        assert!(read(&bytes).is_err());
    }
}
