//! Reading obstacles from Wavefront OBJ files: vertices and faces only (polygons are fanned
//! into triangles), with the file's size limited and errors at their line.

use std::path::Path;

use glam::Vec3;

use crate::error::GrowthError;

/// Largest OBJ file read, in bytes.
pub const MAX_OBJ_BYTES: u64 = 256 << 20;

/// The triangles of an OBJ file: positions and three indices per triangle. Texture and
/// normal references (`f 1/2/3`) and other statements are passed over; negative indices
/// count from the end as OBJ allows. Faces with indices out of range are errors.
///
/// ```no_run
/// let (positions, triangles) = sylva_growth::read_obj("rock.obj")?;
/// # Ok::<(), sylva_growth::GrowthError>(())
/// ```
pub fn read_obj(path: impl AsRef<Path>) -> Result<(Vec<Vec3>, Vec<u32>), GrowthError> {
    let path = path.as_ref();
    let text = sylva_base::text_file::read(path, MAX_OBJ_BYTES)?;
    parse_obj(&text, path)
}

pub(crate) fn parse_obj(text: &str, name: &Path) -> Result<(Vec<Vec3>, Vec<u32>), GrowthError> {
    let err = |line: usize, message: String| GrowthError::MeshFile {
        file: name.to_path_buf(),
        line,
        message,
    };
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                let xyz: Vec<f32> = words.take(3).map_while(|w| w.parse().ok()).collect();
                match xyz.as_slice() {
                    [x, y, z] if xyz.iter().all(|c| c.is_finite()) => {
                        positions.push(Vec3::new(*x, *y, *z));
                    }
                    _ => return Err(err(n + 1, "a vertex needs three finite numbers".into())),
                }
            }
            Some("f") => {
                let mut face = Vec::new();
                for w in words {
                    let first = w.split('/').next().unwrap_or("");
                    let i: i64 = first
                        .parse()
                        .map_err(|_| err(n + 1, format!("'{w}' is not a vertex index")))?;
                    let index = if i < 0 {
                        positions.len() as i64 + i
                    } else {
                        i - 1
                    };
                    if index < 0 || index >= positions.len() as i64 {
                        return Err(err(
                            n + 1,
                            format!("vertex {i} does not exist ({} so far)", positions.len()),
                        ));
                    }
                    face.push(index as u32);
                }
                if face.len() < 3 {
                    return Err(err(n + 1, "a face needs three vertices".into()));
                }
                for k in 1..face.len() - 1 {
                    triangles.extend_from_slice(&[face[0], face[k], face[k + 1]]);
                }
            }
            _ => {}
        }
    }
    Ok((positions, triangles))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quads_are_fanned_and_bad_faces_are_errors_at_their_line() {
        let (p, t) = parse_obj(
            "# a quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1/1 2/2 3/3 -1\n",
            Path::new("q.obj"),
        )
        .unwrap();
        assert_eq!(p.len(), 4);
        assert_eq!(t, vec![0, 1, 2, 0, 2, 3]);
        let e = parse_obj("v 0 0 0\nf 1 2 3\n", Path::new("bad.obj")).unwrap_err();
        assert_eq!(
            e.to_string(),
            "bad.obj:2: vertex 2 does not exist (1 so far)"
        );
        assert!(parse_obj("v 0 nan 0\n", Path::new("n.obj")).is_err());
    }
}
