//! cpfg's surface files (`.s`): shapes made of bicubic Bézier patches that the turtle draws
//! whole where a model writes `~` and the surface's letter (`~l(2)`: surface `l` at twice
//! its size). A model's view file names them: `surface: l leaf.s 1 8 4` (letter, file,
//! scale, and how many quads each patch is cut into along its two parameters).
//!
//! A file gives a bounding box (first line), the surface's contact point (where it meets
//! the turtle), its heading and up directions (which become the turtle's), its size (the
//! length its coordinates are divided by), and then patches: a name, a colour line, three
//! lines naming neighbours, and four rows of four control points `x y z`.

use crate::file_lines::Lines;

/// Most patches of one surface.
pub const MAX_PATCHES: usize = 4096;
/// Most surfaces one model names.
pub const MAX_SURFACES: usize = 256;
/// Most quads a patch is cut into along one parameter.
pub const MAX_DIVISIONS: u32 = 64;
/// Most quads the surfaces of one model may be cut into, all together (48 MB of corners).
pub const MAX_QUADS: usize = 1 << 20;
/// Quads along each parameter when the view file gives no count.
pub const DEFAULT_DIVISIONS: u32 = 8;

/// One surface of a model: its geometry from the `.s` file and how the view file draws it.
#[derive(Debug, Clone, PartialEq)]
pub struct Surface {
    /// The letter that draws it after `~`.
    pub letter: char,
    /// Its scale (the view file's; 1 when not given).
    pub scale: f64,
    /// Quads each patch is cut into along its two parameters.
    pub divisions: [u32; 2],
    /// Where the surface meets the turtle, in the file's coordinates.
    pub contact: [f64; 3],
    /// The file's direction that becomes the turtle's heading.
    pub heading: [f64; 3],
    /// The file's direction that becomes the turtle's up.
    pub up: [f64; 3],
    /// The length the file's coordinates are divided by.
    pub size: f64,
    /// The patches: 4 rows of 4 control points each, row by row.
    pub patches: Vec<[[f64; 3]; 16]>,
}

