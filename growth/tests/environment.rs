//! cpfg's communication module `?E` answered by the voxel space's light: an open
//! L-system grows in the open and stops under a roof.

use sylva_growth::{LightEnvironment, Response, Sky, SunPath, VoxelGrid};
use sylva_lsys::{Dialect, LSystem, Limits};
use sylva_turtle::{TurtleOptions, glam::Vec3};

fn grown(roof: bool) -> usize {
    let plant = LSystem::parse_dialect(
        "Lsystem: 1\nAxiom: A ?E(1,1)\nA > ?E(l,a) : l > 0.5 --> F(1) A\nendlsystem",
        Dialect::Cpfg,
    )
    .unwrap();
    let mut grid = VoxelGrid::new(Vec3::splat(-10.0), Vec3::splat(12.0), 0.5).unwrap();
    if roof {
        // A 4 m square roof 4.25 m up: open sky around the young apex, less as it nears.
        for x in -4..4 {
            for z in -4..4 {
                if let Some(cell) = grid.cell_of(Vec3::new(x as f32 * 0.5, 4.25, z as f32 * 0.5)) {
                    grid.occupy(cell);
                }
            }
        }
    }
    let sky = Sky::new(
        SunPath::Arc {
            positions: 7,
            tilt_degrees: 0.0,
        },
        64,
        1,
    );
    let mut light = LightEnvironment::new(
        grid,
        sky,
        Response::pioneer(),
        &TurtleOptions::default(),
        Vec3::ZERO,
    );
    let word = plant.derive_in(8, 0, &Limits::DEFAULT, &mut light).unwrap();
    word.iter().filter(|m| m.name == "F").count()
}

#[test]
fn an_apex_grows_in_the_open_and_stops_under_a_roof() {
    assert_eq!(grown(false), 8);
    let under = grown(true);
    eprintln!("under the roof the apex stops after {under} steps");
    assert!((1..8).contains(&under), "{under}");
}
