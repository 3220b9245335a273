//! The editor in the viewer's window: egui's input from winit, the panel drawn over each
//! frame, F2 to show or hide it, files reloaded and the project autosaved as frames pass.

use winit::event::WindowEvent;
use winit::window::Window;

use super::Editor;
use super::overlay::Overlay;
use super::preview3d::{Preview3d, show_current};

/// The editor with what it needs to live in a window.
pub(crate) struct EditorWindow {
    pub(crate) editor: Editor,
    ctx: egui::Context,
    input: egui_winit::State,
    overlay: Overlay,
    preview: Preview3d,
    /// Whether the panel is shown (F2).
    pub(crate) visible: bool,
    /// Where the cursor is, in physical pixels.
    cursor_x: f32,
}

impl EditorWindow {
    pub(crate) fn new(
        editor: Editor,
        window: &Window,
        device: &wgpu::Device,
        format: wgpu::TextureFormat,
    ) -> EditorWindow {
        let ctx = egui::Context::default();
        let input = egui_winit::State::new(
            ctx.clone(),
            egui::ViewportId::ROOT,
            window,
            Some(window.scale_factor() as f32),
            None,
            Some(device.limits().max_texture_dimension_2d as usize),
        );
        let mut overlay = Overlay::new(device, format);
        let preview = Preview3d::new(device);
        let mut editor = editor;
        editor.preview_image = Some(overlay.register(device, &preview.view));
        EditorWindow {
            editor,
            ctx,
            input,
            overlay,
            preview,
            visible: true,
            cursor_x: f32::INFINITY,
        }
    }

    /// Gives the panel a window event; whether the panel used it (the walk must not). A
    /// button or wheel over the panel is its own even before egui has seen the cursor there
    /// (egui judges by the frame before: a first click would start the walk's mouse look).
    pub(crate) fn on_event(&mut self, window: &Window, event: &WindowEvent) -> bool {
        if !self.visible {
            return false;
        }
        if let WindowEvent::CursorMoved { position, .. } = event {
            self.cursor_x = position.x as f32;
        }
        let over_panel = matches!(
            event,
            WindowEvent::MouseInput { .. } | WindowEvent::MouseWheel { .. }
        ) && self.cursor_x < super::panel::WIDTH * window.scale_factor() as f32;
        self.input.on_window_event(window, event).consumed || over_panel
    }

    /// Runs the panel for this frame and records it over `target`; returns command buffers
    /// to submit before `encoder`'s. Files changed on disk are read again first, and the
    /// project is autosaved when its interval has passed.
    pub(crate) fn draw(
        &mut self,
        window: &Window,
        gpu: (&wgpu::Device, &wgpu::Queue),
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
        size: (u32, u32),
    ) -> Vec<wgpu::CommandBuffer> {
        self.editor.reload_changed();
        self.editor.autosave(false);
        if !self.visible {
            return Vec::new();
        }
        show_current(&mut self.preview, gpu, encoder, &self.editor);
        let raw = self.input.take_egui_input(window);
        let editor = &mut self.editor;
        let mut output = self.ctx.run_ui(raw, |ui| super::panel::show(ui, editor));
        let platform = std::mem::take(&mut output.platform_output);
        self.input.handle_platform_output(window, platform);
        self.overlay
            .draw(gpu, encoder, target, &self.ctx, output, size)
    }

    /// The line the window's title shows of the editor: the species and its preview, or its
    /// problem (scripts driving the window read it).
    pub(crate) fn title(&self) -> String {
        let d = self.editor.current();
        let offer = if self.editor.restorable.is_some() {
            "an autosave to restore; "
        } else {
            ""
        };
        let forest = &self.editor.tools.forest;
        let forest = if forest.is_empty() {
            String::new()
        } else {
            format!("{forest}; ")
        };
        match &d.outcome {
            Ok(p) => format!(
                "{offer}editing {}: {} triangles in {:.0} ms; {forest}",
                d.name, p.triangles, p.millis
            ),
            Err(problem) => format!("{offer}editing {}: {problem}; {forest}", d.name),
        }
    }

    /// The window closes: unsaved edits are autosaved and the session marked as ended.
    pub(crate) fn quit(&mut self) {
        self.editor.autosave(true);
        super::project::mark_quit(&self.editor.project);
    }
}
