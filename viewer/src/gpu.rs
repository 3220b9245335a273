//! wgpu plumbing the renderer builds on: the device, colour and depth targets, buffers and
//! the pipeline that draws the terrain and the instanced trees.

use sylva::turtle::Vertex;
use wgpu::util::DeviceExt;

use crate::error::ViewerError;
use crate::geometry::InstanceRaw;

/// The format of every depth target, the shadow map's included.
pub(crate) const DEPTH: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// The scene's vertex streams: the mesh (slot 0), the placement per instance (slot 1) and
/// each vertex's material number (slot 2).
fn vertex_layouts() -> [Option<wgpu::VertexBufferLayout<'static>>; 3] {
    const MESH: [wgpu::VertexAttribute; 4] = wgpu::vertex_attr_array![
        0 => Float32x3, 1 => Float32x3, 2 => Float32x2, 3 => Float32x4
    ];
    const INSTANCE: [wgpu::VertexAttribute; 4] = wgpu::vertex_attr_array![
        4 => Float32x4, 5 => Float32x4, 6 => Float32x4, 7 => Float32x4
    ];
    const MATERIAL: [wgpu::VertexAttribute; 1] = wgpu::vertex_attr_array![8 => Uint32];
    [
        Some(wgpu::VertexBufferLayout {
            array_stride: size_of::<Vertex>() as u64,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &MESH,
        }),
        Some(wgpu::VertexBufferLayout {
            array_stride: size_of::<InstanceRaw>() as u64,
            step_mode: wgpu::VertexStepMode::Instance,
            attributes: &INSTANCE,
        }),
        Some(wgpu::VertexBufferLayout {
            array_stride: size_of::<u32>() as u64,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &MATERIAL,
        }),
    ]
}

/// A buffer holding `bytes`, for `usage`.
pub(crate) fn buffer(
    device: &wgpu::Device,
    label: &str,
    bytes: &[u8],
    usage: wgpu::BufferUsages,
) -> wgpu::Buffer {
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents: bytes,
        usage,
    })
}

/// A pipeline drawing the terrain and the instanced trees: both faces (leaves are one-sided
/// quads), depth tested and written, into `target` (none for the depth-only shadow map).
pub(crate) fn scene_pipeline(
    device: &wgpu::Device,
    shader: &wgpu::ShaderModule,
    layout: &wgpu::PipelineLayout,
    (vertex, fragment): (&str, &str),
    target: Option<wgpu::TextureFormat>,
    bias: wgpu::DepthBiasState,
) -> wgpu::RenderPipeline {
    let targets = [target.map(Into::into)];
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(fragment),
        layout: Some(layout),
        vertex: wgpu::VertexState {
            module: shader,
            entry_point: Some(vertex),
            compilation_options: Default::default(),
            buffers: &vertex_layouts(),
        },
        primitive: wgpu::PrimitiveState {
            cull_mode: None,
            ..Default::default()
        },
        depth_stencil: Some(wgpu::DepthStencilState {
            format: DEPTH,
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::Less),
            stencil: Default::default(),
            bias,
        }),
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: shader,
            entry_point: Some(fragment),
            compilation_options: Default::default(),
            targets: if target.is_some() { &targets } else { &[] },
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// An index buffer, or none for no indices (wgpu refuses empty buffers for drawing).
pub(crate) fn index_buffer(
    device: &wgpu::Device,
    label: &str,
    indices: &[u32],
) -> Option<wgpu::Buffer> {
    (!indices.is_empty()).then(|| {
        buffer(
            device,
            label,
            bytemuck::cast_slice(indices),
            wgpu::BufferUsages::INDEX,
        )
    })
}

/// A colour and depth target of the given size.
pub(crate) fn targets(
    device: &wgpu::Device,
    format: wgpu::TextureFormat,
    width: u32,
    height: u32,
    readable: bool,
) -> (wgpu::Texture, wgpu::TextureView, wgpu::TextureView) {
    let size = wgpu::Extent3d {
        width,
        height,
        depth_or_array_layers: 1,
    };
    let colour = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("colour"),
        size,
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT
            | if readable {
                wgpu::TextureUsages::COPY_SRC
            } else {
                wgpu::TextureUsages::empty()
            },
        view_formats: &[],
    });
    let depth = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("depth"),
        size,
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: DEPTH,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
        view_formats: &[],
    });
    let cv = colour.create_view(&Default::default());
    let dv = depth.create_view(&Default::default());
    (colour, cv, dv)
}

/// The limits the viewer asks of `adapter`'s device: the textures' sizes, and storage
/// buffers as large as it allows (the GPU's copy of the drawn cells' placements is one);
/// with no compute at all on an adapter without compute shaders (frames then copy their
/// placements on the CPU).
fn limits(adapter: &wgpu::Adapter) -> wgpu::Limits {
    let most = adapter.limits();
    let computes = (adapter.get_downlevel_capabilities().flags)
        .contains(wgpu::DownlevelFlags::COMPUTE_SHADERS);
    let least = if computes {
        wgpu::Limits::downlevel_defaults()
    } else {
        wgpu::Limits::downlevel_webgl2_defaults()
    };
    wgpu::Limits {
        max_storage_buffer_binding_size: most.max_storage_buffer_binding_size,
        max_buffer_size: most.max_buffer_size,
        ..least.using_resolution(most)
    }
}

/// Requests an adapter and device; `None` surface for headless use.
pub(crate) async fn device(
    instance: &wgpu::Instance,
    surface: Option<&wgpu::Surface<'_>>,
) -> Result<(wgpu::Adapter, wgpu::Device, wgpu::Queue), ViewerError> {
    let adapter = instance
        .request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: surface,
            ..Default::default()
        })
        .await
        .map_err(ViewerError::NoAdapter)?;
    let (device, queue) = adapter
        .request_device(&wgpu::DeviceDescriptor {
            label: Some("sylva viewer"),
            required_limits: limits(&adapter),
            ..Default::default()
        })
        .await
        .map_err(ViewerError::Device)?;
    Ok((adapter, device, queue))
}
