//! The frame's instance buffer, which the draws read their placements from: filled on the
//! GPU from the [`Pool`] of the drawn cells' placements where the device runs compute
//! shaders, the frame sending only which placements it draws; otherwise copied from the
//! cells on the CPU and uploaded whole.

use std::num::NonZeroU64;

use crate::gather::Gathered;
use crate::geometry::InstanceRaw;
use crate::pool::{Layout, Pool};
use crate::scene::Scene;

/// Bytes of each staging buffer: room for a default view's placements (about 4.4 MB at
/// 1280x720) in one, or for several cells' placements on their way to the pool.
const STAGING_CHUNK: u64 = 8 << 20;

/// Threads in one workgroup of `pick.wgsl`, and its workgroups in one row of a dispatch.
const WORKGROUP: u32 = 64;
const ROW: u32 = 65535;
/// Bytes of one placement.
const INSTANCE: u64 = size_of::<InstanceRaw>() as u64;

/// The frame's instance buffer and what fills it.
pub(crate) struct Instances {
    /// The placements in view this frame, then those in the sun's box; grown when a frame
    /// needs more room.
    buffer: Option<wgpu::Buffer>,
    /// Mapped buffers uploads are written into and copied from, kept and mapped again after
    /// each frame: a fresh staging buffer per frame (what `Queue::write_buffer` makes) costs
    /// megabytes of page faults and zeroing, frame after frame.
    staging: wgpu::util::StagingBelt,
    /// The pool and the pipeline that picks from it; none on a device without compute
    /// shaders.
    picking: Option<Picking>,
    /// Whether frames pick from the pool when the device can (false: every frame's
    /// placements are copied on the CPU, as on a device without compute shaders).
    pub(crate) pick: bool,
}

/// What picks a frame's placements on the GPU.
struct Picking {
    pool: Pool,
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    /// The frame's picks; grown when a frame needs more room.
    picks: Option<wgpu::Buffer>,
    /// The most bytes one storage binding takes on this device.
    most: u64,
}

impl Instances {
    /// An empty instance buffer, picking on the GPU where `device` runs compute shaders
    /// with storage buffers enough.
    pub(crate) fn new(device: &wgpu::Device) -> Instances {
        let limits = device.limits();
        let computes = limits.max_compute_workgroups_per_dimension >= ROW
            && limits.max_compute_invocations_per_workgroup >= WORKGROUP
            && limits.max_storage_buffers_per_shader_stage >= 3;
        Instances {
            buffer: None,
            staging: wgpu::util::StagingBelt::new(device.clone(), STAGING_CHUNK),
            picking: computes.then(|| Picking::new(device)),
            pick: true,
        }
    }

    /// The buffer the draws read, once a frame has filled it.
    pub(crate) fn buffer(&self) -> Option<&wgpu::Buffer> {
        self.buffer.as_ref()
    }

    /// Before a frame is gathered: holds the cells `scene` draws in the pool, uploading
    /// those new to it. The pool's layout, for gathering picks from; none when the frame's
    /// placements are to be copied.
    pub(crate) fn hold(
        &mut self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        scene: &Scene,
    ) -> Option<&Layout> {
        // Staging chunks whose copies are done are mapped again by the device's callbacks.
        // A poll that fails only delays that: the belt then makes another chunk.
        let _ = device.poll(wgpu::PollType::Poll);
        let picking = self.picking.as_mut().filter(|_| self.pick)?;
        let cells: Vec<_> = scene.cells.drawn().map(|(_, cell)| cell).collect();
        let held = (picking.pool).hold(device, (encoder, &mut self.staging), &cells);
        held.then_some(&picking.pool.layout)
    }

    /// Whether a frame's `count` placements can be picked on the GPU: the instance buffer
    /// they fill is bound as one storage buffer, and must fit in one binding.
    pub(crate) fn can_pick(&self, count: usize) -> bool {
        (self.picking.as_ref()).is_some_and(|p| count as u64 * INSTANCE <= p.most)
    }

