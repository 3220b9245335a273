//! The preview tree in 3D, beside the species tab: the selected species' tree drawn into a
//! texture of its own (lit bark and leaves in the species' colours over a dark ground) that
//! the panel shows as an image; dragging it turns the tree. Drawn again only when the tree
//! or the view changes.

use std::sync::Arc;

use bytemuck::{Pod, Zeroable};
use sylva::terrain::glam::{self, Vec3};
use sylva::turtle::Mesh;
use wgpu::util::DeviceExt;

/// The preview's size in pixels.
pub(crate) const SIZE: (u32, u32) = (360, 300);
const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
const DEPTH: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// Where the light comes from (towards the sun), and how much light every face gets.
const SUN: Vec3 = Vec3::new(0.4, 0.8, 0.45);
const AMBIENT: f32 = 0.45;

const SHADER: &str = r"
struct Globals { view_proj: mat4x4<f32>, sun: vec4<f32> };
@group(0) @binding(0) var<uniform> globals: Globals;
struct In {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) colour: vec3<f32>,
};
struct Out {
    @builtin(position) clip: vec4<f32>,
    @location(0) normal: vec3<f32>,
    @location(1) colour: vec3<f32>,
};
@vertex fn vs(v: In) -> Out {
    var o: Out;
    o.clip = globals.view_proj * vec4<f32>(v.position, 1.0);
    o.normal = v.normal;
    o.colour = v.colour;
    return o;
}
@fragment fn fs(o: Out, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
    // Leaves are cards seen from both sides: the side facing the eye is lit.
    var n = normalize(o.normal);
    if (!front) { n = -n; }
    let light = globals.sun.w + (1.0 - globals.sun.w) * max(dot(n, globals.sun.xyz), 0.0);
    return vec4<f32>(o.colour * light, 1.0);
}
";

/// One preview vertex: position, normal and colour.
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
struct PreviewVertex {
    position: [f32; 3],
    normal: [f32; 3],
    colour: [f32; 3],
}

#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
struct Globals {
    view_proj: [[f32; 4]; 4],
    sun: [f32; 4],
}

/// The tree uploaded: its buffers, and the sphere the camera frames.
struct Uploaded {
    mesh: Arc<Mesh>,
    vertices: wgpu::Buffer,
    indices: wgpu::Buffer,
    count: u32,
    centre: Vec3,
    radius: f32,
}

/// The preview's GPU side: its pipeline, its texture and the tree drawn into it.
pub(crate) struct Preview3d {
    pipeline: wgpu::RenderPipeline,
    globals: wgpu::Buffer,
    group: wgpu::BindGroup,
    pub(crate) view: wgpu::TextureView,
    depth: wgpu::TextureView,
    tree: Option<Uploaded>,
    /// The yaw last drawn at (`None`: nothing drawn yet).
    drawn_yaw: Option<f32>,
}

impl Preview3d {
    pub(crate) fn new(device: &wgpu::Device) -> Preview3d {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("preview"),
            source: wgpu::ShaderSource::Wgsl(SHADER.into()),
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("preview globals"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            }],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("preview"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("preview"),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs"),
                compilation_options: Default::default(),
                buffers: &[Some(wgpu::VertexBufferLayout {
                    array_stride: size_of::<PreviewVertex>() as u64,
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x3],
                })],
            },
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: Some(wgpu::DepthStencilState {
                format: DEPTH,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Less),
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs"),
                compilation_options: Default::default(),
                targets: &[Some(FORMAT.into())],
            }),
            multiview_mask: None,
            cache: None,
        });
        let globals = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("preview globals"),
            size: size_of::<Globals>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("preview globals"),
            layout: &layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: globals.as_entire_binding(),
            }],
        });
        let texture = |label, format, usage| {
            device
                .create_texture(&wgpu::TextureDescriptor {
                    label: Some(label),
                    size: wgpu::Extent3d {
                        width: SIZE.0,
                        height: SIZE.1,
                        depth_or_array_layers: 1,
                    },
                    mip_level_count: 1,
                    sample_count: 1,
                    dimension: wgpu::TextureDimension::D2,
                    format,
                    usage,
                    view_formats: &[],
                })
                .create_view(&Default::default())
        };
        Preview3d {
            pipeline,
            globals,
            group,
            view: texture(
                "preview",
                FORMAT,
                wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
            ),
            depth: texture(
                "preview depth",
                DEPTH,
                wgpu::TextureUsages::RENDER_ATTACHMENT,
            ),
            tree: None,
            drawn_yaw: None,
        }
    }

    /// Draws `tree` (its mesh, bark and leaf colours) seen from `yaw` radians round it into
    /// the preview's texture, unless that is what it holds already; `None` clears it.
    pub(crate) fn update(
        &mut self,
        (device, queue): (&wgpu::Device, &wgpu::Queue),
        encoder: &mut wgpu::CommandEncoder,
        tree: Option<(&Arc<Mesh>, [[f32; 3]; 2])>,
        yaw: f32,
    ) {
        let same_tree = match (&self.tree, tree) {
            (Some(u), Some((mesh, _))) => Arc::ptr_eq(&u.mesh, mesh),
            (None, None) => true,
            _ => false,
        };
        if same_tree && self.drawn_yaw == Some(yaw) {
            return;
        }
        if !same_tree {
            self.tree = tree.map(|(mesh, colours)| upload(device, mesh, colours));
        }
        self.drawn_yaw = Some(yaw);
        if let Some(u) = &self.tree {
            queue.write_buffer(&self.globals, 0, bytemuck::bytes_of(&globals(u, yaw)));
        }
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("preview"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &self.view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color {
                        r: 0.02,
                        g: 0.025,
                        b: 0.03,
                        a: 1.0,
                    }),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &self.depth,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(1.0),
                    store: wgpu::StoreOp::Discard,
                }),
                stencil_ops: None,
            }),
            ..Default::default()
        });
        if let Some(u) = &self.tree {
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &self.group, &[]);
            pass.set_vertex_buffer(0, u.vertices.slice(..));
            pass.set_index_buffer(u.indices.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..u.count, 0, 0..1);
        }
    }
}

