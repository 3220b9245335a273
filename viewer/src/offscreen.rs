//! Headless rendering: an offscreen target with its own device, frames read back as RGBA.

use crate::error::ViewerError;
use crate::gpu::{device, targets};
use crate::render::{FrameStats, Mode, Renderer, View};
use crate::scene::{Camera, FIELD_OF_VIEW_DEGREES, Scene};

/// Mesa's Vulkan device-select layer looks for a Wayland compositor while adapters are
/// enumerated, and where there is no desktop session (CI, servers) libwayland prints
/// "error: XDG_RUNTIME_DIR is invalid or not set in the environment." to stderr. Offscreen
/// rendering needs no compositor, so in exactly that case, and only while the adapter is
/// requested, stderr is silenced; the guard restores it when dropped.
#[cfg(unix)]
pub(crate) fn quiet_wayland_probe() -> Option<gag::Gag> {
    let no_session = std::env::var_os("XDG_RUNTIME_DIR").is_none_or(|d| d.is_empty());
    if no_session {
        gag::Gag::stderr().ok()
    } else {
        None
    }
}

/// Elsewhere there is no Wayland probe to quiet.
#[cfg(not(unix))]
pub(crate) fn quiet_wayland_probe() -> Option<()> {
    None
}

/// An offscreen target with its device: renders frames and reads them back.
pub(crate) struct Offscreen {
    device: wgpu::Device,
    queue: wgpu::Queue,
    pub(crate) renderer: Renderer,
    colour: wgpu::Texture,
    view: wgpu::TextureView,
    depth: wgpu::TextureView,
    readback: wgpu::Buffer,
    size: (u32, u32),
    /// The adapter's name and backend.
    pub(crate) adapter: String,
    /// Wind strength and the moment of the wind's cycle the frames show (seconds).
    pub(crate) wind: f32,
    /// Every tree at full detail (no coarser levels or impostors).
    pub(crate) full_detail: bool,
    pub(crate) time: f32,
    /// The day of the year the frames show (`None`: the species as given).
    pub(crate) season: Option<f32>,
}

impl Offscreen {
    pub(crate) async fn new(
        scene: &Scene,
        width: u32,
        height: u32,
    ) -> Result<Offscreen, ViewerError> {
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        let (adapter, device, queue) = {
            let _quiet = quiet_wayland_probe();
            device(&instance, None).await?
        };
        let format = wgpu::TextureFormat::Rgba8UnormSrgb;
        let renderer = Renderer::new(&device, &queue, format, scene)?;
        let (colour, view, depth) = targets(&device, format, width, height, true);
        let readback = readback_buffer(&device, (width, height));
        let info = adapter.get_info();
        Ok(Offscreen {
            device,
            queue,
            renderer,
            colour,
            view,
            depth,
            readback,
            size: (width, height),
            adapter: format!("{} ({:?})", info.name, info.backend),
            wind: 1.0,
            full_detail: false,
            time: 0.0,
            season: None,
        })
    }

    /// Streams in the cells `camera` needs (waiting for all of them; in id mode every cell
    /// in view is fine, so the picture measures the real trees), renders one frame and
    /// returns it as tightly packed RGBA8 (sRGB) rows.
    pub(crate) fn frame(
        &mut self,
        scene: &mut Scene,
        camera: &Camera,
        mode: Mode,
    ) -> Result<(Vec<u8>, FrameStats), ViewerError> {
        let (width, height) = self.size;
        let (view_proj, eye) = camera.view_proj(scene, width as f32 / height as f32);
        let streamed = scene.stream(eye, mode == Mode::Ids, true)?;
        let mut encoder = self.device.create_command_encoder(&Default::default());
        let mut stats = self.renderer.render(
            &self.device,
            &self.queue,
            &mut encoder,
            (&self.view, &self.depth),
            scene,
            View {
                view_proj,
                eye,
                forward: camera.forward(),
                mode,
                pixels_per_radian: height as f32 / FIELD_OF_VIEW_DEGREES.to_radians(),
                full_detail: self.full_detail,
                wind: self.wind,
                time: self.time,
                season: self.season,
            },
        );
        let pixels = read_back(
            (&self.device, &self.queue),
            encoder,
            Vec::new(),
            &self.colour,
            &self.readback,
            self.size,
        )?;
        stats.streamed = streamed;
        Ok((pixels, stats))
    }
}

/// Rows of a texture-to-buffer copy must be 256-byte aligned: the padded length of a row of
/// `width` RGBA8 pixels.
fn padded_row(width: u32) -> u32 {
    (width * 4).div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT
}

/// A buffer a frame of `size` pixels is copied into to be read.
pub(crate) fn readback_buffer(device: &wgpu::Device, size: (u32, u32)) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size: u64::from(padded_row(size.0)) * u64::from(size.1),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    })
}

/// Submits `before` and then `encoder` with a copy of `texture` (RGBA8, `size` pixels) into
/// `readback` after its work, waits, and returns the frame as tightly packed rows.
pub(crate) fn read_back(
    (device, queue): (&wgpu::Device, &wgpu::Queue),
    mut encoder: wgpu::CommandEncoder,
    before: Vec<wgpu::CommandBuffer>,
    texture: &wgpu::Texture,
    readback: &wgpu::Buffer,
    (width, height): (u32, u32),
) -> Result<Vec<u8>, ViewerError> {
    let padded = padded_row(width);
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: 0,
            origin: wgpu::Origin3d::ZERO,
            aspect: wgpu::TextureAspect::All,
        },
        wgpu::TexelCopyBufferInfo {
            buffer: readback,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded),
                rows_per_image: Some(height),
            },
        },
        wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
    );
    queue.submit(before.into_iter().chain([encoder.finish()]));
    let slice = readback.slice(..);
    let (tx, rx) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(ViewerError::Poll)?;
    // The callback always runs once the device has been polled to completion.
    let mapped = rx.recv().unwrap_or(Err(wgpu::BufferAsyncError));
    mapped.map_err(ViewerError::Readback)?;
    let row = (width * 4) as usize;
    let mut pixels = Vec::with_capacity(row * height as usize);
    {
        let data = slice.get_mapped_range().map_err(ViewerError::MappedRange)?;
        for r in 0..height as usize {
            let start = r * padded as usize;
            pixels.extend_from_slice(&data[start..start + row]);
        }
    }
    readback.unmap();
    Ok(pixels)
}
