//! The materials a frame draws with, as one array the shader indexes by each vertex's
//! material number: the terrain, then each distinct bark and leaf material of the variants
//! and of their proxies.
//!
//! One array bound once per pass, rather than a material bound per draw, because binds cost:
//! lavapipe (Mesa 22.3) spends about 0.4 ms on each descriptor-set bind and keeps about
//! 190 KB of it until the device is dropped, which made software frames about six times slower
//! and grew the viewer by up to a gigabyte a frame.

use sylva::forest::Phenology;

use crate::textures::{bark_layer, leaf_layer};
use crate::world::World;

/// The terrain's base colour (linear RGB), under its ground colours.
pub(crate) const TERRAIN: [f32; 3] = [0.36, 0.33, 0.20];

/// Flat colours of the id mode: terrain, bark, leaves (sky is the clear colour, black).
pub(crate) const ID_TERRAIN: [f32; 3] = [1.0, 0.0, 0.0];
pub(crate) const ID_BARK: [f32; 3] = [0.0, 1.0, 0.0];
pub(crate) const ID_LEAF: [f32; 3] = [0.0, 0.0, 1.0];

/// How much darker a proxy's crown is than its leaf colour, in every season.
const PROXY_SHADE: f32 = 0.6;

/// Bytes per material in the shader's array: colour (rgb, texture layer plus one), id, and
/// the species' year (leaf out, leaf fall, whether it has one; spring colour; autumn colour).
pub(crate) const MATERIAL_BYTES: usize = 80;

/// One material: colour, flat id colour, the texture layer plus one (0: untextured; -1:
/// the terrain, which the shader paints by slope and altitude), and the year its leaves
/// follow (none for bark, the terrain, the floor's plants and evergreens).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Material {
    colour: [f32; 3],
    id: [f32; 3],
    layer: f32,
    year: Option<Phenology>,
}

impl Material {
    fn new(colour: [f32; 3], id: [f32; 3], layer: f32) -> Material {
        Material {
            colour,
            id,
            layer,
            year: None,
        }
    }

    /// This leaf material following `year` when it is a deciduous one.
    fn following(mut self, year: Option<Phenology>) -> Material {
        self.year = year.filter(|p| !p.evergreen);
        self
    }

    /// The shader's 20 floats: see [`MATERIAL_BYTES`].
    fn floats(&self) -> [f32; 20] {
        let [r, g, b] = self.colour;
        let [ir, ig, ib] = self.id;
        let (season, spring, autumn) = match self.year {
            Some(p) => ([p.leaf_out, p.leaf_fall, 1.0, 0.0], p.spring, p.autumn),
            None => ([0.0; 4], [0.0; 3], [0.0; 3]),
        };
        [
            r, g, b, self.layer, ir, ig, ib, 1.0, season[0], season[1], season[2], season[3],
            spring[0], spring[1], spring[2], 0.0, autumn[0], autumn[1], autumn[2], 0.0,
        ]
    }
}

/// The world's materials, deduplicated, and which of them each variant uses.
#[derive(Debug)]
pub(crate) struct Materials {
    /// The array's contents, [`MATERIAL_BYTES`] per material.
    pub(crate) bytes: Vec<u8>,
    /// (bark, leaves) material of each variant.
    pub(crate) variants: Vec<(u32, u32)>,
    /// (bark, leaves) material of each variant's proxy: untextured, the crown darker than
    /// the leaf colour ([`PROXY_SHADE`]), as the leaf cards' texture and the gaps between
    /// them darken a real crown.
    pub(crate) proxies: Vec<(u32, u32)>,
}

