//! Filling cells with no data: each empty cell next to known ones takes the mean of its
//! known neighbours (of the eight), ring after ring inward, so holes close from their edges
//! with heights between the ones around them, and nothing beyond the model's own range.

use super::ElevationModel;
use crate::error::TerrainError;

impl ElevationModel {
    /// Fills the cells without data (NaN) from their neighbours, ring by ring from the edges
    /// of each hole (each filled cell the mean of its known neighbours among the eight), and
    /// counts them in [`ElevationModel::nodata`]. An error when no cell has data.
    ///
    /// ```
    /// use sylva_terrain::dem::ElevationModel;
    /// let mut m = ElevationModel {
    ///     width: 3, height: 1, heights: vec![10.0, f32::NAN, 20.0], spacing: [1.0, 1.0],
    ///     nodata: 0, georeference: None, spacing_from_file: false,
    /// };
    /// m.fill_nodata()?;
    /// assert_eq!((m.heights[1], m.nodata), (15.0, 1));
    /// # Ok::<(), sylva_terrain::TerrainError>(())
    /// ```
    pub fn fill_nodata(&mut self) -> Result<(), TerrainError> {
        let (w, h) = (self.width, self.height);
        let mut empty: Vec<usize> = (0..self.heights.len())
            .filter(|&i| !self.heights[i].is_finite())
            .collect();
        if empty.is_empty() {
            return Ok(());
        }
        if empty.len() == self.heights.len() {
            return Err(TerrainError::Dem {
                format: "elevation model",
                message: "no cell has data".into(),
            });
        }
        self.nodata += empty.len();
        for &i in &empty {
            self.heights[i] = f32::NAN;
        }
        let neighbours = |i: usize| {
            let (x, z) = ((i % w) as isize, (i / w) as isize);
            (-1..=1isize)
                .flat_map(move |dz| (-1..=1isize).map(move |dx| (x + dx, z + dz)))
                .filter(move |&(nx, nz)| {
                    (nx, nz) != (x, z) && nx >= 0 && nz >= 0 && nx < w as isize && nz < h as isize
                })
                .map(move |(nx, nz)| nz as usize * w + nx as usize)
        };
        // Rings as a breadth-first search from the known cells: each empty cell is reached
        // once, so filling is linear in the model's size however large its holes.
        let mut queued = vec![false; self.heights.len()];
        let mut ring: Vec<usize> = empty
            .drain(..)
            .filter(|&i| neighbours(i).any(|n| self.heights[n].is_finite()))
            .collect();
        for &i in &ring {
            queued[i] = true;
        }
        let mut values = Vec::new();
        while !ring.is_empty() {
            // A ring reads only what was known before it, so its order does not matter.
            values.clear();
            for &i in &ring {
                let (sum, n) = neighbours(i)
                    .map(|n| self.heights[n])
                    .filter(|v| v.is_finite())
                    .fold((0.0f64, 0u32), |(s, n), v| (s + f64::from(v), n + 1));
                values.push((sum / f64::from(n.max(1))) as f32);
            }
            for (&i, &v) in ring.iter().zip(&values) {
                self.heights[i] = v;
            }
            let mut next = Vec::new();
            for &i in &ring {
                for n in neighbours(i) {
                    if !queued[n] && !self.heights[n].is_finite() {
                        queued[n] = true;
                        next.push(n);
                    }
                }
            }
            ring = next;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_hole_closes_within_the_range_around_it() {
        let (w, h) = (9, 9);
        let mut heights: Vec<f32> = (0..w * h).map(|i| (i % w) as f32).collect();
        for z in 2..7 {
            for x in 2..7 {
                heights[z * w + x] = f32::NAN;
            }
        }
        let mut m = ElevationModel {
            width: w,
            height: h,
            heights,
            spacing: [1.0; 2],
            nodata: 0,
            georeference: None,
            spacing_from_file: false,
        };
        m.fill_nodata().unwrap();
        assert_eq!(m.nodata, 25);
        assert!(
            m.heights
                .iter()
                .all(|v| v.is_finite() && (0.0..=8.0).contains(v))
        );
        // The middle is near the mean of the ramp around it.
        assert!(
            (m.heights[4 * w + 4] - 4.0).abs() < 0.5,
            "{}",
            m.heights[4 * w + 4]
        );
    }

    #[test]
    fn nothing_known_is_an_error() {
        let mut m = ElevationModel {
            width: 2,
            height: 2,
            heights: vec![f32::NAN; 4],
            spacing: [1.0; 2],
            nodata: 0,
            georeference: None,
            spacing_from_file: false,
        };
        assert!(m.fill_nodata().is_err());
    }
}