    /// Fills the instance buffer with the frame's placements: picked on the GPU from the
    /// pool when `gathered` holds picks, copied otherwise.
    pub(crate) fn fill(
        &mut self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        gathered: &Gathered,
    ) {
        let (picks, visible) = (&gathered.picks, &gathered.visible);
        let count = picks.len().max(visible.len()) as u64;
        let bytes = count * INSTANCE;
        if bytes > self.buffer.as_ref().map_or(0, wgpu::Buffer::size) {
            // Room for the most a frame has needed, rounded up, so walking does not
            // reallocate it frame after frame.
            self.buffer = Some(device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("instances in view"),
                size: bytes.next_power_of_two(),
                // Written by the picking pass where there is one.
                usage: wgpu::BufferUsages::VERTEX
                    | wgpu::BufferUsages::COPY_DST
                    | if self.picking.is_some() {
                        wgpu::BufferUsages::STORAGE
                    } else {
                        wgpu::BufferUsages::empty()
                    },
                mapped_at_creation: false,
            }));
        }
        let (Some(buffer), Some(size)) = (&self.buffer, NonZeroU64::new(bytes)) else {
            self.staging.finish_and_recall_on_submit(encoder);
            return;
        };
        match &mut self.picking {
            Some(picking) if !picks.is_empty() => {
                picking.pick(device, (encoder, &mut self.staging), picks, buffer);
            }
            _ => {
                let mut view = self.staging.write_buffer(encoder, buffer, 0, size);
                view.copy_from_slice(bytemuck::cast_slice(visible));
            }
        }
        self.staging.finish_and_recall_on_submit(encoder);
    }
}

impl Picking {
    fn new(device: &wgpu::Device) -> Picking {
        let storage = |binding: u32, read_only: bool| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only },
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("picking"),
            entries: &[storage(0, true), storage(1, true), storage(2, false)],
        });
        let shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("pick.wgsl"),
            source: wgpu::ShaderSource::Wgsl(include_str!("pick.wgsl").into()),
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("picking"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("picking"),
            layout: Some(&pipeline_layout),
            module: &shader,
            entry_point: Some("pick"),
            compilation_options: Default::default(),
            cache: None,
        });
        Picking {
            pool: Pool::new(device),
            pipeline,
            layout,
            picks: None,
            most: device.limits().max_storage_buffer_binding_size,
        }
    }

    /// Uploads `picks` and records the pass that copies each picked placement from the
    /// pool into `drawn`, in order.
    fn pick(
        &mut self,
        device: &wgpu::Device,
        (encoder, belt): (&mut wgpu::CommandEncoder, &mut wgpu::util::StagingBelt),
        picks: &[[u32; 2]],
        drawn: &wgpu::Buffer,
    ) {
        let (Some(pool), Some(size)) = (
            self.pool.buffer(),
            NonZeroU64::new(size_of_val(picks) as u64),
        ) else {
            return;
        };
        if size.get() > self.picks.as_ref().map_or(0, wgpu::Buffer::size) {
            self.picks = Some(device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("picks"),
                size: size.get().next_power_of_two(),
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }));
        }
        let Some(picks_buffer) = &self.picks else {
            return;
        };
        belt.write_buffer(encoder, picks_buffer, 0, size)
            .copy_from_slice(bytemuck::cast_slice(picks));
        // The bindings are exactly this frame's, so the shader's `arrayLength` is the picks'
        // count (and a buffer grown by an earlier, larger frame is never bound whole).
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("picking"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: pool.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer: picks_buffer,
                        offset: 0,
                        size: Some(size),
                    }),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer: drawn,
                        offset: 0,
                        size: NonZeroU64::new(picks.len() as u64 * INSTANCE),
                    }),
                },
            ],
        });
        let groups = (picks.len() as u32).div_ceil(WORKGROUP);
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("picking"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &group, &[]);
        pass.dispatch_workgroups(groups.min(ROW), groups.div_ceil(ROW), 1);
    }
}