impl Materials {
    /// The materials of `world`'s variants and proxies; material 0 is the terrain.
    pub(crate) fn of(world: &World) -> Materials {
        let mut list: Vec<Material> = vec![Material::new(TERRAIN, ID_TERRAIN, -1.0)];
        // Variants of a species share their materials: each is stored once.
        let mut intern = |m: Material| -> u32 {
            let index = list
                .iter()
                .position(|known| *known == m)
                .unwrap_or_else(|| {
                    list.push(m);
                    list.len() - 1
                });
            index as u32
        };
        let variants = world
            .variants
            .iter()
            .map(|v| {
                (
                    intern(Material::new(
                        v.bark_colour,
                        ID_BARK,
                        1.0 + bark_layer(v.bark_pattern) as f32,
                    )),
                    intern(
                        Material::new(
                            v.leaf_colour,
                            ID_LEAF,
                            if v.textured_leaves {
                                1.0 + leaf_layer(v.leaf_shape) as f32
                            } else {
                                0.0
                            },
                        )
                        .following(v.phenology),
                    ),
                )
            })
            .collect();
        let proxies = world
            .variants
            .iter()
            .map(|v| {
                (
                    intern(Material::new(v.bark_colour, ID_BARK, 0.0)),
                    intern(
                        Material::new(v.leaf_colour.map(|c| c * PROXY_SHADE), ID_LEAF, 0.0)
                            .following(v.phenology.map(|p| Phenology {
                                spring: p.spring.map(|c| c * PROXY_SHADE),
                                autumn: p.autumn.map(|c| c * PROXY_SHADE),
                                ..p
                            })),
                    ),
                )
            })
            .collect();
        let bytes = list
            .iter()
            .flat_map(|m| bytemuck::cast::<[f32; 20], [u8; MATERIAL_BYTES]>(m.floats()))
            .collect();
        Materials {
            bytes,
            variants,
            proxies,
        }
    }

    /// How many materials the array holds.
    pub(crate) fn count(&self) -> usize {
        self.bytes.len() / MATERIAL_BYTES
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::world::SceneOptions;

    /// Variants of one species share their materials; each material is stored once; the
    /// terrain is material 0 and the proxies are untextured.
    #[test]
    fn each_distinct_material_is_stored_once() {
        let options = SceneOptions {
            floor: false,
            ..SceneOptions::small(5, 150.0)
        };
        let world = World::build(options).expect("world builds");
        let materials = Materials::of(&world);
        assert!(world.variants.len() > 2, "several variants per species");
        assert_eq!(materials.variants.len(), world.variants.len());
        assert_eq!(materials.proxies.len(), world.variants.len());
        let floats: &[f32] = bytemuck::cast_slice(&materials.bytes);
        let records: Vec<&[f32]> = floats.chunks(MATERIAL_BYTES / 4).collect();
        assert_eq!(records.len(), materials.count());
        for (i, a) in records.iter().enumerate() {
            assert!(
                records[i + 1..].iter().all(|b| a != b),
                "material {i} stored twice"
            );
        }
        // Two species: terrain, two textured and two untextured materials each.
        assert_eq!(materials.count(), 1 + 2 * 4);
        assert_eq!(records[0][3], -1.0, "material 0 is the terrain");
        for (&(bark, leaves), &(proxy_bark, proxy_leaves)) in
            materials.variants.iter().zip(&materials.proxies)
        {
            assert!(records[bark as usize][3] >= 1.0 && records[leaves as usize][3] >= 1.0);
            assert_eq!(records[proxy_bark as usize][3], 0.0);
            assert_eq!(records[proxy_leaves as usize][3], 0.0);
        }
    }

    /// The floor's kinds are variants after the trees': grass blades untextured, ferns on
    /// their cards' texture.
    #[test]
    fn the_floor_has_its_own_materials() {
        let world = World::build(SceneOptions::small(5, 150.0)).expect("world builds");
        let materials = Materials::of(&world);
        let floats: &[f32] = bytemuck::cast_slice(&materials.bytes);
        let records: Vec<&[f32]> = floats.chunks(MATERIAL_BYTES / 4).collect();
        let first = world.variants.len() - sylva::forest::GroundKind::ALL.len();
        let (_, grass) = materials.variants[first];
        let (_, fern) = materials.variants[first + 1];
        assert_eq!(records[grass as usize][3], 0.0, "grass blades are plain");
        assert!(records[fern as usize][3] >= 1.0, "fern leaflets are cards");
    }
}
