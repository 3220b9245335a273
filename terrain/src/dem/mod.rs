//! Real elevation models in any size and the common formats: GeoTIFF (16-bit integer and
//! 32-bit float, stripped or tiled, uncompressed, LZW, Deflate or PackBits), SRTM `.hgt`,
//! ESRI ASCII grids, 16-bit PNG and RAW of any width and height.
//!
//! An [`ElevationModel`] is the file's grid as it is: its width and height, its spacing in
//! metres on each axis (degrees converted at the model's latitude), and where nodata cells
//! were (filled, see [`ElevationModel::fill_nodata`]). [`ElevationModel::to_heightmap`]
//! resamples it onto the square (2^n + 1) grid that generation, erosion and forests work on.
//!
//! ```
//! use sylva_terrain::dem::{DemFormat, ElevationModel, ReadOptions};
//!
//! let asc = "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 30\nNODATA_value -9999\n\
//!            10 11 12\n13 -9999 15\n";
//! let model = ElevationModel::parse(asc.as_bytes(), DemFormat::AsciiGrid, &ReadOptions::default())?;
//! assert_eq!((model.width, model.height, model.nodata), (3, 2, 1));
//! assert_eq!(model.spacing, [30.0, 30.0]);
//! let (map, extent) = model.to_heightmap()?;
//! assert_eq!(map.size(), 3);
//! assert_eq!(extent, [60.0, 30.0]);
//! # Ok::<(), sylva_terrain::TerrainError>(())
//! ```

mod ascii_grid;
mod crop;
mod fill;
mod geotiff;
mod hgt;
mod raster;
mod resample;

pub use crop::Window;

use std::path::Path;

use crate::error::TerrainError;

/// Most samples a model may have: 8193 x 8193 (256 MiB of heights). Headers claiming more
/// are refused before anything is allocated.
pub const MAX_SAMPLES: u64 = 8193 * 8193;
/// Most samples along one side.
pub const MAX_SIDE: u64 = 16385;
/// Largest file read, bytes.
pub const MAX_FILE_BYTES: u64 = 1 << 30;

/// The formats read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum DemFormat {
    /// GeoTIFF (`.tif`, `.tiff`).
    GeoTiff,
    /// SRTM `.hgt`: big-endian 16-bit samples, 1201 or 3601 a side, named by its corner.
    Hgt,
    /// ESRI ASCII grid (`.asc`).
    AsciiGrid,
    /// 16-bit grayscale PNG (`.png`).
    Png16,
    /// Little-endian 16-bit RAW (`.raw`, `.r16`) of a given or square size.
    Raw16,
}

impl DemFormat {
    /// The format a file's name says, or its first bytes when the name says nothing.
    pub fn of(path: &Path, head: &[u8]) -> Option<DemFormat> {
        let by_name = match path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .as_deref()
        {
            Some("tif" | "tiff" | "gtif") => Some(DemFormat::GeoTiff),
            Some("hgt") => Some(DemFormat::Hgt),
            Some("asc") => Some(DemFormat::AsciiGrid),
            Some("png") => Some(DemFormat::Png16),
            Some("raw" | "r16") => Some(DemFormat::Raw16),
            _ => None,
        };
        by_name.or_else(|| {
            if head.starts_with(b"II*\0")
                || head.starts_with(b"MM\0*")
                || head.starts_with(b"II+\0")
                || head.starts_with(b"MM\0+")
            {
                Some(DemFormat::GeoTiff)
            } else if head.starts_with(b"\x89PNG") {
                Some(DemFormat::Png16)
            } else if head.len() >= 5 && head[..5].eq_ignore_ascii_case(b"ncols") {
                Some(DemFormat::AsciiGrid)
            } else {
                None
            }
        })
    }
}

/// What a file does not say, given by the user.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ReadOptions {
    /// Metres between samples, overriding the file's georeferencing (or standing in where it
    /// has none). Default: none (the file's, else 1 m).
    pub spacing: Option<f32>,
    /// Heights of 16-bit samples 0 and 65535 (PNG without sylva's chunk, RAW).
    /// Default: none (the file's; a file that needs one is refused without it).
    pub height_range: Option<[f32; 2]>,
    /// Width and height of a RAW file (a square RAW's side follows from its length).
    /// Default: none (square, its side from the file's length).
    pub raw_size: Option<[usize; 2]>,
}

