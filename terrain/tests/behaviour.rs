//! Determinism, seams, sampling, erosion, meshes, import/export and bad input.

use std::io::Cursor;

use proptest::prelude::*;
use sylva_terrain::glam::{Vec2, Vec3};
use sylva_terrain::{
    DiamondSquare, EdgeMode, FlatPlane, HeightField, HeightRange, Heightmap, HydraulicErosion,
    OutOfRange, TerrainError, ThermalErosion,
};

fn map(seed: u64) -> Heightmap {
    DiamondSquare::new(129).with_seed(seed).generate().unwrap()
}

#[test]
fn same_seed_same_heights_other_seed_other_heights() {
    assert_eq!(map(5), map(5));
    assert_ne!(map(5), map(6));
}

#[test]
fn wrapped_maps_have_equal_opposite_edges() {
    let m = DiamondSquare::new(65)
        .with_wrap(true)
        .with_seed(2)
        .generate()
        .unwrap();
    let mut s = m.clone();
    s.smooth(1.5, EdgeMode::Wrap).unwrap();
    for m in [&m, &s] {
        for i in 0..65 {
            assert_eq!(m.get(0, i), m.get(64, i));
            assert_eq!(m.get(i, 0), m.get(i, 64));
        }
    }
}

#[test]
fn neighbouring_tiles_meet_without_a_seam() {
    let tile = |tx, tz| {
        DiamondSquare::new(65)
            .with_seed(9)
            .with_tile(tx, tz)
            .generate()
            .unwrap()
    };
    let (a, right, below) = (tile(0, 0), tile(1, 0), tile(0, 1));
    for i in 0..65 {
        assert_eq!(a.get(64, i), right.get(0, i), "x edge, row {i}");
        assert_eq!(a.get(i, 64), below.get(i, 0), "z edge, column {i}");
    }
    assert_eq!(right.origin(), Vec2::new(64.0, 0.0));
    assert_eq!(right.height(64.0, 10.0), a.height(64.0, 10.0));
}

#[test]
fn fixed_corners_are_kept() {
    let m = DiamondSquare::new(33)
        .with_corners([1.0, 2.0, 3.0, 4.0])
        .generate()
        .unwrap();
    assert_eq!(
        [m.get(0, 0), m.get(32, 0), m.get(0, 32), m.get(32, 32)],
        [1.0, 2.0, 3.0, 4.0]
    );
}

#[test]
fn bilinear_sampling_is_exact_at_grid_points_and_between() {
    let m = map(1).with_origin(Vec2::new(-10.0, 5.0));
    for (x, z) in [(0, 0), (3, 7), (128, 128), (64, 1)] {
        assert_eq!(m.height(-10.0 + x as f32, 5.0 + z as f32), m.get(x, z));
    }
    let mid = m.height(-10.0 + 3.5, 5.0 + 7.0);
    assert!((mid - 0.5 * (m.get(3, 7) + m.get(4, 7))).abs() < 1e-4);
    // Outside the map: clamped to the edge, never NaN.
    assert_eq!(m.height(-1e6, 5.0), m.get(0, 0));
    assert!(m.height(f32::NAN, 0.0).is_finite());
}

#[test]
fn normals_point_up_and_lean_away_from_slopes() {
    let plane = FlatPlane {
        height: 2.0,
        min: Vec2::ZERO,
        max: Vec2::splat(10.0),
    };
    assert_eq!(plane.normal(3.0, 4.0), Vec3::Y);
    assert_eq!(Heightmap::flat(9, 1.0).unwrap().normal(4.0, 4.0), Vec3::Y);
    let ramp: Vec<f32> = (0..81).map(|i| (i % 9) as f32).collect();
    let ramp = Heightmap::from_heights(9, 1.0, ramp).unwrap();
    let n = ramp.normal(4.0, 4.0);
    assert!(
        (n - Vec3::new(-1.0, 1.0, 0.0).normalize()).length() < 1e-5,
        "{n}"
    );
}

#[test]
fn thermal_erosion_conserves_mass_and_flattens_cliffs() {
    let mut m = DiamondSquare::new(65)
        .with_roughness(0.2)
        .with_amplitude(40.0)
        .with_seed(1)
        .generate()
        .unwrap();
    let slope = |m: &Heightmap| {
        (0..64)
            .flat_map(|z| (0..64).map(move |x| (x, z)))
            .map(|(x, z)| (m.get(x + 1, z) - m.get(x, z)).abs())
            .fold(0.0, f32::max)
    };
    let (mass0, slope0) = (
        m.heights().iter().map(|&h| f64::from(h)).sum::<f64>(),
        slope(&m),
    );
    ThermalErosion::new(0.5, 0.25, 200).apply(&mut m).unwrap();
    let mass1: f64 = m.heights().iter().map(|&h| f64::from(h)).sum();
    assert!(
        (mass1 - mass0).abs() < 1e-6 * mass0.abs().max(1.0) * 100.0,
        "{mass0} -> {mass1}"
    );
    assert!(slope(&m) < 0.5 * slope0, "{slope0} -> {}", slope(&m));
}

