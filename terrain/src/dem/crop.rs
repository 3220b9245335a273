//! A window of a model: an SRTM tile is 80 x 111 km, a world at most 20 km; the part that is
//! wanted, cut out with its place on the globe moved to its own corner.

use super::{ElevationModel, Georeference, metres_per_degree};
use crate::error::TerrainError;

/// A window of samples: `column` and `row` of its north-west sample, `width` and `height`
/// in samples.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Window {
    /// Column of the west edge (0 is the model's).
    pub column: usize,
    /// Row of the north edge (0 is the model's).
    pub row: usize,
    /// Samples per row, at least 2.
    pub width: usize,
    /// Rows, at least 2.
    pub height: usize,
}

impl std::str::FromStr for Window {
    type Err = String;

    /// `COLUMN,ROW,WIDTH,HEIGHT`, as `--crop` takes it.
    fn from_str(text: &str) -> Result<Window, String> {
        let v: Vec<usize> = text
            .split(',')
            .map(|p| p.trim().parse())
            .collect::<Result<_, _>>()
            .map_err(|_| format!("'{text}': expected COLUMN,ROW,WIDTH,HEIGHT in samples"))?;
        match v[..] {
            [column, row, width, height] => Ok(Window {
                column,
                row,
                width,
                height,
            }),
            _ => Err(format!(
                "'{text}': expected four numbers, COLUMN,ROW,WIDTH,HEIGHT in samples"
            )),
        }
    }
}

impl ElevationModel {
    /// The samples of `window`, an error unless it lies inside the model and is at least
    /// 2 x 2. The georeference moves to the window's north-west sample; a geographic model's
    /// spacing is worked out anew at the window's own middle latitude (a degree of longitude
    /// shrinks northward: 2% across an SRTM tile at 45 degrees). The count of filled cells
    /// is the whole model's.
    ///
    /// ```
    /// use sylva_terrain::dem::{DemFormat, ElevationModel, ReadOptions, Window};
    ///
    /// let asc = "ncols 4\nnrows 3\nxllcorner 500000\nyllcorner 4000000\ncellsize 30\n\
    ///            1 2 3 4\n5 6 7 8\n9 10 11 12\n";
    /// let model = ElevationModel::parse(asc.as_bytes(), DemFormat::AsciiGrid, &ReadOptions::default())?;
    /// let part = model.crop(Window { column: 1, row: 1, width: 3, height: 2 })?;
    /// assert_eq!(part.heights, [6.0, 7.0, 8.0, 10.0, 11.0, 12.0]);
    /// assert!(model.crop(Window { column: 3, row: 0, width: 2, height: 2 }).is_err());
    /// # Ok::<(), sylva_terrain::TerrainError>(())
    /// ```
    pub fn crop(&self, window: Window) -> Result<ElevationModel, TerrainError> {
        let Window {
            column,
            row,
            width,
            height,
        } = window;
        let fits = width >= 2
            && height >= 2
            && column.checked_add(width).is_some_and(|e| e <= self.width)
            && row.checked_add(height).is_some_and(|e| e <= self.height);
        if !fits {
            return Err(TerrainError::Dem {
                format: "elevation model",
                message: format!(
                    "the window of {width} x {height} samples at column {column}, row {row} \
                     does not lie inside the model's {} x {} (and needs at least 2 x 2)",
                    self.width, self.height
                ),
            });
        }
        let heights = (row..row + height)
            .flat_map(|r| &self.heights[r * self.width + column..r * self.width + column + width])
            .copied()
            .collect();
        let (dx, dz) = (column as f64, row as f64);
        let mut spacing = self.spacing;
        let georeference = self.georeference.map(|g| match g {
            Georeference::Geographic {
                longitude,
                latitude,
                step,
            } => {
                let latitude = latitude - dz * step[1];
                if self.spacing_from_file {
                    let middle = latitude - 0.5 * (height - 1) as f64 * step[1];
                    let (per_lon, per_lat) = metres_per_degree(middle);
                    spacing = [(step[0] * per_lon) as f32, (step[1] * per_lat) as f32];
                }
                Georeference::Geographic {
                    longitude: longitude + dx * step[0],
                    latitude,
                    step,
                }
            }
            Georeference::Projected { x, y, step, epsg } => Georeference::Projected {
                x: x + dx * step[0],
                y: y - dz * step[1],
                step,
                epsg,
            },
        });
        Ok(ElevationModel {
            width,
            height,
            heights,
            spacing,
            // Where the filled cells were is not kept: the whole model's count stands.
            nodata: self.nodata,
            georeference,
            spacing_from_file: self.spacing_from_file,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn geographic(width: usize, height: usize) -> ElevationModel {
        let step = 1.0 / 1200.0;
        let (per_lon, per_lat) = metres_per_degree(44.5);
        ElevationModel {
            width,
            height,
            heights: (0..width * height).map(|i| i as f32).collect(),
            spacing: [(step * per_lon) as f32, (step * per_lat) as f32],
            nodata: 0,
            georeference: Some(Georeference::Geographic {
                longitude: -72.0,
                latitude: 45.0,
                step: [step; 2],
            }),
            spacing_from_file: true,
        }
    }

    #[test]
    fn a_window_moves_its_corner_and_its_latitude() {
        let m = geographic(1201, 1201);
        let part = m
            .crop(Window {
                column: 600,
                row: 1000,
                width: 201,
                height: 201,
            })
            .unwrap();
        assert_eq!(part.heights[0], (1000 * 1201 + 600) as f32);
        assert_eq!(part.heights[200 * 201 + 200], (1200 * 1201 + 800) as f32);
        let Some(Georeference::Geographic {
            longitude,
            latitude,
            ..
        }) = part.georeference
        else {
            panic!("{:?}", part.georeference)
        };
        assert!(
            (longitude + 71.5).abs() < 1e-9 && (latitude - (45.0 - 1000.0 / 1200.0)).abs() < 1e-9
        );
        // Farther south, a degree of longitude is longer.
        assert!(
            part.spacing[0] > m.spacing[0],
            "{:?} {:?}",
            part.spacing,
            m.spacing
        );
        assert!((part.spacing[1] - m.spacing[1]).abs() < 0.01);
    }

    #[test]
    fn windows_outside_or_too_small_are_errors() {
        let m = geographic(10, 10);
        let w = |column, row, width, height| Window {
            column,
            row,
            width,
            height,
        };
        assert!(m.crop(w(0, 0, 10, 10)).is_ok());
        assert!(m.crop(w(1, 0, 10, 10)).is_err());
        assert!(m.crop(w(0, 0, 1, 5)).is_err());
        assert!(m.crop(w(usize::MAX, 0, 2, 2)).is_err());
    }

    #[test]
    fn a_window_reads_from_its_text() {
        assert_eq!(
            "1, 2,30,40".parse::<Window>(),
            Ok(Window {
                column: 1,
                row: 2,
                width: 30,
                height: 40
            })
        );
        assert!("1,2,3".parse::<Window>().is_err());
        assert!("a,b,c,d".parse::<Window>().is_err());
    }
}