impl ReadOptions {
    /// Sets [`ReadOptions::spacing`].
    #[must_use]
    pub fn with_spacing(mut self, metres: f32) -> Self {
        self.spacing = Some(metres);
        self
    }
    /// Sets [`ReadOptions::height_range`].
    #[must_use]
    pub fn with_height_range(mut self, low: f32, high: f32) -> Self {
        self.height_range = Some([low, high]);
        self
    }
    /// Sets [`ReadOptions::raw_size`].
    #[must_use]
    pub fn with_raw_size(mut self, width: usize, height: usize) -> Self {
        self.raw_size = Some([width, height]);
        self
    }
}

/// Where a model lies on the globe, as far as its file says.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Georeference {
    /// Longitude and latitude (degrees) of the north-west corner's sample.
    Geographic {
        /// Degrees east.
        longitude: f64,
        /// Degrees north.
        latitude: f64,
        /// Degrees between samples: eastward along a row, southward down a column.
        step: [f64; 2],
    },
    /// Projected coordinates of the north-west corner's sample, in the file's units.
    Projected {
        /// Easting.
        x: f64,
        /// Northing.
        y: f64,
        /// The file's units between samples: eastward along a row, southward down a column.
        step: [f64; 2],
        /// The EPSG code of the projection, where the file names one.
        epsg: Option<u16>,
    },
}

/// A grid of heights read from a file: row 0 is the north edge (z = 0), column 0 the west
/// (x = 0); cells with no data are filled.
#[derive(Debug, Clone, PartialEq)]
pub struct ElevationModel {
    /// Samples per row.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// Heights, row-major, metres.
    pub heights: Vec<f32>,
    /// Metres between samples along x (columns) and z (rows).
    pub spacing: [f32; 2],
    /// Cells that had no data and were filled.
    pub nodata: usize,
    /// Where it lies, if the file says.
    pub georeference: Option<Georeference>,
    /// Whether the spacing came from the file (`false`: from the options or a default of 1).
    pub spacing_from_file: bool,
}

impl ElevationModel {
    /// Reads a model from a file of at most [`MAX_FILE_BYTES`], in the format its name (or
    /// its first bytes) says.
    pub fn read(
        path: impl AsRef<Path>,
        options: &ReadOptions,
    ) -> Result<ElevationModel, TerrainError> {
        let path = path.as_ref();
        // Only a regular file, and no more of it than the limit, whatever its size says.
        use sylva_base::text_file::{TextFileError, read_bytes};
        let bytes = read_bytes(path, MAX_FILE_BYTES).map_err(|e| match e {
            TextFileError::TooLarge { .. } => TerrainError::TooLarge {
                // The size it says, or (a file that grew while read) the limit passed.
                what: format!(
                    "{} bytes of file",
                    std::fs::metadata(path)
                        .map_or(0, |m| m.len())
                        .max(MAX_FILE_BYTES + 1)
                ),
                limit: format!("{MAX_FILE_BYTES} bytes"),
            },
            TextFileError::Io(e) => TerrainError::Io(e.source),
            other => TerrainError::Io(std::sync::Arc::new(std::io::Error::other(
                other.to_string(),
            ))),
        })?;
        let format = DemFormat::of(path, &bytes[..bytes.len().min(16)]).ok_or_else(|| {
            TerrainError::Dem {
                format: "elevation model",
                message: format!(
                    "{}: not a GeoTIFF, .hgt, .asc, PNG or RAW file (by its name or first bytes)",
                    path.display()
                ),
            }
        })?;
        let model = Self::parse_named(
            &bytes,
            format,
            options,
            path.file_name().and_then(|n| n.to_str()),
        )?;
        model.check_spacing()?;
        Ok(model)
    }

    /// Parses a model from bytes in `format`.
    pub fn parse(
        bytes: &[u8],
        format: DemFormat,
        options: &ReadOptions,
    ) -> Result<ElevationModel, TerrainError> {
        let model = Self::parse_named(bytes, format, options, None)?;
        model.check_spacing()?;
        Ok(model)
    }