impl Surface {
    /// Reads a `.s` file as the surface `letter` (scale 1, [`DEFAULT_DIVISIONS`]).
    ///
    /// ```
    /// use sylva_lsys::surface::Surface;
    /// let text = "0 1 0 1 0 0\nCONTACT POINT X: 0 Y: 0 Z: 0\nEND POINT X: 0 Y: 1 Z: 0\n\
    ///   HEADING X: 0 Y: 1 Z: 0\nUP X: 0 Y: 0 Z: 1\nSIZE: 1\nsquare\n\
    ///   TOP COLOR: 0 DIFFUSE: 0 BOTTOM COLOR: 0 DIFFUSE: 0\nAL: ~ A: ~ AR: ~\nL: ~ R: ~\nBL: ~ B: ~ BR: ~\n\
    ///   0 0 0  0 0.33 0  0 0.67 0  0 1 0\n0.33 0 0  0.33 0.33 0  0.33 0.67 0  0.33 1 0\n\
    ///   0.67 0 0  0.67 0.33 0  0.67 0.67 0  0.67 1 0\n1 0 0  1 0.33 0  1 0.67 0  1 1 0\n";
    /// let s = Surface::parse(text, 'q')?;
    /// assert_eq!(s.patches.len(), 1);
    /// assert_eq!(s.quads().len(), 64);
    /// # Ok::<(), String>(())
    /// ```
    pub fn parse(text: &str, letter: char) -> Result<Surface, String> {
        let mut lines = Lines::new(text);
        let bounds = lines.numbers("the bounding box (six numbers)")?;
        if bounds.len() != 6 {
            return Err(lines.at("expected the bounding box (six numbers)"));
        }
        let mut surface = Surface {
            letter,
            scale: 1.0,
            divisions: [DEFAULT_DIVISIONS; 2],
            contact: [0.0; 3],
            heading: [0.0, 1.0, 0.0],
            up: [0.0, 0.0, 1.0],
            size: 1.0,
            patches: Vec::new(),
        };
        // The header's labelled lines, in the order the editor writes them.
        let mut line = lines.next_line()?;
        if line.starts_with("PRECISION") {
            line = lines.next_line()?;
        }
        for (label, slot) in [
            ("CONTACT POINT", Some(&mut surface.contact)),
            ("END POINT", None),
            ("HEADING", Some(&mut surface.heading)),
            ("UP", Some(&mut surface.up)),
        ] {
            let Some(rest) = line.strip_prefix(label) else {
                return Err(lines.at(format!("expected '{label}', found '{line}'")));
            };
            let numbers: Vec<f64> = rest
                .split_whitespace()
                .filter_map(|t| t.parse().ok())
                .filter(|v: &f64| v.is_finite())
                .collect();
            if numbers.len() != 3 {
                return Err(lines.at(format!("{label}: expected X, Y and Z")));
            }
            if let Some(slot) = slot {
                *slot = [numbers[0], numbers[1], numbers[2]];
            }
            line = lines.next_line()?;
        }
        surface.size = line
            .strip_prefix("SIZE:")
            .and_then(|v| v.trim().parse::<f64>().ok())
            .filter(|v| v.is_finite() && *v > 0.0)
            .ok_or_else(|| {
                lines.at(format!(
                    "expected 'SIZE:' and a positive length, found '{line}'"
                ))
            })?;
        if length(surface.heading) == 0.0 || length(cross(surface.up, surface.heading)) == 0.0 {
            return Err(lines.at("the heading and up directions must be distinct, non-zero"));
        }
        // Patches: every line of twelve numbers is a row of control points, four rows a
        // patch; names, colours and neighbours lie between them.
        let mut rows: Vec<[f64; 3]> = Vec::with_capacity(16);
        while let Ok(line) = lines.next_line() {
            let numbers: Option<Vec<f64>> = line
                .split_whitespace()
                .map(|t| t.parse::<f64>().ok().filter(|v| v.is_finite()))
                .collect();
            let Some(numbers) = numbers.filter(|n| n.len() == 12) else {
                if !rows.is_empty() {
                    return Err(lines.at(format!("'{line}': expected a row of four points x y z")));
                }
                continue;
            };
            rows.extend(numbers.chunks_exact(3).map(|p| [p[0], p[1], p[2]]));
            if rows.len() == 16 {
                if surface.patches.len() == MAX_PATCHES {
                    return Err(lines.at(format!("more than {MAX_PATCHES} patches")));
                }
                let mut patch = [[0.0; 3]; 16];
                patch.copy_from_slice(&rows);
                surface.patches.push(patch);
                rows.clear();
            }
        }
        if !rows.is_empty() {
            return Err(lines.at("the last patch has fewer than four rows"));
        }
        if surface.patches.is_empty() {
            return Err("no patches".into());
        }
        Ok(surface)
    }

    /// How many quads [`Surface::quads`] gives.
    pub fn quad_count(&self) -> usize {
        let [s, t] = self.divisions.map(|d| d.clamp(1, MAX_DIVISIONS) as usize);
        self.patches.len() * s * t
    }

