//! SRTM `.hgt`: big-endian signed 16-bit metres, 1201 (3 arc-seconds) or 3601 (1 arc-second)
//! samples a side, -32768 for voids; the file's name (`N47E008.hgt`) gives its south-west
//! corner, from which the spacing in metres follows.

use super::{ElevationModel, Georeference, check_size, metres_per_degree};
use crate::error::TerrainError;

/// The void value.
const VOID: i16 = -32768;

/// The south-west corner a name like `N47E008.hgt` gives, in degrees.
fn corner(name: &str) -> Option<(f64, f64)> {
    let n = name.get(..7)?.to_ascii_uppercase();
    let lat: f64 = n.get(1..3)?.parse().ok()?;
    let lon: f64 = n.get(4..7)?.parse().ok()?;
    let lat = match n.as_bytes()[0] {
        b'N' => lat,
        b'S' => -lat,
        _ => return None,
    };
    let lon = match n.as_bytes()[3] {
        b'E' => lon,
        b'W' => -lon,
        _ => return None,
    };
    Some((lat, lon))
}

pub(super) fn read(bytes: &[u8], name: Option<&str>) -> Result<ElevationModel, TerrainError> {
    let side = match bytes.len() {
        n if n == 2 * 1201 * 1201 => 1201,
        n if n == 2 * 3601 * 3601 => 3601,
        n => {
            return Err(TerrainError::Dem {
                format: "SRTM .hgt",
                message: format!(
                    "{n} bytes: an .hgt file is 1201 x 1201 or 3601 x 3601 big-endian 16-bit samples"
                ),
            });
        }
    };
    let (width, height) = check_size(side, side)?;
    let heights: Vec<f32> = bytes
        .chunks_exact(2)
        .map(|b| match i16::from_be_bytes([b[0], b[1]]) {
            VOID => f32::NAN,
            h => f32::from(h),
        })
        .collect();
    let degrees = 1.0 / (side - 1) as f64;
    let place = name.and_then(corner);
    // Spacing at the tile's middle latitude; a tile of unknown name is taken at 45 degrees.
    let middle = place.map_or(45.0, |(lat, _)| lat + 0.5);
    let (per_lon, per_lat) = metres_per_degree(middle);
    Ok(ElevationModel {
        width,
        height,
        heights,
        spacing: [(degrees * per_lon) as f32, (degrees * per_lat) as f32],
        nodata: 0,
        georeference: place.map(|(lat, lon)| Georeference::Geographic {
            longitude: lon,
            latitude: lat + 1.0,
            step: [degrees; 2],
        }),
        spacing_from_file: place.is_some(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_give_the_corner() {
        assert_eq!(corner("N47E008.hgt"), Some((47.0, 8.0)));
        assert_eq!(corner("s33w071.hgt"), Some((-33.0, -71.0)));
        assert_eq!(corner("X47E008.hgt"), None);
        assert_eq!(corner("N4"), None);
    }

    #[test]
    fn voids_are_nodata_and_spacing_follows_the_latitude() {
        let mut bytes = vec![0u8; 2 * 1201 * 1201];
        bytes[0..2].copy_from_slice(&VOID.to_be_bytes());
        bytes[2..4].copy_from_slice(&1234i16.to_be_bytes());
        let m = read(&bytes, Some("N00E010.hgt")).unwrap();
        assert!(m.heights[0].is_nan());
        assert_eq!(m.heights[1], 1234.0);
        // 3 arc-seconds at 0.5 degrees north: about 92.8 m east-west, 92.1 m north-south.
        assert!(
            (m.spacing[0] - 92.77).abs() < 0.05 && (m.spacing[1] - 92.15).abs() < 0.05,
            "{:?}",
            m.spacing
        );
        assert!(read(&bytes[..100], None).is_err());
    }
}
