//! The viewer's render pipelines: the shader (sized to the world's materials and textures),
//! the bind group layouts of its globals and materials, and the pipelines of the shaded and
//! id passes, the shadow map and the sky.

use std::num::NonZeroU64;

use crate::gpu::{DEPTH, scene_pipeline};
use crate::materials::Materials;

/// The pipelines a frame is drawn with, and the layouts their bind groups follow.
pub(crate) struct Pipelines {
    pub(crate) shaded: wgpu::RenderPipeline,
    pub(crate) ids: wgpu::RenderPipeline,
    /// Impostor cards, shaded and as material ids.
    pub(crate) impostor: wgpu::RenderPipeline,
    pub(crate) impostor_ids: wgpu::RenderPipeline,
    pub(crate) shadow: wgpu::RenderPipeline,
    pub(crate) sky: wgpu::RenderPipeline,
    pub(crate) globals_layout: wgpu::BindGroupLayout,
    pub(crate) material_layout: wgpu::BindGroupLayout,
}

impl Pipelines {
    /// The pipelines for drawing into `format`, with globals of `globals_size` bytes, the
    /// world's `materials`, and the layouts of the textures and the shadow map.
    pub(crate) fn new(
        device: &wgpu::Device,
        format: wgpu::TextureFormat,
        (globals_size, materials): (u64, &Materials),
        (texture_layout, shadow_map_layout): (&wgpu::BindGroupLayout, &wgpu::BindGroupLayout),
    ) -> Pipelines {
        let uniform_layout = |size: u64| {
            device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: None,
                entries: &[wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: NonZeroU64::new(size),
                    },
                    count: None,
                }],
            })
        };
        let globals_layout = uniform_layout(globals_size);
        let material_layout = uniform_layout(materials.bytes.len() as u64);
        // The material array is sized to the world's materials.
        let source = include_str!("shader.wgsl")
            .replace("MATERIAL_COUNT", &materials.count().to_string())
            .replace("FIRST_BARK", &crate::textures::FIRST_BARK.to_string())
            .replace("BARK_COUNT", &crate::textures::BARK_COUNT.to_string())
            .replace(
                "CLUSTER_SHADE_MEAN",
                &format!("{:?}", sylva::forest::CLUSTER_SHADE_MEAN),
            )
            .replace("FLUSH_DAYS", &format!("{:?}", sylva::forest::FLUSH_DAYS))
            .replace("FALL_DAYS", &format!("{:?}", sylva::forest::FALL_DAYS))
            .replace("TURN_DAYS", &format!("{:?}", sylva::forest::TURN_DAYS))
            .replace("GREEN_DAYS", &format!("{:?}", sylva::forest::GREEN_DAYS))
            .replace("TREE_DAYS", &format!("{:?}", sylva::forest::TREE_DAYS));
        let shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("shader.wgsl"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: None,
            bind_group_layouts: &[
                Some(&globals_layout),
                Some(&material_layout),
                Some(texture_layout),
                Some(shadow_map_layout),
            ],
            immediate_size: 0,
        });
        // The shadow pass writes the map, so its pipeline does not read it.
        let shadow_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("shadow"),
            bind_group_layouts: &[
                Some(&globals_layout),
                Some(&material_layout),
                Some(texture_layout),
            ],
            immediate_size: 0,
        });
        // Against shadow acne on surfaces lit at a grazing angle.
        let acne = wgpu::DepthBiasState {
            constant: 2,
            slope_scale: 2.0,
            clamp: 0.0,
        };
        let shadow_pipeline = scene_pipeline(
            device,
            &shader,
            &shadow_layout,
            ("vs_shadow", "fs_shadow"),
            None,
            acne,
        );
        // The sky: drawn first, behind everything, without touching depth.
        let sky = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("sky"),
            layout: Some(&layout),
            vertex: wgpu::VertexState {
                module: &shader,
                entry_point: Some("vs_sky"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: Default::default(),
            depth_stencil: Some(wgpu::DepthStencilState {
                format: DEPTH,
                depth_write_enabled: Some(false),
                depth_compare: Some(wgpu::CompareFunction::Always),
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &shader,
                entry_point: Some("fs_sky"),
                compilation_options: Default::default(),
                targets: &[Some(format.into())],
            }),
            multiview_mask: None,
            cache: None,
        });
        let pipeline = |vertex: &str, fragment: &str| {
            scene_pipeline(
                device,
                &shader,
                &layout,
                (vertex, fragment),
                Some(format),
                Default::default(),
            )
        };
        Pipelines {
            shaded: pipeline("vs_main", "fs_main"),
            ids: pipeline("vs_main", "fs_id"),
            impostor: pipeline("vs_impostor", "fs_impostor"),
            impostor_ids: pipeline("vs_impostor", "fs_impostor_id"),
            shadow: shadow_pipeline,
            sky,
            globals_layout,
            material_layout,
        }
    }
}
