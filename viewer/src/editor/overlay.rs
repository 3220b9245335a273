//! Draws egui's output over a frame with wgpu (egui-wgpu), in the window and headless, and
//! renders the panel alone headless for its golden image.

use egui_wgpu::{Renderer, RendererOptions, ScreenDescriptor};

use crate::error::ViewerError;

/// egui's renderer for one device and target format.
pub(crate) struct Overlay {
    renderer: Renderer,
}

impl Overlay {
    pub(crate) fn new(device: &wgpu::Device, format: wgpu::TextureFormat) -> Overlay {
        Overlay {
            renderer: Renderer::new(device, format, RendererOptions::default()),
        }
    }

    /// Registers a texture of our own (the 3D preview) for egui to show as an image.
    pub(crate) fn register(
        &mut self,
        device: &wgpu::Device,
        view: &wgpu::TextureView,
    ) -> egui::TextureId {
        self.renderer
            .register_native_texture(device, view, wgpu::FilterMode::Linear)
    }

    /// Records egui's `output` drawn over `target` (its contents kept) of `size` pixels;
    /// returns command buffers to submit before `encoder`'s.
    pub(crate) fn draw(
        &mut self,
        (device, queue): (&wgpu::Device, &wgpu::Queue),
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
        ctx: &egui::Context,
        mut output: egui::FullOutput,
        size: (u32, u32),
    ) -> Vec<wgpu::CommandBuffer> {
        for (id, deltas) in output.textures_delta.set.drain() {
            for delta in deltas {
                self.renderer.update_texture(device, queue, id, &delta);
            }
        }
        let primitives =
            ctx.tessellate(std::mem::take(&mut output.shapes), output.pixels_per_point);
        let screen = ScreenDescriptor {
            size_in_pixels: [size.0, size.1],
            pixels_per_point: output.pixels_per_point,
        };
        let commands = self
            .renderer
            .update_buffers(device, queue, encoder, &primitives, &screen);
        {
            let mut pass = encoder
                .begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some("egui"),
                    color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                        view: target,
                        depth_slice: None,
                        resolve_target: None,
                        ops: wgpu::Operations {
                            load: wgpu::LoadOp::Load,
                            store: wgpu::StoreOp::Store,
                        },
                    })],
                    ..Default::default()
                })
                .forget_lifetime();
            self.renderer.render(&mut pass, &primitives, &screen);
        }
        for id in output.textures_delta.free.drain() {
            self.renderer.free_texture(&id);
        }
        commands
    }
}