    fn parse_named(
        bytes: &[u8],
        format: DemFormat,
        options: &ReadOptions,
        name: Option<&str>,
    ) -> Result<ElevationModel, TerrainError> {
        let mut model = match format {
            DemFormat::GeoTiff => geotiff::read(bytes)?,
            DemFormat::Hgt => hgt::read(bytes, name)?,
            DemFormat::AsciiGrid => ascii_grid::read(bytes)?,
            DemFormat::Png16 => raster::read_png16(bytes, options.height_range)?,
            DemFormat::Raw16 => raster::read_raw16(bytes, options)?,
        };
        if let Some(s) = options.spacing {
            model.spacing = [s, s];
            model.spacing_from_file = false;
        }
        model.fill_nodata()?;
        Ok(model)
    }

    fn check_spacing(&self) -> Result<(), TerrainError> {
        for s in self.spacing {
            crate::error::check(
                "spacing",
                f64::from(s),
                s > 0.0 && s <= 100_000.0,
                "more than 0 and at most 100000 m",
            )?;
        }
        Ok(())
    }

    /// The model's extent, metres: `[(width - 1) * dx, (height - 1) * dz]`.
    pub fn extent(&self) -> [f32; 2] {
        [
            (self.width.saturating_sub(1)) as f32 * self.spacing[0],
            (self.height.saturating_sub(1)) as f32 * self.spacing[1],
        ]
    }
}

/// Checks a claimed grid size before anything is allocated for it.
pub(crate) fn check_size(width: u64, height: u64) -> Result<(usize, usize), TerrainError> {
    if width < 2 || height < 2 {
        return Err(TerrainError::Dem {
            format: "elevation model",
            message: format!("{width} x {height} samples: a model needs at least 2 x 2"),
        });
    }
    if width > MAX_SIDE || height > MAX_SIDE || width.saturating_mul(height) > MAX_SAMPLES {
        return Err(TerrainError::TooLarge {
            what: format!("{width} x {height} samples"),
            limit: format!("{MAX_SAMPLES} samples and {MAX_SIDE} a side"),
        });
    }
    Ok((width as usize, height as usize))
}

/// Metres per degree of longitude and of latitude at `latitude` degrees on the WGS 84
/// ellipsoid (the usual series in the latitude; within a millimetre a degree).
pub fn metres_per_degree(latitude: f64) -> (f64, f64) {
    let phi = latitude.to_radians();
    let lon = 111_412.84 * phi.cos() - 93.5 * (3.0 * phi).cos() + 0.118 * (5.0 * phi).cos();
    let lat = 111_132.92 - 559.82 * (2.0 * phi).cos() + 1.175 * (4.0 * phi).cos()
        - 0.0023 * (6.0 * phi).cos();
    (lon, lat)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_degree_is_what_the_tables_say() {
        let (lon, lat) = metres_per_degree(0.0);
        assert!(
            (lon - 111_319.5).abs() < 1.0 && (lat - 110_574.3).abs() < 1.0,
            "{lon} {lat}"
        );
        let (lon, lat) = metres_per_degree(45.0);
        assert!(
            (lon - 78_846.8).abs() < 1.0 && (lat - 111_131.7).abs() < 1.0,
            "{lon} {lat}"
        );
    }

    #[test]
    fn formats_are_known_by_name_or_by_their_first_bytes() {
        assert_eq!(
            DemFormat::of(Path::new("a.TIF"), b""),
            Some(DemFormat::GeoTiff)
        );
        assert_eq!(
            DemFormat::of(Path::new("N47E008.hgt"), b""),
            Some(DemFormat::Hgt)
        );
        assert_eq!(
            DemFormat::of(Path::new("x"), b"II*\0abc"),
            Some(DemFormat::GeoTiff)
        );
        assert_eq!(
            DemFormat::of(Path::new("x"), b"NCOLS 4"),
            Some(DemFormat::AsciiGrid)
        );
        assert_eq!(DemFormat::of(Path::new("x"), b"hello"), None);
    }

    #[test]
    fn vast_claims_are_refused_before_allocating() {
        assert!(matches!(
            check_size(100_000, 100_000),
            Err(TerrainError::TooLarge { .. })
        ));
        assert!(check_size(3601, 3601).is_ok());
        assert!(check_size(1, 5).is_err());
    }
}
