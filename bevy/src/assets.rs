//! What the forest is drawn with: per variant its levels of detail (built off the main thread
//! by `sylva_export::lod::VariantLods`), its bark, leaf and impostor materials over sylva's
//! textures, the visibility range of each level, and meshes of cached instances, made the
//! first time a placement needs them and shared by every placement after (so Bevy batches
//! them into instanced draws).

use std::collections::HashMap;

use bevy::asset::RenderAssetUsages;
use bevy::camera::visibility::VisibilityRange;
use bevy::image::{ImageAddressMode, ImageSampler, ImageSamplerDescriptor};
use bevy::mesh::{Indices, PrimitiveTopology};
use bevy::prelude::*;
use bevy::render::render_resource::{Extent3d, TextureDimension, TextureFormat};
use sylva::export::Texture;
use sylva::export::limits::CUTOFF_MIP_LEVEL;
use sylva::export::lod::{CARD_ALPHA_CUTOFF, LodChain, VariantLods, impostor_cards};
use sylva::forest::Species;
use sylva::turtle::Vertex;

use crate::wind::{ATTRIBUTE_WIND, Wind, WindMaterial};

/// Levels drawn from meshes (the full cache and two coarser levels); the impostor is the next.
pub(crate) const MESH_LEVELS: usize = 3;

/// One variant's materials, impostor and the distances its levels are drawn at.
pub(crate) struct VariantAssets {
    pub(crate) lods: VariantLods,
    pub(crate) bark: Handle<WindMaterial>,
    pub(crate) leaves: Handle<WindMaterial>,
    /// The impostor's cards and their material (canopy variants).
    pub(crate) impostor: Option<(Handle<Mesh>, Handle<StandardMaterial>)>,
    /// Visibility ranges of the mesh levels, then of the impostor.
    pub(crate) ranges: [VisibilityRange; MESH_LEVELS + 1],
}

/// A species' textures: its leaf card (alpha cut at `cutoff`, where its coverage survives
/// mipmaps) and its bark. (Bark normal maps need tangents, which the plugin's meshes do not
/// carry yet.)
#[derive(Clone)]
struct SpeciesTextures {
    leaf: Handle<Image>,
    bark: Handle<Image>,
    cutoff: f32,
}

/// Every variant's assets, and the instance meshes made so far.
#[derive(Resource)]
pub(crate) struct ForestAssets {
    pub(crate) variants: Vec<VariantAssets>,
    /// By (variant, instance, level, bark): the mesh of that span (none when empty).
    meshes: HashMap<(u16, u32, u8, bool), Option<Handle<Mesh>>>,
}

/// A sylva texture as a Bevy image with its mipmaps (box-filtered): `repeat` for bark, which
/// tiles; `linear` for data (normal maps) rather than colour.
pub(crate) fn image(texture: &Texture, repeat: bool, linear: bool) -> Image {
    let (mut w, mut h) = (texture.width.max(1), texture.height.max(1));
    let mut level = texture.rgba.clone();
    let mut data = level.clone();
    let mut levels = 1;
    while w > 1 && h > 1 && levels < 12 {
        let (nw, nh) = (w / 2, h / 2);
        let mut next = vec![0u8; (nw * nh * 4) as usize];
        for y in 0..nh {
            for x in 0..nw {
                for c in 0..4 {
                    let at = |dx: u32, dy: u32| {
                        u32::from(level[(((2 * y + dy) * w + 2 * x + dx) * 4 + c) as usize])
                    };
                    let sum = at(0, 0) + at(1, 0) + at(0, 1) + at(1, 1);
                    next[((y * nw + x) * 4 + c) as usize] = ((sum + 2) / 4) as u8;
                }
            }
        }
        data.extend_from_slice(&next);
        (level, w, h) = (next, nw, nh);
        levels += 1;
    }
    let format = if linear {
        TextureFormat::Rgba8Unorm
    } else {
        TextureFormat::Rgba8UnormSrgb
    };
    // Made with the first level (as `Image::new` checks), then given the whole chain.
    let first = (texture.width.max(1) * texture.height.max(1) * 4) as usize;
    let mut image = Image::new(
        Extent3d {
            width: texture.width.max(1),
            height: texture.height.max(1),
            depth_or_array_layers: 1,
        },
        TextureDimension::D2,
        data[..first.min(data.len())].to_vec(),
        format,
        RenderAssetUsages::RENDER_WORLD,
    );
    image.data = Some(data);
    image.texture_descriptor.mip_level_count = levels;
    let mode = if repeat {
        ImageAddressMode::Repeat
    } else {
        ImageAddressMode::ClampToEdge
    };
    image.sampler = ImageSampler::Descriptor(ImageSamplerDescriptor {
        address_mode_u: mode,
        address_mode_v: mode,
        ..ImageSamplerDescriptor::linear()
    });
    image
}

