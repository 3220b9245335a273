//! ESRI ASCII grids (`.asc`): a header of `ncols`, `nrows`, `xllcorner` or `xllcenter`,
//! `yllcorner` or `yllcenter`, `cellsize` (or `dx` and `dy`) and `NODATA_value`, then the rows
//! from north to south. Errors name the line and column.

use super::{ElevationModel, Georeference, check_size, metres_per_degree};
use crate::error::TerrainError;

fn at(line: usize, column: usize, message: String) -> TerrainError {
    TerrainError::AsciiGrid {
        line,
        column,
        message,
    }
}

pub(super) fn read(bytes: &[u8]) -> Result<ElevationModel, TerrainError> {
    let text = std::str::from_utf8(bytes).map_err(|e| at(1, 1, format!("not text: {e}")))?;
    let mut lines = text.lines().enumerate().peekable();
    let (mut ncols, mut nrows, mut cell, mut dx, mut dy) = (None, None, None, None, None);
    let (mut x0, mut y0, mut centre, mut nodata) = (0.0f64, 0.0f64, false, None);
    // The header: `key value` lines until the first line that starts with a number.
    while let Some(&(n, line)) = lines.peek() {
        let mut words = line.split_whitespace();
        let Some(key) = words.next() else {
            lines.next();
            continue;
        };
        if key.parse::<f64>().is_ok() {
            break;
        }
        let value = words
            .next()
            .ok_or_else(|| at(n + 1, line.len() + 1, format!("'{key}' has no value")))?;
        let column = line.find(value).unwrap_or(0) + 1;
        let number: f64 = value
            .parse()
            .map_err(|_| at(n + 1, column, format!("'{key}': '{value}' is not a number")))?;
        match key.to_ascii_lowercase().as_str() {
            "ncols" => ncols = Some(number),
            "nrows" => nrows = Some(number),
            "cellsize" => cell = Some(number),
            "dx" => dx = Some(number),
            "dy" => dy = Some(number),
            "xllcorner" => x0 = number,
            "yllcorner" => y0 = number,
            "xllcenter" => (x0, centre) = (number, true),
            "yllcenter" => (y0, centre) = (number, true),
            "nodata_value" => nodata = Some(number),
            other => return Err(at(n + 1, 1, format!("unknown header key '{other}'"))),
        }
        lines.next();
    }
    let whole = |v: Option<f64>, key: &str| match v {
        Some(v) if v >= 1.0 && v.fract() == 0.0 => Ok(v as u64),
        _ => Err(at(
            1,
            1,
            format!("the header needs '{key}', a whole number"),
        )),
    };
    let (width, height) = check_size(whole(ncols, "ncols")?, whole(nrows, "nrows")?)?;
    let (sx, sy) = match (cell, dx, dy) {
        (Some(c), _, _) => (c, c),
        (None, Some(x), Some(y)) => (x, y),
        _ => {
            return Err(at(
                1,
                1,
                "the header needs 'cellsize' (or 'dx' and 'dy')".into(),
            ));
        }
    };
    if !(sx > 0.0 && sy > 0.0 && sx.is_finite() && sy.is_finite()) {
        return Err(at(
            1,
            1,
            format!("cell size {sx} x {sy}: expected positive numbers"),
        ));
    }
    let mut heights = Vec::with_capacity(width * height);
    let mut last = (1, 1);
    for (n, line) in lines {
        for (column, word) in words_with_columns(line) {
            if heights.len() == width * height {
                return Err(at(
                    n + 1,
                    column,
                    format!("more than {width} x {height} values"),
                ));
            }
            let v: f64 = word
                .parse()
                .map_err(|_| at(n + 1, column, format!("'{word}' is not a number")))?;
            heights.push(if Some(v) == nodata || !v.is_finite() {
                f32::NAN
            } else {
                v as f32
            });
            last = (n + 1, column);
        }
    }
    if heights.len() != width * height {
        return Err(at(
            last.0,
            last.1,
            format!("{} values for a {width} x {height} grid", heights.len()),
        ));
    }
    // Degrees when the corner and cells look like longitude and latitude: a projected grid's
    // cells are metres (or feet), far larger than a degree's fractions.
    let geographic = sx < 0.1 && sy < 0.1 && x0.abs() <= 180.0 && y0.abs() <= 90.0;
    // The north-west sample's centre: a corner header gives the outer edge of the grid.
    let half = if centre { 0.0 } else { 0.5 };
    let north = y0 + (height as f64 - 1.0 + half) * sy;
    let west = x0 + half * sx;
    let (spacing, georeference) = if geographic {
        let middle = y0 + 0.5 * height as f64 * sy;
        let (per_lon, per_lat) = metres_per_degree(middle);
        (
            [(sx * per_lon) as f32, (sy * per_lat) as f32],
            Georeference::Geographic {
                longitude: west,
                latitude: north,
                step: [sx, sy],
            },
        )
    } else {
        (
            [sx as f32, sy as f32],
            Georeference::Projected {
                x: west,
                y: north,
                step: [sx, sy],
                epsg: None,
            },
        )
    };
    Ok(ElevationModel {
        width,
        height,
        heights,
        spacing,
        nodata: 0,
        georeference: Some(georeference),
        spacing_from_file: true,
    })
}

/// The whitespace-separated words of a line with their 1-based columns.
fn words_with_columns(line: &str) -> impl Iterator<Item = (usize, &str)> {
    line.split_ascii_whitespace()
        .map(move |w| (w.as_ptr() as usize - line.as_ptr() as usize + 1, w))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mistakes_name_their_line_and_column() {
        let e = read(b"ncols 2\nnrows 2\ncellsize 1\n1 2\n3 x\n").unwrap_err();
        assert!(e.to_string().contains("line 5, column 3"), "{e}");
        let e = read(b"ncols 2\nnrows 2\ncellsize 1\n1 2\n3\n").unwrap_err();
        assert!(e.to_string().contains("3 values"), "{e}");
        let e = read(b"ncols 900000000\nnrows 900000000\ncellsize 1\n1\n").unwrap_err();
        assert!(matches!(e, TerrainError::TooLarge { .. }), "{e}");
        assert!(read(b"ncols 2\nnrows 2\n1 2 3 4\n").is_err());
    }

    #[test]
    fn degrees_become_metres_and_nodata_nan() {
        let m = read(b"ncols 2\nnrows 2\nxllcorner 8\nyllcorner 47\ncellsize 0.000833333333\nNODATA_value -9999\n1 -9999\n3 4\n").unwrap();
        assert!(m.heights[1].is_nan());
        assert!(
            (m.spacing[1] - 92.6).abs() < 0.2 && (m.spacing[0] - 63.1).abs() < 0.3,
            "{:?}",
            m.spacing
        );
        assert!(matches!(
            m.georeference,
            Some(Georeference::Geographic { .. })
        ));
    }
}
