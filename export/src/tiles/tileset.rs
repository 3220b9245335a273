//! The 3D Tiles 1.1 tileset: a root over the world, placed on the globe by an east-north-up
//! frame, coarse tiles of impostor cards, each refined by its fine tiles of branch
//! instances.

use serde_json::{Value, json};

/// The east-north-up frame at (longitude, latitude) in degrees on the WGS84 ellipsoid, as
/// the column-major 4 x 4 matrix 3D Tiles' `transform` takes: tile content in metres east,
/// north and up lands on the globe there.
pub(crate) fn east_north_up(longitude: f64, latitude: f64) -> [f64; 16] {
    let (lon, lat) = (longitude.to_radians(), latitude.to_radians());
    let a = 6_378_137.0f64;
    let e2 = 6.694_379_990_14e-3;
    let n = a / (1.0 - e2 * lat.sin().powi(2)).sqrt();
    let origin = [
        n * lat.cos() * lon.cos(),
        n * lat.cos() * lon.sin(),
        n * (1.0 - e2) * lat.sin(),
    ];
    let east = [-lon.sin(), lon.cos(), 0.0];
    let north = [-lat.sin() * lon.cos(), -lat.sin() * lon.sin(), lat.cos()];
    let up = [lat.cos() * lon.cos(), lat.cos() * lon.sin(), lat.sin()];
    [
        east[0], east[1], east[2], 0.0, north[0], north[1], north[2], 0.0, up[0], up[1], up[2],
        0.0, origin[0], origin[1], origin[2], 1.0,
    ]
}

/// A 3D Tiles `box` bounding volume around a y-up glTF box from `min` to `max` (x, height,
/// z): glTF content is turned z-up by clients, so glTF (x, y, z) is tile (x, -z, y).
pub(crate) fn bounding_box(min: [f32; 3], max: [f32; 3]) -> Value {
    let c = [
        (min[0] + max[0]) * 0.5,
        -(min[2] + max[2]) * 0.5,
        (min[1] + max[1]) * 0.5,
    ];
    let h = [
        (max[0] - min[0]) * 0.5,
        (max[2] - min[2]) * 0.5,
        (max[1] - min[1]) * 0.5,
    ];
    json!({"box": [c[0], c[1], c[2], h[0], 0.0, 0.0, 0.0, h[1], 0.0, 0.0, 0.0, h[2]]})
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_frame_at_zero_zero_points_up_along_x() {
        let m = east_north_up(0.0, 0.0);
        // Up is the x axis, east y, north z; the origin on the equator at the meridian.
        assert_eq!(&m[8..11], &[1.0, 0.0, 0.0]);
        assert!((m[12] - 6_378_137.0).abs() < 1e-6 && m[13].abs() < 1e-6);
        let m = east_north_up(90.0, 90.0);
        assert!((m[14] - 6_356_752.314).abs() < 1e-2, "{}", m[14]);
    }

    #[test]
    fn boxes_turn_y_up_into_z_up() {
        let b = bounding_box([0.0, 10.0, 0.0], [100.0, 30.0, 50.0]);
        let v: Vec<f64> = b["box"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        assert_eq!(&v[..3], &[50.0, -25.0, 20.0]);
        assert_eq!((v[3], v[7], v[11]), (50.0, 25.0, 10.0));
    }
}