/// The visibility ranges of a variant's levels from its errors: each level from where the one
/// before hands over to where the next takes over, cross-fading over `chain.fade` of each
/// switch distance; the last level drawn ends at `far`.
fn ranges(lods: &VariantLods, chain: &LodChain, far: f32) -> [VisibilityRange; MESH_LEVELS + 1] {
    let fade = 1.0 + chain.fade.max(0.0);
    let mut switch = [0.0f32; MESH_LEVELS];
    let mut last = 0.0f32;
    for (k, s) in switch.iter_mut().enumerate() {
        let d = lods
            .errors
            .get(k)
            .map_or(f32::INFINITY, |&e| chain.distance_for(e))
            .min(far);
        // Each switch past the last one's fade, so the bands never cross.
        *s = d.max(last * fade);
        last = *s;
    }
    let band = |d: f32| if d >= far { far..far } else { d..d * fade };
    let mut out: [VisibilityRange; MESH_LEVELS + 1] = Default::default();
    let mut start = 0.0..0.0;
    for (k, range) in out.iter_mut().enumerate() {
        let end = switch.get(k).map_or(far..far, |&d| band(d));
        *range = VisibilityRange {
            start_margin: start.clone(),
            end_margin: end.clone(),
            use_aabb: false,
        };
        start = end;
    }
    out
}

impl ForestAssets {
    /// Materials, images and impostors of every variant (`lods` in variant order).
    pub(crate) fn new(
        lods: Vec<(VariantLods, bool)>,
        species: &[Species],
        variant_species: &[usize],
        (chain, far): (&LodChain, f32),
        (images, materials, plain, meshes): (
            &mut Assets<Image>,
            &mut Assets<WindMaterial>,
            &mut Assets<StandardMaterial>,
            &mut Assets<Mesh>,
        ),
    ) -> ForestAssets {
        let mut variants = Vec::with_capacity(lods.len());
        // Textures shared by the variants of a species.
        let mut textures: HashMap<usize, SpeciesTextures> = HashMap::new();
        for ((lods, _), &s) in lods.into_iter().zip(variant_species) {
            let sp = &species[s];
            let SpeciesTextures { leaf, bark, cutoff } = textures
                .entry(s)
                .or_insert_with(|| {
                    let leaf = Texture::leaf(sp.leaf_shape);
                    SpeciesTextures {
                        cutoff: leaf.alpha_cutoff(CUTOFF_MIP_LEVEL),
                        leaf: images.add(image(&leaf, false, false)),
                        bark: images.add(image(&Texture::bark(sp.bark_pattern), true, false)),
                    }
                })
                .clone();
            let colour = |c: [f32; 3]| Color::linear_rgb(c[0], c[1], c[2]);
            let wind = Wind {
                wind: Vec4::new(0.8, 0.0, 0.6, 0.0),
            };
            let bark = materials.add(WindMaterial {
                base: StandardMaterial {
                    base_color: colour(sp.bark),
                    base_color_texture: Some(bark),
                    perceptual_roughness: 0.9,
                    ..default()
                },
                extension: wind.clone(),
            });
            let leaves = materials.add(WindMaterial {
                base: StandardMaterial {
                    base_color: colour(sp.leaf),
                    base_color_texture: Some(leaf),
                    alpha_mode: AlphaMode::Mask(cutoff),
                    double_sided: true,
                    cull_mode: None,
                    perceptual_roughness: 0.8,
                    // Leaves are matt: Bevy's default reflectance glazes backlit cards.
                    reflectance: 0.15,
                    ..default()
                },
                extension: wind,
            });
            let impostor = lods.impostor.as_ref().map(|i| {
                let cards = images.add(image(&i.cards_texture(), false, false));
                let material = plain.add(StandardMaterial {
                    // A crown shades itself; a flat card lit as facing the sky does not.
                    base_color: Color::linear_rgb(0.45, 0.45, 0.45),
                    base_color_texture: Some(cards),
                    alpha_mode: AlphaMode::Mask(CARD_ALPHA_CUTOFF),
                    perceptual_roughness: 0.9,
                    reflectance: 0.15,
                    ..default()
                });
                let cards = impostor_cards(i);
                (
                    meshes.add(bevy_mesh(&cards.vertices, &cards.leaves)),
                    material,
                )
            });
            variants.push(VariantAssets {
                ranges: ranges(&lods, chain, far),
                lods,
                bark,
                leaves,
                impostor,
            });
        }
        ForestAssets {
            variants,
            meshes: HashMap::new(),
        }
    }

