//! The procedural textures on the GPU: leaf cards and bark as one texture array, and which
//! layer a material reads.

use sylva::export::{Texture, linear_to_srgb};
use sylva::forest::{BarkPattern, LeafShape};
use wgpu::util::DeviceExt;

/// The first bark layer of the viewer's texture array: leaf shapes come first.
pub(crate) const FIRST_BARK: usize = LeafShape::ALL.len();
/// Bark patterns, each with a colour layer and, this many layers on, its normal map.
pub(crate) const BARK_COUNT: usize = BarkPattern::ALL.len();

/// The layer of a bark pattern's texture in the viewer's texture array, after the leaf
/// shapes; the shader tiles layers from [`FIRST_BARK`] on.
pub(crate) fn bark_layer(pattern: BarkPattern) -> u32 {
    let k = BarkPattern::ALL
        .iter()
        .position(|&p| p == pattern)
        .unwrap_or(0);
    (FIRST_BARK + k) as u32
}

/// The layer of a leaf shape's texture in the viewer's texture array.
pub(crate) fn leaf_layer(shape: LeafShape) -> u32 {
    LeafShape::ALL.iter().position(|&s| s == shape).unwrap_or(0) as u32
}

/// A texture of plain values (a normal map) re-encoded so that the sRGB array, which decodes
/// every texel to linear, hands the shader the original values.
fn srgb_encoded(mut texture: Texture) -> Texture {
    for px in texture.rgba.chunks_exact_mut(4) {
        for c in &mut px[..3] {
            *c = linear_to_srgb(f32::from(*c) / 255.0);
        }
    }
    texture
}

/// `images` (all of one size) as one sRGB texture array.
fn texture_array(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    label: &str,
    images: &[Texture],
) -> wgpu::TextureView {
    let blank = Texture {
        width: 1,
        height: 1,
        rgba: vec![0; 4],
    };
    let first = images.first().unwrap_or(&blank);
    let mut data: Vec<u8> = images.iter().flat_map(|t| t.rgba.iter().copied()).collect();
    let mut layers = images.len() as u32;
    // wgpu's GL backend takes a square texture of a multiple of six layers for a cube map
    // (it cannot know the view's dimension when it creates the texture) and then samples it
    // as black; a clear spare layer keeps the array an array (and an empty one has a layer).
    if layers.is_multiple_of(6) {
        data.resize(data.len() + first.rgba.len(), 0);
        layers += 1;
    }
    let texture = device.create_texture_with_data(
        queue,
        &wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d {
                width: first.width,
                height: first.height,
                depth_or_array_layers: layers,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba8UnormSrgb,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        &data,
    );
    texture.create_view(&wgpu::TextureViewDescriptor {
        dimension: Some(wgpu::TextureViewDimension::D2Array),
        ..Default::default()
    })
}

/// The procedural textures as one texture array (every leaf shape, every bark pattern, then
/// the barks' normal maps, each [`BARK_COUNT`] layers after its colour), a linear sampler,
/// and the impostor atlases (`atlases`: each variant's colour, then its normals) as a second
/// array, with the bind group layout the shader reads them through.
pub(crate) fn textures(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    atlases: &[Texture],
) -> (wgpu::BindGroupLayout, wgpu::BindGroup) {
    let images: Vec<Texture> = LeafShape::ALL
        .into_iter()
        .map(Texture::leaf)
        .chain(BarkPattern::ALL.into_iter().map(Texture::bark))
        .chain(
            BarkPattern::ALL
                .into_iter()
                .map(|p| srgb_encoded(Texture::bark_normal(p))),
        )
        .collect();
    let view = texture_array(device, queue, "textures", &images);
    // Normal atlases hold plain values, like the barks' normal maps.
    let atlases: Vec<Texture> = atlases
        .iter()
        .enumerate()
        .map(|(k, t)| {
            if k % 2 == 1 {
                srgb_encoded(t.clone())
            } else {
                t.clone()
            }
        })
        .collect();
    let atlas_view = texture_array(device, queue, "impostor atlases", &atlases);
    let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some("texture sampler"),
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        ..Default::default()
    });
    let array = |binding: u32| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable: true },
            view_dimension: wgpu::TextureViewDimension::D2Array,
            multisampled: false,
        },
        count: None,
    };
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("textures"),
        entries: &[
            array(0),
            wgpu::BindGroupLayoutEntry {
                binding: 1,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                count: None,
            },
            array(2),
        ],
    });
    let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("textures"),
        layout: &layout,
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::TextureView(&view),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: wgpu::BindingResource::Sampler(&sampler),
            },
            wgpu::BindGroupEntry {
                binding: 2,
                resource: wgpu::BindingResource::TextureView(&atlas_view),
            },
        ],
    });
    (layout, group)
}

/// A bind group of a texture view (binding 0) and its sampler (binding 1), read by the
/// fragment shader, with its layout.
pub(crate) fn sampled_texture(
    device: &wgpu::Device,
    label: &str,
    view: &wgpu::TextureView,
    sampler: &wgpu::Sampler,
    (sample_type, view_dimension, sampler_type): (
        wgpu::TextureSampleType,
        wgpu::TextureViewDimension,
        wgpu::SamplerBindingType,
    ),
) -> (wgpu::BindGroupLayout, wgpu::BindGroup) {
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(label),
        entries: &[
            wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Texture {
                    sample_type,
                    view_dimension,
                    multisampled: false,
                },
                count: None,
            },
            wgpu::BindGroupLayoutEntry {
                binding: 1,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Sampler(sampler_type),
                count: None,
            },
        ],
    });
    let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(label),
        layout: &layout,
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::TextureView(view),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: wgpu::BindingResource::Sampler(sampler),
            },
        ],
    });
    (layout, group)
}