#[test]
fn hydraulic_erosion_is_deterministic_and_carves() {
    let base = DiamondSquare::new(129)
        .with_seed(3)
        .with_amplitude(30.0)
        .generate()
        .unwrap();
    let run = |seed| {
        let mut m = base.clone();
        HydraulicErosion::new(5_000, seed).apply(&mut m).unwrap();
        m
    };
    let (a, b) = (run(1), run(1));
    assert_eq!(a, b);
    assert_ne!(a, run(2));
    assert_ne!(a, base);
    assert!(a.heights().iter().all(|h| h.is_finite()));
}

#[test]
fn mesh_strides_give_levels_of_detail_facing_up() {
    let m = map(4);
    for stride in [1, 2, 8] {
        let mesh = m.mesh(stride).unwrap();
        let side = 128 / stride + 1;
        assert_eq!(mesh.vertices.len(), side * side);
        assert_eq!(mesh.indices.len(), (side - 1) * (side - 1) * 6);
        for t in mesh.indices.chunks_exact(3) {
            let p: Vec<Vec3> = t
                .iter()
                .map(|&i| Vec3::from(mesh.vertices[i as usize].position))
                .collect();
            assert!((p[1] - p[0]).cross(p[2] - p[0]).y > 0.0);
        }
    }
    assert!(m.mesh(3).is_err());
    assert!(m.mesh(0).is_err());
}

#[test]
fn png16_round_trip_is_exact_at_16_bits() {
    let m = map(8);
    let mut png = Vec::new();
    let range = m.write_png16(&mut png).unwrap();
    let back = Heightmap::read_png16(Cursor::new(&png), None).unwrap();
    assert_eq!(back.size(), m.size());
    assert_eq!(back.spacing(), m.spacing());
    let step = (range.max - range.min) / 65535.0;
    for (a, b) in m.heights().iter().zip(back.heights()) {
        assert!((a - b).abs() <= 0.51 * step + 1e-6);
    }
    let mut again = Vec::new();
    back.write_png16(&mut again).unwrap();
    let back2 = Heightmap::read_png16(Cursor::new(&again), None).unwrap();
    assert_eq!(back2.heights(), back.heights());
}

#[test]
fn raw_round_trips() {
    let m = map(9);
    let (raw, range) = m.to_raw16();
    assert_eq!(raw.len(), 129 * 129 * 2);
    let back = Heightmap::from_raw16(&raw, range, 1.0).unwrap();
    assert_eq!(back.to_raw16().0, raw);
    let exact = Heightmap::from_raw32(&m.to_raw32(), 1.0).unwrap();
    assert_eq!(exact.heights(), m.heights());
}

#[test]
fn bad_input_gives_clear_errors() {
    assert!(matches!(
        DiamondSquare::new(100).generate(),
        Err(TerrainError::BadSize(100))
    ));
    assert!(matches!(
        DiamondSquare::new(0).generate(),
        Err(TerrainError::BadSize(0))
    ));
    assert!(matches!(
        DiamondSquare::new(usize::MAX).generate(),
        Err(TerrainError::BadSize(usize::MAX))
    ));
    assert!(matches!(
        DiamondSquare::new((1 << 20) + 1).generate(),
        Err(TerrainError::BadSize(1_048_577))
    ));
    assert!(matches!(
        DiamondSquare::new(33).with_spacing(0.0).generate(),
        Err(TerrainError::OutOfRange(OutOfRange {
            name: "spacing",
            ..
        }))
    ));
    assert!(matches!(
        DiamondSquare::new(33).with_spacing(-1.0).generate(),
        Err(TerrainError::OutOfRange(_))
    ));
    assert!(matches!(
        DiamondSquare::new(33).with_roughness(f32::NAN).generate(),
        Err(TerrainError::OutOfRange(OutOfRange {
            name: "roughness",
            ..
        }))
    ));
    assert!(matches!(
        DiamondSquare::new(33)
            .with_amplitude(f32::INFINITY)
            .generate(),
        Err(TerrainError::OutOfRange(_))
    ));
    let mut m = map(1);
    assert!(m.smooth(f32::NAN, EdgeMode::Mirror).is_err());
    assert!(m.smooth(-1.0, EdgeMode::Mirror).is_err());
    assert!(Heightmap::from_raw16(&[0; 10], HeightRange { min: 0.0, max: 1.0 }, 1.0).is_err());
    assert!(Heightmap::from_raw16(&[0; 8], HeightRange { min: 1.0, max: 1.0 }, 1.0).is_err());
    assert!(Heightmap::from_raw32(&[0; 7], 1.0).is_err());
    assert!(Heightmap::read_png16(Cursor::new(b"not a png".to_vec()), None).is_err());
    assert!(
        Heightmap::from_heights(
            3,
            1.0,
            vec![0.0, 1.0, f32::NAN, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]
        )
        .is_err()
    );
    assert!(ThermalErosion::new(0.5, 2.0, 1).apply(&mut m).is_err());
    let mut bad = HydraulicErosion::default();
    bad.inertia = f32::NAN;
    assert!(bad.apply(&mut m).is_err());
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 32, ..ProptestConfig::default() })]

    #[test]
    fn generation_is_finite_and_deterministic(seed: u64, h in 0.0f32..=1.0, levels in 1u32..7, wrap: bool, sigma in 0.0f32..4.0) {
        let size = (1usize << levels) + 1;
        let build = || {
            let mut m = DiamondSquare::new(size).with_seed(seed).with_roughness(h).with_wrap(wrap).generate().unwrap();
            m.smooth(sigma, if wrap { EdgeMode::Wrap } else { EdgeMode::Mirror }).unwrap();
            m
        };
        let m = build();
        prop_assert!(m.heights().iter().all(|v| v.is_finite()));
        prop_assert_eq!(m, build());
    }
}

