//! A frame on the GPU: the uniforms, the sun's shadow pass and the forest pass, with one
//! `draw_indexed` per instance range and bark or leaves over the meshes uploaded once
//! ([`crate::meshes`]) and the one instance buffer; the materials are one array bound once
//! per pass, indexed by a material number on each vertex.

use bytemuck::{Pod, Zeroable};
use sylva::terrain::glam::{Mat4, Vec3};

use crate::cells::{Streamed, VIEW_DISTANCE};
use crate::cull::{LodView, Sight, Volume};
use crate::draw::{Draw, DrawIndex};
use crate::error::ViewerError;
use crate::gather::{Gathered, Range};
use crate::geometry::lod_chain;
use crate::gpu::{DEPTH, buffer};
use crate::instances::Instances;
use crate::materials::Materials;
use crate::meshes::Meshes;
use crate::pipelines::Pipelines;
use crate::scene::Scene;
use crate::shadow::{SHADOW_TEXEL, ShadowMap, light_view_proj};
use crate::textures::textures;

/// Sky colours at the horizon and overhead (linear RGB); fog fades towards the horizon's.
pub(crate) const HORIZON: [f32; 3] = [0.62, 0.74, 0.86];
const ZENITH: [f32; 3] = [0.22, 0.42, 0.75];
/// Towards the sun: high in the south-west, so trunks cast long-ish shadows.
const SUN: Vec3 = Vec3::new(0.45, 0.75, 0.35);

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct Globals {
    view_proj: [[f32; 4]; 4],
    inverse_view_proj: [[f32; 4]; 4],
    light_view_proj: [[f32; 4]; 4],
    camera: [f32; 4],
    light: [f32; 4],
    horizon: [f32; 4],
    zenith: [f32; 4],
    fog: [f32; 4],
    wind: [f32; 4],
    // x: the day of the year; y: 1 when the seasons are played (0 draws the species as
    // given); z: snow lying, 0 to 1 (`sylva_forest::snow`).
    season: [f32; 4],
}

/// What one frame drew.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct FrameStats {
    pub(crate) draws: u32,
    pub(crate) instances: u64,
    pub(crate) triangles: u64,
    /// What streaming the cells for it did.
    pub(crate) streamed: Streamed,
    /// Milliseconds of the CPU's part of drawing it (streaming aside): culling the cells'
    /// placements for the camera and the sun, choosing levels of detail, gathering and
    /// uploading them, and recording the draws.
    pub(crate) cpu_ms: f64,
    /// Whether its placements were picked on the GPU from the cells' placements held there
    /// (otherwise they were copied on the CPU and uploaded).
    pub(crate) picked: bool,
}

/// Where the frame is seen from, how it is shaded and how the wind blows.
#[derive(Debug, Clone, Copy)]
pub(crate) struct View {
    pub(crate) view_proj: Mat4,
    pub(crate) eye: Vec3,
    /// The camera's viewing direction: the shadow map covers what lies ahead.
    pub(crate) forward: Vec3,
    pub(crate) mode: Mode,
    /// The picture's height in pixels over the vertical field of view in radians: how large
    /// things look, for dropping what is too small to see.
    pub(crate) pixels_per_radian: f32,
    /// Every tree at full detail, with no coarser level or impostor (to measure against).
    pub(crate) full_detail: bool,
    /// Wind strength (1: a breeze; 0: still air) and the time in seconds.
    pub(crate) wind: f32,
    pub(crate) time: f32,
    /// The day of the year the seasons are drawn on (`None`: the species as given, summer).
    pub(crate) season: Option<f32>,
}

/// Shading or flat material ids.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Mode {
    Shaded,
    Ids,
}

pub(crate) struct Renderer {
    texture_group: wgpu::BindGroup,
    shaded: wgpu::RenderPipeline,
    ids: wgpu::RenderPipeline,
    impostor: wgpu::RenderPipeline,
    impostor_ids: wgpu::RenderPipeline,
    shadow_pipeline: wgpu::RenderPipeline,
    sky: wgpu::RenderPipeline,
    shadow: ShadowMap,
    globals: wgpu::Buffer,
    globals_group: wgpu::BindGroup,
    /// Every material (the terrain's first), bound once per pass; each vertex names its own.
    material_group: wgpu::BindGroup,
    /// The variants', proxies' and terrain's meshes.
    meshes: Meshes,
    /// The buffer the draws read their placements from.
    pub(crate) instances: Instances,
    draws: Vec<Draw>,
    /// Which draws each slot feeds.
    draw_index: DrawIndex,
    /// The last frame's culling, whose buffers the next frame reuses.
    gathered: Gathered,
    fog_density: f32,
    /// Lowest and highest terrain vertex, for the ground colour by altitude.
    terrain_heights: (f32, f32),
}