    /// The surface as quads (corners in order around each), in the turtle's frame: each
    /// point as (along the heading, along the left, along the up) from the contact point,
    /// scaled by `scale / size`. Left is up × heading, as the turtle's is.
    pub fn quads(&self) -> Vec<[[f32; 3]; 4]> {
        let heading = normalized(self.heading);
        let left = normalized(cross(self.up, heading));
        let up = cross(heading, left);
        let factor = self.scale / self.size;
        let local = |p: [f64; 3]| {
            let q = [
                p[0] - self.contact[0],
                p[1] - self.contact[1],
                p[2] - self.contact[2],
            ];
            [
                (dot(q, heading) * factor) as f32,
                (dot(q, left) * factor) as f32,
                (dot(q, up) * factor) as f32,
            ]
        };
        let [ns, nt] = self.divisions.map(|d| d.clamp(1, MAX_DIVISIONS) as usize);
        let mut out = Vec::with_capacity(self.patches.len() * ns * nt);
        for patch in &self.patches {
            let grid: Vec<[f32; 3]> = (0..=ns)
                .flat_map(|i| (0..=nt).map(move |j| (i as f64 / ns as f64, j as f64 / nt as f64)))
                .map(|(s, t)| local(bezier_patch(patch, s, t)))
                .collect();
            let at = |i: usize, j: usize| grid[i * (nt + 1) + j];
            for i in 0..ns {
                for j in 0..nt {
                    out.push([at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
                }
            }
        }
        out
    }
}

/// The point of a bicubic Bézier patch (rows along `s`, columns along `t`).
fn bezier_patch(patch: &[[f64; 3]; 16], s: f64, t: f64) -> [f64; 3] {
    let bernstein = |u: f64| {
        let v = 1.0 - u;
        [v * v * v, 3.0 * u * v * v, 3.0 * u * u * v, u * u * u]
    };
    let (bs, bt) = (bernstein(s), bernstein(t));
    let mut sum = [0.0; 3];
    for (i, ws) in bs.iter().enumerate() {
        for (j, wt) in bt.iter().enumerate() {
            for (axis, v) in sum.iter_mut().zip(patch[i * 4 + j]) {
                *axis += ws * wt * v;
            }
        }
    }
    sum
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn length(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

fn normalized(a: [f64; 3]) -> [f64; 3] {
    let l = length(a);
    [a[0] / l, a[1] / l, a[2] / l]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat patch on the plane z = 0, heading +y, up +z, contact at (0.5, 0, 0), size 2:
    /// the corner (1, 1, 0) lies 1 along the heading and 0.5 to the right, which is -0.5
    /// along the left (left = up x heading = -x), all halved by the size.
    #[test]
    fn points_come_into_the_turtles_frame() {
        let mut text = String::from(
            "0 1 0 1 0 0\nPRECISION S: 8 T: 8\nCONTACT POINT X: 0.5 Y: 0 Z: 0\nEND POINT X: 0.5 Y: 1 Z: 0\n\
             HEADING X: 0 Y: 1 Z: 0\nUP X: 0 Y: 0 Z: 1\nSIZE: 2\np\nTOP COLOR: 0\nAL: ~\nL: ~\nBL: ~\n",
        );
        for i in 0..4 {
            for j in 0..4 {
                text += &format!("{} {} 0  ", i as f64 / 3.0, j as f64 / 3.0);
            }
            text += "\n";
        }
        // Rows in the file run along x (s), columns along y (t).
        let mut s = Surface::parse(&text, 'p').unwrap();
        s.divisions = [1, 1];
        let quads = s.quads();
        assert_eq!(quads.len(), 1);
        let far = quads[0][2];
        assert!(
            (far[0] - 0.5).abs() < 1e-6 && (far[1] + 0.25).abs() < 1e-6 && far[2].abs() < 1e-6,
            "{far:?}"
        );
        let near = quads[0][0];
        assert!(
            (near[0]).abs() < 1e-6 && (near[1] - 0.25).abs() < 1e-6,
            "{near:?}"
        );
        // A patch's midpoint is its control net's Bernstein mean: for this evenly spaced
        // net, the centre (0.5, 0.5) -> 0.25 along the heading, 0 across.
        s.divisions = [2, 2];
        let centre = s.quads()[0][2];
        assert!(
            (centre[0] - 0.25).abs() < 1e-6 && centre[1].abs() < 1e-6,
            "{centre:?}"
        );
    }

    #[test]
    fn bad_files_are_errors_with_their_line() {
        assert!(
            Surface::parse("1 2 3\n", 'a')
                .unwrap_err()
                .contains("bounding box")
        );
        let no_up = "0 1 0 1 0 0\nCONTACT POINT X: 0 Y: 0 Z: 0\nEND POINT X: 0 Y: 1 Z: 0\nHEADING X: 0 Y: 1 Z: 0\nSIZE: 1\n";
        assert!(
            Surface::parse(no_up, 'a')
                .unwrap_err()
                .starts_with("line 5:")
        );
        let flat = "0 1 0 1 0 0\nCONTACT POINT X: 0 Y: 0 Z: 0\nEND POINT X: 0 Y: 1 Z: 0\nHEADING X: 0 Y: 1 Z: 0\nUP X: 0 Y: 2 Z: 0\nSIZE: 1\n";
        assert!(Surface::parse(flat, 'a').unwrap_err().contains("distinct"));
        let short = "0 1 0 1 0 0\nCONTACT POINT X: 0 Y: 0 Z: 0\nEND POINT X: 0 Y: 1 Z: 0\nHEADING X: 0 Y: 1 Z: 0\nUP X: 0 Y: 0 Z: 1\nSIZE: 1\np\n0 0 0 0 0 0 0 0 0 0 0 0\nq\n";
        assert!(
            Surface::parse(short, 'a')
                .unwrap_err()
                .contains("row of four points")
        );
    }
}
