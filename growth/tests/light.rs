//! Known answers for light: open sky, a plate overhead, a half-space, and how the estimate's
//! spread falls with the number of rays.

use sylva_growth::glam::{UVec3, Vec3};
use sylva_growth::{Sky, SunPath, VoxelGrid, march, voxelise_triangles};

fn sky(rays: u32, seed: u64) -> Sky {
    Sky::new(
        SunPath::Arc {
            positions: 9,
            tilt_degrees: 30.0,
        },
        rays,
        seed,
    )
}

fn grid() -> VoxelGrid {
    VoxelGrid::new(
        Vec3::new(-10.0, 0.0, -10.0),
        Vec3::new(10.0, 10.0, 10.0),
        0.1,
    )
    .unwrap()
}

/// The grid with every voxel beyond x = 0.1 occupied.
fn half_space() -> VoxelGrid {
    let mut g = grid();
    for z in 0..200 {
        for y in 0..100 {
            for x in 101..200 {
                g.occupy(UVec3::new(x, y, z));
            }
        }
    }
    g
}

#[test]
fn open_sky_gives_one() {
    let l = sky(256, 1).light_at(&grid(), Vec3::new(0.0, 1.0, 0.0));
    assert_eq!((l.direct, l.ambient), (1.0, 1.0));
}

#[test]
fn under_the_middle_of_a_large_plate_there_is_no_direct_and_almost_no_ambient_light() {
    let mut g = grid();
    // A 20 m plate 1 m above the point: only rays within atan(1/10) of the horizon pass.
    let plate = [
        Vec3::new(-10.0, 2.0, -10.0),
        Vec3::new(10.0, 2.0, -10.0),
        Vec3::new(10.0, 2.0, 10.0),
        Vec3::new(-10.0, 2.0, 10.0),
    ];
    voxelise_triangles(&mut g, &plate, &[0, 1, 2, 0, 2, 3]);
    let l = sky(1024, 2).light_at(&g, Vec3::new(0.0, 1.0, 0.0));
    assert_eq!(l.direct, 0.0);
    // A uniform hemisphere puts sin(atan(0.1)) ~ 0.0995 of its rays below 5.7 degrees.
    assert!(l.ambient < 0.13, "{}", l.ambient);
}

/// A wall filling the half-space x > 0.05 beside the point hides half of a uniform
/// hemisphere. With n rays the estimate is binomial: standard deviation sqrt(p (1 - p) / n),
/// so 1,024 rays give 0.5 within 4 sigma = 0.0625 (a false failure once in 15,000 seeds).
#[test]
fn a_half_space_hides_half_the_sky() {
    let g = half_space();
    let n = 1024;
    let sigma = (0.25f32 / n as f32).sqrt();
    for seed in 0..5 {
        let l = sky(n, seed).light_at(&g, Vec3::new(0.05, 0.5, 0.0));
        assert!(
            (l.ambient - 0.5).abs() < 4.0 * sigma,
            "seed {seed}: {}",
            l.ambient
        );
    }
}

/// The paper's figure 2: more rays, less spread. Sixteen times the rays should divide the
/// standard deviation over seeds by about four.
#[test]
fn the_spread_falls_as_one_over_the_square_root_of_the_rays() {
    let g = half_space();
    let spread = |rays: u32| {
        let v: Vec<f32> = (0..200)
            .map(|seed| {
                sky(rays, seed)
                    .light_at(&g, Vec3::new(0.05, 0.5, 0.0))
                    .ambient
            })
            .collect();
        let mean = v.iter().sum::<f32>() / v.len() as f32;
        (v.iter().map(|x| (x - mean).powi(2)).sum::<f32>() / (v.len() - 1) as f32).sqrt()
    };
    let (few, many) = (spread(32), spread(512));
    let ratio = few / many;
    eprintln!("spread with 32 rays {few:.4}, with 512 {many:.4}: ratio {ratio:.2} (expected 4)");
    assert!((3.0..5.3).contains(&ratio), "{ratio}");
    // And each is near the binomial value.
    assert!((few - (0.25f32 / 32.0).sqrt()).abs() < 0.03, "{few}");
}

#[test]
fn the_hierarchy_takes_fewer_steps_through_empty_space() {
    let g = grid();
    let from = Vec3::new(0.0, 0.5, 0.0);
    let (with, without) = sky(256, 3).hemisphere.iter().fold((0, 0), |(a, b), &d| {
        (
            a + march(&g, from, d, true).steps,
            b + march(&g, from, d, false).steps,
        )
    });
    assert!(with * 4 < without, "{with} against {without}");
}