    /// The mesh of `instance` of `variant` at `level`, its bark or its leaves: made the first
    /// time it is asked for; none when that part is empty.
    pub(crate) fn instance_mesh(
        &mut self,
        (variant, instance, level, bark): (u16, u32, u8, bool),
        meshes: &mut Assets<Mesh>,
    ) -> Option<Handle<Mesh>> {
        let key = (variant, instance, level, bark);
        if let Some(found) = self.meshes.get(&key) {
            return found.clone();
        }
        let made = self.variants.get(usize::from(variant)).and_then(|v| {
            let cache = &v.lods.cache;
            let l = cache.levels.get(usize::from(level))?;
            let (b, f) = *l.spans.get(instance as usize)?;
            let (indices, span) = if bark { (&l.bark, b) } else { (&l.leaves, f) };
            let triangles = indices.get(span.range())?;
            (!triangles.is_empty()).then(|| meshes.add(bevy_mesh(&cache.vertices, triangles)))
        });
        self.meshes.insert(key, made.clone());
        made
    }
}

/// A Bevy mesh of the triangles `indices` over `vertices`, keeping only the vertices they
/// use, with sylva's wind data.
pub(crate) fn bevy_mesh(vertices: &[Vertex], indices: &[u32]) -> Mesh {
    let mut remap: HashMap<u32, u32> = HashMap::new();
    let mut used: Vec<Vertex> = Vec::new();
    let compact: Vec<u32> = indices
        .iter()
        .map(|&i| {
            *remap.entry(i).or_insert_with(|| {
                used.push(vertices.get(i as usize).copied().unwrap_or_default());
                (used.len() - 1) as u32
            })
        })
        .collect();
    Mesh::new(
        PrimitiveTopology::TriangleList,
        RenderAssetUsages::RENDER_WORLD,
    )
    .with_inserted_attribute(
        Mesh::ATTRIBUTE_POSITION,
        used.iter().map(|v| v.position).collect::<Vec<_>>(),
    )
    .with_inserted_attribute(
        Mesh::ATTRIBUTE_NORMAL,
        used.iter().map(|v| v.normal).collect::<Vec<_>>(),
    )
    .with_inserted_attribute(
        Mesh::ATTRIBUTE_UV_0,
        used.iter().map(|v| v.uv).collect::<Vec<_>>(),
    )
    .with_inserted_attribute(
        ATTRIBUTE_WIND,
        used.iter().map(|v| v.wind).collect::<Vec<_>>(),
    )
    .with_inserted_indices(Indices::U32(compact))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An image's mipmaps halve down to a pixel, each the average of the four texels above.
    #[test]
    fn images_carry_their_mipmaps() {
        let texture = Texture {
            width: 4,
            height: 4,
            rgba: (0..64)
                .map(|i| if i % 4 == 3 { 255 } else { (i * 4) as u8 })
                .collect(),
        };
        let image = image(&texture, true, false);
        assert_eq!(image.texture_descriptor.mip_level_count, 3);
        let data = image.data.expect("pixels");
        assert_eq!(data.len(), (16 + 4 + 1) * 4);
        // The last level averages the whole picture.
        let mean = |c: usize| {
            texture
                .rgba
                .chunks_exact(4)
                .map(|p| u32::from(p[c]))
                .sum::<u32>() as f32
                / 16.0
        };
        let last = &data[data.len() - 4..];
        assert!((f32::from(last[0]) - mean(0)).abs() <= 2.0, "{last:?}");
        assert_eq!(last[3], 255);
    }

    /// Each level's visibility range starts where the one before ends, so Bevy's dither hands
    /// each tree from one level to the next with no gap and no double cover.
    #[test]
    fn levels_hand_over_without_gaps() {
        let mut config = sylva::forest::ForestConfig::new(vec![
            Species::from_preset("sylva-hazel", 3).expect("species"),
        ]);
        config.budget = 1 << 20;
        let builder = sylva::forest::ForestBuilder::new(config).expect("builder");
        let chain = LodChain::default();
        let lods = VariantLods::build(&builder.variants()[0], &builder.config().species[0], &chain)
            .expect("levels");
        let r = ranges(&lods, &chain, 1000.0);
        assert_eq!(r[0].start_margin, 0.0..0.0);
        for w in r.windows(2) {
            assert_eq!(w[0].end_margin, w[1].start_margin);
            assert!(w[0].start_margin.end <= w[0].end_margin.start);
        }
        assert!(r[MESH_LEVELS].end_margin.end <= 1000.0);
    }
}