/// A PNG whose header claims `side` x `side` 16-bit grey samples but whose data is one
/// empty compressed block: what a hostile or truncated file looks like.
fn forged_png(side: u32) -> Vec<u8> {
    fn crc32(bytes: &[u8]) -> u32 {
        let mut crc = !0u32;
        for &b in bytes {
            crc ^= u32::from(b);
            for _ in 0..8 {
                crc = if crc & 1 == 1 {
                    (crc >> 1) ^ 0xedb8_8320
                } else {
                    crc >> 1
                };
            }
        }
        !crc
    }
    fn chunk(out: &mut Vec<u8>, kind: &[u8; 4], data: &[u8]) {
        out.extend_from_slice(&(data.len() as u32).to_be_bytes());
        let start = out.len();
        out.extend_from_slice(kind);
        out.extend_from_slice(data);
        let crc = crc32(&out[start..]);
        out.extend_from_slice(&crc.to_be_bytes());
    }
    let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
    let mut header = Vec::new();
    header.extend_from_slice(&side.to_be_bytes());
    header.extend_from_slice(&side.to_be_bytes());
    header.extend_from_slice(&[16, 0, 0, 0, 0]); // 16-bit greyscale, no interlace
    chunk(&mut png, b"IHDR", &header);
    chunk(&mut png, b"tEXt", b"sylva:heights\x000 1 1");
    chunk(
        &mut png,
        b"IDAT",
        &[0x78, 0x01, 0x03, 0x00, 0x00, 0x00, 0x00, 0x01],
    );
    chunk(&mut png, b"IEND", &[]);
    png
}

/// Headers that promise more than the file holds, or more than any heightmap may be, end in
/// an error; the largest legal size is read only as far as the data goes.
#[test]
fn forged_png_headers_are_errors_not_allocations() {
    for side in [3, 4097, 16_385, 16_386, 100_000, u32::MAX] {
        let result = Heightmap::read_png16(Cursor::new(forged_png(side)), None);
        assert!(result.is_err(), "side {side}");
    }
    // The forgery is a well-formed PNG apart from its missing rows: a real 3 x 3 map reads.
    let m = Heightmap::flat(3, 1.0).unwrap();
    let mut png = Vec::new();
    m.write_png16(&mut png).unwrap();
    assert_eq!(
        Heightmap::read_png16(Cursor::new(png), None)
            .unwrap()
            .size(),
        3
    );
}

/// The ground palette: grass on the flats, soil then rock as the slope rises, snow on the
/// heights but not on cliffs; one colour per mesh vertex.
#[test]
fn ground_colours_follow_slope_and_altitude() {
    use sylva_terrain::ground::{GRASS, ROCK, SNOW, SOIL, ground_colour};
    let near = |a: [f32; 3], b: [f32; 3]| a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-5);
    assert!(near(ground_colour(1.0, 0.2), GRASS));
    assert!(near(ground_colour(0.75, 0.2), SOIL));
    assert!(near(ground_colour(0.5, 0.2), ROCK));
    assert!(near(ground_colour(1.0, 1.0), SNOW));
    assert!(near(ground_colour(0.5, 1.0), ROCK));
    let steps = [1.0, 0.95, 0.9, 0.85, 0.8, 0.75, 0.7, 0.6, 0.5];
    let rockiness: Vec<f32> = steps.iter().map(|&up| ground_colour(up, 0.3)[2]).collect();
    assert!(
        rockiness.windows(2).all(|w| w[1] >= w[0] - 1e-6),
        "{rockiness:?}"
    );
    let m = DiamondSquare::new(33)
        .with_seed(3)
        .generate()
        .unwrap()
        .mesh(1)
        .unwrap();
    let colours = m.ground_colours();
    assert_eq!(colours.len(), m.vertices.len());
    assert!(colours.iter().flatten().all(|c| (0.0..=1.0).contains(c)));
}