/// The camera framing the tree's sphere from `yaw`, a little above its middle.
fn globals(u: &Uploaded, yaw: f32) -> Globals {
    let pitch = 0.25f32;
    let aspect = SIZE.0 as f32 / SIZE.1 as f32;
    let fov = 35f32.to_radians();
    // Far enough that the sphere fits the narrower of the two fields of view (a tree's
    // sphere is wider than its outline, so a little closer than that).
    let half = (fov * 0.5).min((fov * 0.5).tan().atan2(1.0 / aspect.min(1.0)));
    let distance = 0.85 * u.radius / half.sin().max(1e-3);
    let eye = u.centre
        + distance
            * Vec3::new(
                yaw.sin() * pitch.cos(),
                pitch.sin(),
                yaw.cos() * pitch.cos(),
            );
    let view = glam::camera::rh::view::look_at_mat4(eye, u.centre, Vec3::Y);
    let near = (distance - u.radius * 1.1).max(distance * 0.01);
    // wgpu's clip space is Direct3D's: depth from 0 to 1.
    let proj =
        glam::camera::rh::proj::directx::perspective(fov, aspect, near, distance + u.radius * 1.1);
    let sun = SUN.normalize();
    Globals {
        view_proj: (proj * view).to_cols_array_2d(),
        sun: [sun.x, sun.y, sun.z, AMBIENT],
    }
}

/// The tree's vertices coloured by material (bark where a bark triangle uses them), and
/// its bark then leaf triangles.
fn upload(device: &wgpu::Device, mesh: &Arc<Mesh>, [bark, leaf]: [[f32; 3]; 2]) -> Uploaded {
    let mut colour = vec![leaf; mesh.vertices.len()];
    for &i in &mesh.bark {
        if let Some(c) = colour.get_mut(i as usize) {
            *c = bark;
        }
    }
    let vertices: Vec<PreviewVertex> = mesh
        .vertices
        .iter()
        .zip(colour)
        .map(|(v, colour)| PreviewVertex {
            position: v.position,
            normal: v.normal,
            colour,
        })
        .collect();
    let indices: Vec<u32> = mesh.bark.iter().chain(&mesh.leaves).copied().collect();
    let (centre, radius) =
        crate::geometry::bounding_sphere(mesh.vertices.iter().map(|v| Vec3::from(v.position)));
    let buffer = |label, contents: &[u8], usage| {
        device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            // wgpu refuses empty buffers: an empty tree gets one zero vertex.
            contents: if contents.is_empty() {
                &[0; 36]
            } else {
                contents
            },
            usage,
        })
    };
    Uploaded {
        mesh: Arc::clone(mesh),
        vertices: buffer(
            "preview vertices",
            bytemuck::cast_slice(&vertices),
            wgpu::BufferUsages::VERTEX,
        ),
        indices: buffer(
            "preview indices",
            bytemuck::cast_slice(&indices),
            wgpu::BufferUsages::INDEX,
        ),
        count: indices.len() as u32,
        centre,
        radius: radius.max(1e-3),
    }
}

/// Draws the selected species' tree into `preview` when the species tab shows it.
pub(crate) fn show_current(
    preview: &mut Preview3d,
    gpu: (&wgpu::Device, &wgpu::Queue),
    encoder: &mut wgpu::CommandEncoder,
    editor: &super::Editor,
) {
    if editor.tab != super::Tab::Species {
        return;
    }
    let tree = editor
        .current()
        .outcome
        .as_ref()
        .ok()
        .map(|p| (&p.mesh, [p.species.bark, p.species.leaf]));
    preview.update(gpu, encoder, tree, editor.preview_yaw);
}