/// The panel of `editor` alone, rendered headless at `size` pixels over a dark ground, as
/// tightly packed RGBA8 (sRGB) rows. Two passes: the first lays the panel out and loads
/// egui's fonts, the second is drawn.
pub(crate) fn render_panel(
    editor: &mut super::Editor,
    size: (u32, u32),
) -> Result<Vec<u8>, ViewerError> {
    let instance =
        wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    let (_, device, queue) = {
        let _quiet = crate::offscreen::quiet_wayland_probe();
        pollster::block_on(crate::gpu::device(&instance, None))?
    };
    let format = wgpu::TextureFormat::Rgba8UnormSrgb;
    let texture = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("panel"),
        size: wgpu::Extent3d {
            width: size.0,
            height: size.1,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    let view = texture.create_view(&Default::default());
    let ctx = egui::Context::default();
    // A picture of the panel at rest: windows shown at once, not fading in.
    ctx.all_styles_mut(|style| style.animation_time = 0.0);
    let input = || egui::RawInput {
        screen_rect: Some(egui::Rect::from_min_size(
            egui::Pos2::ZERO,
            egui::vec2(size.0 as f32, size.1 as f32),
        )),
        ..Default::default()
    };
    let mut overlay = Overlay::new(&device, format);
    let mut preview = super::preview3d::Preview3d::new(&device);
    editor.preview_image = Some(overlay.register(&device, &preview.view));
    let mut pixels = Vec::new();
    for pass in 0..2 {
        let mut encoder = device.create_command_encoder(&Default::default());
        super::preview3d::show_current(&mut preview, (&device, &queue), &mut encoder, editor);
        let output = ctx.run_ui(input(), |ui| super::panel::show(ui, editor));
        {
            // The ground the panel stands on.
            encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("ground"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color {
                            r: 0.05,
                            g: 0.08,
                            b: 0.05,
                            a: 1.0,
                        }),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                ..Default::default()
            });
        }
        let before = overlay.draw((&device, &queue), &mut encoder, &view, &ctx, output, size);
        if pass == 1 {
            let readback = crate::offscreen::readback_buffer(&device, size);
            pixels = crate::offscreen::read_back(
                (&device, &queue),
                encoder,
                before,
                &texture,
                &readback,
                size,
            )?;
        } else {
            queue.submit(before.into_iter().chain([encoder.finish()]));
        }
    }
    Ok(pixels)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The panel, or `None` (after saying why) where no adapter is available and the
    /// environment does not require one.
    fn panel(editor: &mut super::super::Editor, size: (u32, u32)) -> Option<Vec<u8>> {
        match render_panel(editor, size) {
            Ok(pixels) => Some(pixels),
            Err(e) if std::env::var_os("SYLVA_REQUIRE_GPU").is_none() => {
                eprintln!("skipping the headless panel: {e}");
                None
            }
            Err(e) => panic!("{e}"),
        }
    }

    /// Pixels of the panel's strip (the left third) that are reddish: the problem line.
    fn red(pixels: &[u8], size: (u32, u32)) -> usize {
        pixels
            .chunks_exact(4)
            .enumerate()
            .filter(|(k, p)| {
                (*k as u32 % size.0) < size.0 / 3 && p[0] > 180 && p[1] < 150 && p[2] < 150
            })
            .count()
    }

    /// Pixels of the right third (where the preview window stands) that are leafy green.
    fn leafy(pixels: &[u8], size: (u32, u32)) -> usize {
        pixels
            .chunks_exact(4)
            .enumerate()
            .filter(|(k, p)| {
                (*k as u32 % size.0) > 2 * size.0 / 3 && p[1] > p[0] + 25 && p[1] > p[2] + 25
            })
            .count()
    }

    /// The panel's three tabs at 1280 x 720, as the editor opens the bundled species, match
    /// their pictures in docs/editor: at most 0.5% of the pixels differ by more than 16 levels
    /// (the preview's build time is in its text). `SYLVA_BLESS=1` writes them.
    #[test]
    fn the_panels_match_their_goldens() {
        let size = (1280, 720);
        for (tab, name) in [
            (super::super::Tab::Species, "species"),
            (super::super::Tab::Forest, "forest"),
            (super::super::Tab::Tools, "tools"),
        ] {
            let project = std::env::temp_dir().join(format!("sylva-panel-golden-{name}"));
            let _ = std::fs::remove_dir_all(&project);
            let settings = super::super::forest::ForestSettings::of_flags(1, 800.0, Some(32));
            let mut editor = super::super::Editor::open(&[], project.clone(), settings).unwrap();
            editor.tab = tab;
            let Some(pixels) = panel(&mut editor, size) else {
                return;
            };
            let _ = std::fs::remove_dir_all(&project);
            let path = format!("{}/../docs/editor/{name}.png", env!("CARGO_MANIFEST_DIR"));
            if std::env::var_os("SYLVA_BLESS").is_some() {
                crate::write_png(&path, size, &pixels).unwrap();
                continue;
            }
            let golden = crate::golden::read_png(&path)
                .unwrap_or_else(|| panic!("{path} missing: run with SYLVA_BLESS=1 to write it"));
            assert_eq!(golden.len(), pixels.len(), "{name}");
            let differing = pixels
                .chunks_exact(4)
                .zip(golden.chunks_exact(4))
                .filter(|(a, b)| a.iter().zip(*b).any(|(x, y)| x.abs_diff(*y) > 16))
                .count();
            assert!(
                differing * 200 <= pixels.len() / 4,
                "{name}: {differing} pixels differ from {path}"
            );
        }
    }

    /// The panel draws its text over its ground, and a grammar that does not read shows its
    /// problem in red below the grammar; the preview window shows the tree, and nothing
    /// while the grammar does not read.
    #[test]
    fn the_panel_shows_a_problem_in_red() {
        let project = std::env::temp_dir().join("sylva-panel-problem");
        let settings = super::super::forest::ForestSettings::of_flags(1, 400.0, Some(32));
        let mut editor = super::super::Editor::open(&[], project.clone(), settings).unwrap();
        let size = (1280, 720);
        let Some(clean) = panel(&mut editor, size) else {
            return;
        };
        // Light text on the dark panel: many bright pixels in its strip.
        let bright = clean
            .chunks_exact(4)
            .enumerate()
            .filter(|(k, p)| (*k as u32 % size.0) < size.0 / 3 && p[0] > 200 && p[1] > 200)
            .count();
        assert!(bright > 2000, "{bright} bright pixels");
        assert_eq!(red(&clean, size), 0);
        assert!(
            leafy(&clean, size) > 5000,
            "{} leafy pixels",
            leafy(&clean, size)
        );
        editor.edit(|d| d.grammar_text.push_str("\nA -> B(1,"));
        let broken = panel(&mut editor, size).expect("rendered once already");
        assert!(
            red(&broken, size) > 100,
            "{} red pixels",
            red(&broken, size)
        );
        assert!(leafy(&broken, size) < 100, "{}", leafy(&broken, size));
        let _ = std::fs::remove_dir_all(&project);
    }
}