impl Renderer {
    /// The GPU side of `scene`: its meshes, materials, textures and pipelines; an error when
    /// the adapter cannot bind the world's materials in one uniform array.
    pub(crate) fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        format: wgpu::TextureFormat,
        scene: &Scene,
    ) -> Result<Renderer, ViewerError> {
        let world = &scene.world;
        let (texture_layout, texture_group) = textures(device, queue, &world.atlases);
        let materials = Materials::of(world);
        let most = device.limits().max_uniform_buffer_binding_size;
        if materials.bytes.len() as u64 > most {
            return Err(ViewerError::TooManyMaterials {
                materials: materials.count(),
                bytes: materials.bytes.len() as u64,
                most,
            });
        }
        let shadow = ShadowMap::new(device, DEPTH);
        let pipelines = Pipelines::new(
            device,
            format,
            (size_of::<Globals>() as u64, &materials),
            (&texture_layout, &shadow.layout),
        );
        let globals = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("globals"),
            size: size_of::<Globals>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let material_buffer = buffer(
            device,
            "materials",
            &materials.bytes,
            wgpu::BufferUsages::UNIFORM,
        );
        let globals_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &pipelines.globals_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: globals.as_entire_binding(),
            }],
        });
        let material_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &pipelines.material_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: material_buffer.as_entire_binding(),
            }],
        });
        let meshes = Meshes::new(device, scene, &materials);
        let draws = Draw::all(world);
        Ok(Renderer {
            texture_group,
            shaded: pipelines.shaded,
            ids: pipelines.ids,
            impostor: pipelines.impostor,
            impostor_ids: pipelines.impostor_ids,
            shadow_pipeline: pipelines.shadow,
            sky: pipelines.sky,
            shadow,
            globals,
            globals_group,
            material_group,
            meshes,
            instances: Instances::new(device),
            draw_index: DrawIndex::of(&draws, world.slots()),
            draws,
            gathered: Gathered::default(),
            // Thick enough that what lies at the view distance is mostly haze.
            // Worlds smaller than 400 m (a turntable's) are as clear as one of 400 m.
            fog_density: (1.2 / world.side.max(400.0)).max(2.3 / VIEW_DISTANCE),
            terrain_heights: scene
                .terrain_vertices
                .iter()
                .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), v| {
                    (lo.min(v.position[1]), hi.max(v.position[1]))
                }),
        })
    }

    /// Records one frame into `encoder`: the shadow map (shaded mode), then the sky, the
    /// terrain and the forest.
    pub(crate) fn render(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        (target, depth): (&wgpu::TextureView, &wgpu::TextureView),
        scene: &Scene,
        view: View,
    ) -> FrameStats {
        let started = std::time::Instant::now();
        let shaded = view.mode == Mode::Shaded;
        let sun = SUN.normalize();
        let light_view_proj = light_view_proj(view.eye, view.forward, sun);
        self.write_globals(queue, &view, sun, light_view_proj);
        // The placements each pass can see, gathered into the instance buffer: the camera's
        // first, then the sun's.
        // Each tree at the level of detail its distance asks for (unless the view asks for
        // every tree at full detail); the shadow map's levels are the camera's.
        let chain = lod_chain();
        let lod = (!view.full_detail).then_some(LodView {
            eye: view.eye,
            pixels_per_radian: view.pixels_per_radian,
            pixel_error: chain.pixel_error,
            fade: chain.fade,
        });
        // The sun sees the box from afar at one texel per SHADOW_TEXEL metres.
        let camera = Sight {
            volume: Volume::of(&view.view_proj),
            eye: view.eye,
            pixels_per_radian: view.pixels_per_radian,
        };
        let sun_sight = Sight {
            volume: Volume::of(&light_view_proj),
            eye: view.eye + sun * 1e4,
            pixels_per_radian: 1e4 / SHADOW_TEXEL,
        };
        let sights = if shaded {
            vec![camera, sun_sight]
        } else {
            vec![camera]
        };
        let mut gathered = std::mem::take(&mut self.gathered);
        let pool = self.instances.hold(device, encoder, scene);
        gathered.gather(scene, (&sights, lod), pool);
        if !gathered.picks.is_empty() && !self.instances.can_pick(gathered.picks.len()) {
            // More placements than one storage binding takes: copied on the CPU instead.
            gathered.gather(scene, (&sights, lod), None);
        }
        self.instances.fill(device, encoder, &gathered);
        if shaded {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("shadow"),
                color_attachments: &[],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &self.shadow.view,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.shadow_pipeline);
            self.draw_scene(&mut pass, gathered.ranges(1), false, None);
        }
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("forest"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: target,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: depth,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(1.0),
                    store: wgpu::StoreOp::Discard,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_bind_group(0, &self.globals_group, &[]);
        pass.set_bind_group(1, &self.material_group, &[]);
        pass.set_bind_group(2, &self.texture_group, &[]);
        pass.set_bind_group(3, &self.shadow.group, &[]);
        if shaded {
            // In id mode the sky stays the clear colour, black.
            pass.set_pipeline(&self.sky);
            pass.draw(0..3, 0..1);
        }
        pass.set_pipeline(if shaded { &self.shaded } else { &self.ids });
        let impostor = if shaded {
            &self.impostor
        } else {
            &self.impostor_ids
        };
        let stats = self.draw_scene(&mut pass, gathered.ranges(0), true, Some(impostor));
        let picked = !gathered.picks.is_empty();
        self.gathered = gathered;
        FrameStats {
            cpu_ms: started.elapsed().as_secs_f64() * 1e3,
            picked,
            ..stats
        }
    }

    /// The frame's uniforms: the camera's and the sun's transforms, sky, fog and wind.
    fn write_globals(&self, queue: &wgpu::Queue, view: &View, sun: Vec3, light_view_proj: Mat4) {
        let shaded = view.mode == Mode::Shaded;
        let wind = Vec3::new(0.8, 0.0, 0.6) * view.wind.max(0.0);
        let rgb1 = |c: [f32; 3]| [c[0], c[1], c[2], 1.0];
        let globals = Globals {
            view_proj: view.view_proj.to_cols_array_2d(),
            inverse_view_proj: view.view_proj.inverse().to_cols_array_2d(),
            light_view_proj: light_view_proj.to_cols_array_2d(),
            camera: [view.eye.x, view.eye.y, view.eye.z, 1.0],
            light: [sun.x, sun.y, sun.z, if shaded { 1.0 } else { 0.0 }],
            horizon: rgb1(HORIZON),
            zenith: rgb1(ZENITH),
            fog: [
                if shaded { self.fog_density } else { 0.0 },
                self.terrain_heights.0,
                self.terrain_heights.1,
                0.0,
            ],
            wind: [wind.x, 0.0, wind.z, view.time],
            season: match view.season {
                Some(day) => [day, 1.0, sylva::forest::snow(day), 0.0],
                None => [0.0; 4],
            },
        };
        queue.write_buffer(&self.globals, 0, bytemuck::bytes_of(&globals));
    }

    /// Draws the terrain and the placements of each slot in `ranges` (a group's level, or a
    /// variant's impostors: first and count in the instance buffer) with the pipeline
    /// already set, then the impostor
    /// cards with `impostor` (none: not drawn); `terrain` false leaves the terrain out (the
    /// shadow pass: the ground casts no shadow that matters, and it is the largest single
    /// mesh).
    fn draw_scene(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        ranges: impl Iterator<Item = Range>,
        terrain: bool,
        impostor: Option<&wgpu::RenderPipeline>,
    ) -> FrameStats {
        pass.set_bind_group(0, &self.globals_group, &[]);
        pass.set_bind_group(1, &self.material_group, &[]);
        pass.set_bind_group(2, &self.texture_group, &[]);
        let mut stats = FrameStats::default();
        if terrain {
            let t = &self.meshes.terrain;
            pass.set_vertex_buffer(0, t.vertices.slice(..));
            pass.set_vertex_buffer(2, t.materials.slice(..));
            pass.set_vertex_buffer(1, t.identity.slice(..));
            pass.set_index_buffer(t.indices.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..t.count, 0, 0..1);
            stats.draws += 1;
            stats.instances += 1;
            stats.triangles += u64::from(t.count / 3);
        }
        let Some(instances) = self.instances.buffer() else {
            return stats;
        };
        pass.set_vertex_buffer(1, instances.slice(..));
        // The filled slots' draws, in the draw list's order (by variant and material).
        let mut todo: Vec<(u32, Range)> = ranges
            .flat_map(|r| {
                (self.draw_index.of_slot(r.slot as usize).iter())
                    .map(move |&position| (position, r))
            })
            .collect();
        todo.sort_unstable_by_key(|(position, _)| *position);
        let mut bound: Option<(usize, bool)> = None;
        let mut cards = false;
        for (position, range) in todo {
            let d = &self.draws[position as usize];
            // Impostor cards come last (their variants are numbered after the meshes').
            if d.impostor && !cards {
                let Some(pipeline) = impostor else { break };
                pass.set_pipeline(pipeline);
                cards = true;
            }
            let count = range.count;
            let v = &self.meshes.variants[d.variant];
            let indices = if d.bark { &v.bark } else { &v.leaves };
            let Some(indices) = indices else { continue };
            if bound != Some((d.variant, d.bark)) {
                pass.set_vertex_buffer(0, v.vertices.slice(..));
                pass.set_vertex_buffer(2, v.materials.slice(..));
                pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
                bound = Some((d.variant, d.bark));
            }
            // Each slot's placements sit contiguously in the one instance buffer, bound
            // once: the draw's instance range points at them.
            pass.draw_indexed(
                d.indices.0..d.indices.1,
                0,
                range.first..range.first + count,
            );
            stats.draws += 1;
            stats.instances += u64::from(count);
            stats.triangles += u64::from((d.indices.1 - d.indices.0) / 3) * u64::from(count);
        }
        stats
    }
}
