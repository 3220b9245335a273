//! Ground colours by slope and altitude: grass on the flats, soil on slopes, rock on cliffs,
//! snow on the heights. One palette, so every client of the terrain paints it alike (the
//! viewer's shader repeats these numbers).

use glam::Vec3;

use crate::mesh::TerrainMesh;

/// Linear RGB of grass, soil, rock and snow.
pub const GRASS: [f32; 3] = [0.20, 0.30, 0.09];
/// Bare soil on moderate slopes.
pub const SOIL: [f32; 3] = [0.30, 0.23, 0.14];
/// Rock on steep slopes.
pub const ROCK: [f32; 3] = [0.36, 0.35, 0.33];
/// Snow on the highest ground.
pub const SNOW: [f32; 3] = [0.85, 0.87, 0.90];

fn smoothstep(lo: f32, hi: f32, x: f32) -> f32 {
    let t = ((x - lo) / (hi - lo)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// The ground colour where the surface normal's up component is `up` (1 flat, 0 vertical)
/// at relative height `height` (0 the lowest ground, 1 the highest): soil from about 23
/// degrees of slope, rock from about 41, snow over the top tenth where it is not rock.
///
/// ```
/// use sylva_terrain::ground::{GRASS, ground_colour};
/// assert_eq!(ground_colour(1.0, 0.0), GRASS); // flat and low: grass
/// let cliff = ground_colour(0.3, 0.5);
/// assert!(cliff[0] > GRASS[0] && cliff[2] > GRASS[2]); // steep: rock
/// ```
pub fn ground_colour(up: f32, height: f32) -> [f32; 3] {
    let slope = 1.0 - up.clamp(0.0, 1.0);
    let soil = smoothstep(0.08, 0.25, slope);
    let rock = smoothstep(0.25, 0.45, slope);
    let snow = smoothstep(0.80, 0.90, height) * (1.0 - rock);
    let [grass, soil_colour, rock_colour, snow_colour] = [GRASS, SOIL, ROCK, SNOW].map(Vec3::from);
    grass
        .lerp(soil_colour, soil)
        .lerp(rock_colour, rock)
        .lerp(snow_colour, snow)
        .to_array()
}

impl TerrainMesh {
    /// The ground colour of every vertex ([`ground_colour`]), heights taken relative to the
    /// mesh's own lowest and highest vertex.
    pub fn ground_colours(&self) -> Vec<[f32; 3]> {
        self.ground_colours_under_snow(0.0)
    }

    /// [`TerrainMesh::ground_colours`] with `snow` (0 to 1) lying on the ground as well: a
    /// winter's day of a forest drawn with a season. Snow settles on the flats and slides off
    /// slopes of over about 40 degrees.
    ///
    /// ```
    /// use sylva_terrain::DiamondSquare;
    /// let terrain = DiamondSquare::new(9).with_seed(1).with_amplitude(0.1).generate()?;
    /// let mesh = terrain.mesh(1)?;
    /// let (bare, white) = (mesh.ground_colours(), mesh.ground_colours_under_snow(1.0));
    /// assert!(white[0][2] > bare[0][2] + 0.3); // nearly flat ground: snow-white
    /// # Ok::<(), sylva_terrain::TerrainError>(())
    /// ```
    pub fn ground_colours_under_snow(&self, snow: f32) -> Vec<[f32; 3]> {
        let snow = if snow.is_finite() {
            snow.clamp(0.0, 1.0)
        } else {
            0.0
        };
        let (lo, hi) = self
            .vertices
            .iter()
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), v| {
                (lo.min(v.position[1]), hi.max(v.position[1]))
            });
        let span = (hi - lo).max(1e-6);
        self.vertices
            .iter()
            .map(|v| {
                let ground = Vec3::from(ground_colour(v.normal[1], (v.position[1] - lo) / span));
                let lying = snow * smoothstep(0.7, 0.85, v.normal[1]);
                ground.lerp(Vec3::from(SNOW), lying).to_array()
            })
            .collect()
    }
}
