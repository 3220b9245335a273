//! The windowed mode: winit event loop, walking camera, frame statistics in the title.

use std::collections::HashSet;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use winit::application::ApplicationHandler;
use winit::event::{DeviceEvent, DeviceId, ElementState, MouseButton, WindowEvent};
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::keyboard::{KeyCode, PhysicalKey};
use winit::window::{CursorGrabMode, Window, WindowId};

mod editing;

use crate::editor::Editor;
use crate::editor::forest::ForestSettings;
use crate::editor::in_window::EditorWindow;
use crate::error::ViewerError;
use crate::gpu::targets;
use crate::guide::Guide;
use crate::painting::{Painting, pick};
use crate::rebuild::Rebuild;
use crate::render::{Mode, Renderer, View};
use crate::scene::{Camera, FIELD_OF_VIEW_DEGREES, Scene};
use crate::world::SceneOptions;
use sylva::forest::Species;
use sylva::terrain::glam::Vec2;
use winit::event::Modifiers;
use winit::keyboard::Key;

struct Gpu {
    window: Arc<Window>,
    surface: wgpu::Surface<'static>,
    device: wgpu::Device,
    queue: wgpu::Queue,
    config: wgpu::SurfaceConfiguration,
    renderer: Renderer,
    depth: wgpu::TextureView,
}

struct App {
    scene: Scene,
    camera: Camera,
    gpu: Option<Gpu>,
    keys: HashSet<KeyCode>,
    captured: bool,
    last: Instant,
    /// When the window opened: the wind's clock.
    started: Instant,
    /// The day of the year drawn, and whether the year plays (N).
    year: crate::season::YearClock,
    frame_ms: f64,
    error: Option<ViewerError>,
    lost: Arc<AtomicBool>,
    /// Close after this many frames (0: run until closed), printing frame times.
    max_frames: u32,
    frame_times: Vec<f64>,
    /// The painting tool, once P has been pressed, and whether it is on.
    painting: Option<Painting>,
    paint_mode: bool,
    /// Where the painting tool saves its masks.
    save_to: std::path::PathBuf,
    /// The guided walk, while G has it on; `look` turns the view from its way.
    guide: Option<Guide>,
    guides: u64,
    look: f32,
    cursor: (f32, f32),
    /// The right button is down: mouse motion looks around while painting.
    looking: bool,
    modifiers: Modifiers,
    /// The species editor, waiting for the window, then in it (F2 shows or hides it).
    waiting_editor: Option<Editor>,
    editor: Option<EditorWindow>,
    /// The options the world was built from, which the editor's rebuilds start from.
    base: SceneOptions,
    /// The world being built again after the editor's changes, and the change that waits
    /// for it to finish.
    rebuild: Option<Rebuild>,
    waiting_forest: Option<(Vec<Species>, ForestSettings, u64)>,
    /// The [`Editor::recipe`] of the world in use and of the one being built: a rebuild of
    /// the same recipe keeps the forest and makes only the ground anew.
    recipe: Option<u64>,
    building: Option<u64>,
    /// Frames drawn so far, and rebuilds finished (the status line counts both).
    frames: u64,
    rebuilds: u64,
}

/// Opens the window and runs until it closes. Errors (no display, no adapter, a lost device)
/// come back as messages.
///
/// Keys: P paints (then 1 to 9 pick the species, E erases, T turns trees into the species,
/// `[` `]` size the brush, `-` `=` set its strength, Ctrl+Z undo, Ctrl+Y redo, Ctrl+S saves
/// the masks to `save_to`; the left button paints, the right one looks around); G walks
/// guided (the mouse looks around, A and D lean left and right, Shift hurries). With an
/// `editor`, its panel stands at the left (F2 shows or hides it): the world is built again
/// from `base` when its species or forest settings change, masks save into its project, and
/// Ctrl+Z and Ctrl+Y undo and redo strokes and edits in one history.
pub(crate) fn run(
    scene: Scene,
    base: SceneOptions,
    camera: Option<Camera>,
    max_frames: u32,
    save_to: std::path::PathBuf,
    editor: Option<Editor>,
    season: Option<f32>,
) -> Result<(), ViewerError> {
    let save_to = match &editor {
        Some(e) => e.project.join(sylva::world::MASKS_FOLDER),
        None => save_to,
    };
    let event_loop = EventLoop::new().map_err(ViewerError::NoDisplay)?;
    let camera = camera.unwrap_or_else(|| Camera::overview(scene.side(), 1.7));
    let mut app = App {
        scene,
        camera,
        gpu: None,
        keys: HashSet::new(),
        captured: false,
        last: Instant::now(),
        started: Instant::now(),
        year: crate::season::YearClock::at(season),
        frame_ms: 0.0,
        error: None,
        lost: Arc::new(AtomicBool::new(false)),
        max_frames,
        frame_times: Vec::new(),
        painting: None,
        paint_mode: false,
        save_to,
        guide: None,
        guides: 0,
        look: 0.0,
        cursor: (0.0, 0.0),
        looking: false,
        modifiers: Modifiers::default(),
        waiting_editor: editor,
        editor: None,
        base,
        rebuild: None,
        waiting_forest: None,
        recipe: None,
        building: None,
        frames: 0,
        rebuilds: 0,
    };
    let ran = event_loop.run_app(&mut app);
    // However the loop ended (closed, --frames done, an error), the session ended as it
    // should: edits are autosaved and the running mark goes.
    if let Some(editor) = &mut app.editor {
        editor.quit();
    }
    ran.map_err(ViewerError::EventLoop)?;
    app.error.map_or(Ok(()), Err)
}

impl App {
    fn fail(&mut self, event_loop: &ActiveEventLoop, error: impl Into<ViewerError>) {
        self.error = Some(error.into());
        event_loop.exit();
    }

    fn init(&mut self, event_loop: &ActiveEventLoop) -> Result<Gpu, ViewerError> {
        let window = Arc::new(
            event_loop
                .create_window(Window::default_attributes().with_title("sylva"))
                .map_err(ViewerError::Window)?,
        );
        // The display handle lets the GL backend (WGPU_BACKEND=gl) present to the window too.
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_with_display_handle_from_env(
                Box::new(event_loop.owned_display_handle()),
            ));
        let surface = instance
            .create_surface(window.clone())
            .map_err(ViewerError::Surface)?;
        let (adapter, device, queue) =
            pollster::block_on(crate::gpu::device(&instance, Some(&surface)))?;
        let lost = self.lost.clone();
        device.set_device_lost_callback(move |_, _| lost.store(true, Ordering::SeqCst));
        let size = window.inner_size();
        let mut config = surface
            .get_default_config(&adapter, size.width.max(1), size.height.max(1))
            .ok_or(ViewerError::CannotPresent)?;
        let caps = surface.get_capabilities(&adapter);
        if let Some(srgb) = caps.formats.iter().find(|f| f.is_srgb()) {
            config.format = *srgb;
        }
        surface.configure(&device, &config);
        let renderer = Renderer::new(&device, &queue, config.format, &self.scene)?;
        let (_, _, depth) = targets(&device, config.format, config.width, config.height, false);
        Ok(Gpu {
            window,
            surface,
            device,
            queue,
            config,
            renderer,
            depth,
        })
    }

    fn walk(&mut self, dt: f32) {
        let hurry =
            self.keys.contains(&KeyCode::ShiftLeft) || self.keys.contains(&KeyCode::ShiftRight);
        if let Some(guide) = &mut self.guide {
            // Led: a walking pace; the walker may only lean a little off the way.
            let lean = f32::from(u8::from(self.keys.contains(&KeyCode::KeyD)))
                - f32::from(u8::from(self.keys.contains(&KeyCode::KeyA)));
            guide.advance(if hurry { 5.6 } else { 1.4 } * dt, lean);
            self.camera = guide.camera(self.look, self.camera.pitch);
            return;
        }
        let speed = if hurry { 20.0 } else { 5.0 };
        let (s, c) = self.camera.yaw.sin_cos();
        let mut step = [0.0f32; 2];
        for (key, dx, dz) in [
            (KeyCode::KeyW, c, s),
            (KeyCode::KeyS, -c, -s),
            (KeyCode::KeyD, -s, c),
            (KeyCode::KeyA, s, -c),
        ] {
            if self.keys.contains(&key) {
                step[0] += dx;
                step[1] += dz;
            }
        }
        let side = self.scene.side();
        self.camera.x = (self.camera.x + step[0] * speed * dt).clamp(0.0, side);
        self.camera.z = (self.camera.z + step[1] * speed * dt).clamp(0.0, side);
    }

    fn redraw(&mut self, event_loop: &ActiveEventLoop) {
        if self.lost.load(Ordering::SeqCst) {
            return self.fail(event_loop, ViewerError::DeviceLost);
        }
        let now = Instant::now();
        let elapsed = (now - self.last).as_secs_f64();
        self.last = now;
        // Movement steps at most 0.1 s at a time, so a slow frame does not jump the camera;
        // the frame time shown and measured is the real one.
        self.walk(elapsed.min(0.1) as f32);
        self.frames += 1;
        self.tend_editor();
        // Cells arrive from the loader thread; until a fine cell comes its coarse one stands
        // in.
        let streamed = match self
            .scene
            .stream(self.camera.eye(&self.scene), false, false)
        {
            Ok(s) => s,
            Err(e) => return self.fail(event_loop, e),
        };
        let Some(gpu) = &mut self.gpu else { return };
        if gpu.config.width == 0 || gpu.config.height == 0 {
            return;
        }
        let frame = match gpu.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(f)
            | wgpu::CurrentSurfaceTexture::Suboptimal(f) => f,
            wgpu::CurrentSurfaceTexture::Timeout | wgpu::CurrentSurfaceTexture::Occluded => return,
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                gpu.surface.configure(&gpu.device, &gpu.config);
                return;
            }
            wgpu::CurrentSurfaceTexture::Validation => {
                return self.fail(event_loop, ViewerError::SurfaceInvalid);
            }
        };
        let view = frame.texture.create_view(&Default::default());
        let aspect = gpu.config.width as f32 / gpu.config.height as f32;
        let (view_proj, eye) = self.camera.view_proj(&self.scene, aspect);
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        let stats = gpu.renderer.render(
            &gpu.device,
            &gpu.queue,
            &mut encoder,
            (&view, &gpu.depth),
            &self.scene,
            View {
                view_proj,
                eye,
                forward: self.camera.forward(),
                mode: Mode::Shaded,
                pixels_per_radian: gpu.config.height as f32 / FIELD_OF_VIEW_DEGREES.to_radians(),
                full_detail: false,
                wind: 1.0,
                time: self.started.elapsed().as_secs_f32(),
                season: self.year.day(),
            },
        );
        let before = match &mut self.editor {
            Some(editor) => editor.draw(
                &gpu.window,
                (&gpu.device, &gpu.queue),
                &mut encoder,
                &view,
                (gpu.config.width, gpu.config.height),
            ),
            None => Vec::new(),
        };
        gpu.queue
            .submit(before.into_iter().chain([encoder.finish()]));
        gpu.queue.present(frame);
        self.frame_ms = 0.9 * self.frame_ms + 0.1 * elapsed * 1e3;
        if self.max_frames > 0 {
            self.frame_times.push(elapsed * 1e3);
            if self.frame_times.len() as u32 >= self.max_frames {
                let mut t = self.frame_times[1..].to_vec();
                println!(
                    "{} frames: {} draw calls, {} instances, {} triangles per frame; median frame {:.0} ms",
                    self.frame_times.len(),
                    stats.draws,
                    stats.instances,
                    stats.triangles,
                    crate::median(&mut t).unwrap_or(0.0)
                );
                event_loop.exit();
            }
        }
        let editing = self
            .editor
            .as_ref()
            .map(EditorWindow::title)
            .unwrap_or_default();
        let mut mode = match (&self.painting, self.paint_mode, &self.guide) {
            (Some(p), true, _) => format!("{}; ", p.status()),
            (_, _, Some(_)) => "guided walk (G to stop); ".to_string(),
            _ => String::new(),
        };
        if let Some(year) = self.scene.world.year() {
            mode.push_str(&format!("year {year} (Y: +10, Shift+Y: +1); "));
        }
        mode.push_str(&self.year.title());
        gpu.window.set_title(&format!(
            "sylva: {editing}{mode}{} draw calls, {} instances, {:.1} M triangles, {:.1} ms; {} trees in {} cells{}",
            stats.draws,
            stats.instances,
            stats.triangles as f64 / 1e6,
            self.frame_ms,
            streamed.trees,
            streamed.resident,
            if streamed.pending > 0 {
                format!(", {} cells coming", streamed.pending)
            } else {
                String::new()
            }
        ));
    }

    /// Where the cursor points on the terrain.
    fn under_cursor(&self) -> Option<sylva::terrain::glam::Vec3> {
        let gpu = self.gpu.as_ref()?;
        let size = (gpu.config.width as f32, gpu.config.height as f32);
        let (view_proj, eye) = self.camera.view_proj(&self.scene, size.0 / size.1.max(1.0));
        pick(&self.scene, view_proj, eye, self.cursor, size)
    }

    /// A key while painting: the tool's keys go to it.
    fn paint_key(&mut self, event: &winit::event::KeyEvent) -> bool {
        let (Some(painting), true) = (&mut self.painting, self.paint_mode) else {
            return false;
        };
        let Key::Character(text) = &event.logical_key else {
            return false;
        };
        let state = self.modifiers.state();
        let key = text.to_lowercase();
        // With the editor, strokes undo in its one history, in turn with its edits.
        if let Some(w) = &mut self.editor
            && state.control_key()
            && (key == "z" || key == "y")
        {
            if key == "y" || state.shift_key() {
                w.editor.redo();
            } else {
                w.editor.undo();
            }
            return true;
        }
        let used = painting.key(
            &mut self.scene,
            &key,
            state.control_key(),
            state.shift_key(),
        );
        self.after_painting();
        used
    }

    /// After the painting tool acted: a forest it changed has new trunks for the guided walk
    /// to steer round.
    fn after_painting(&mut self) {
        if self.painting.as_mut().is_some_and(Painting::take_changed)
            && let Some(guide) = &mut self.guide
        {
            guide.forget_trunks();
        }
    }

    /// P: the painting tool on or off (the cursor is freed to paint).
    fn toggle_painting(&mut self) {
        if self.painting.is_none() {
            match Painting::new(&mut self.scene, self.save_to.clone()) {
                Ok(p) => self.painting = Some(p),
                Err(e) => {
                    eprintln!("cannot paint: {e}");
                    return;
                }
            }
        }
        self.paint_mode = !self.paint_mode;
        if self.paint_mode {
            self.capture(false);
        }
    }

    /// G: the guided walk on or off.
    fn toggle_guide(&mut self) {
        if self.guide.take().is_some() {
            return;
        }
        self.guides += 1;
        let start = Vec2::new(self.camera.x, self.camera.z);
        match Guide::new(&self.scene.world, start, self.guides) {
            Ok(g) => {
                self.look = 0.0;
                self.guide = Some(g);
            }
            Err(e) => eprintln!("cannot walk guided here: {e}"),
        }
    }

    fn capture(&mut self, on: bool) {
        let Some(gpu) = &self.gpu else { return };
        let mode = if on {
            CursorGrabMode::Locked
        } else {
            CursorGrabMode::None
        };
        let grabbed = gpu.window.set_cursor_grab(mode).or_else(|_| {
            gpu.window.set_cursor_grab(if on {
                CursorGrabMode::Confined
            } else {
                CursorGrabMode::None
            })
        });
        gpu.window.set_cursor_visible(!on);
        self.captured = on && grabbed.is_ok();
    }
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.gpu.is_none() {
            match self.init(event_loop) {
                Ok(gpu) => {
                    if let Some(editor) = self.waiting_editor.take() {
                        // The world was built from the editor's species as it opened.
                        self.recipe = Some(editor.recipe());
                        self.editor = Some(EditorWindow::new(
                            editor,
                            &gpu.window,
                            &gpu.device,
                            gpu.config.format,
                        ));
                    }
                    self.gpu = Some(gpu);
                }
                Err(e) => self.fail(event_loop, e),
            }
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        // Input the panel takes (typing in its editor, dragging its sliders) is not the walk's.
        let input = matches!(
            event,
            WindowEvent::KeyboardInput { .. }
                | WindowEvent::MouseInput { .. }
                | WindowEvent::CursorMoved { .. }
                | WindowEvent::MouseWheel { .. }
                | WindowEvent::Ime(_)
        );
        if let (Some(editor), Some(gpu)) = (&mut self.editor, &self.gpu)
            && editor.on_event(&gpu.window, &event)
            && input
        {
            return;
        }
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => {
                if let Some(gpu) = &mut self.gpu {
                    // A minimised window has size zero: keep the old surface until it returns.
                    if size.width > 0 && size.height > 0 {
                        gpu.config.width = size.width;
                        gpu.config.height = size.height;
                        gpu.surface.configure(&gpu.device, &gpu.config);
                        gpu.depth = targets(
                            &gpu.device,
                            gpu.config.format,
                            size.width,
                            size.height,
                            false,
                        )
                        .2;
                    } else {
                        gpu.config.width = 0;
                    }
                }
            }
            WindowEvent::ModifiersChanged(m) => self.modifiers = m,
            WindowEvent::KeyboardInput { event, .. } => {
                if let PhysicalKey::Code(code) = event.physical_key {
                    if event.state == ElementState::Pressed {
                        if !event.repeat && self.paint_key(&event) {
                            return;
                        }
                        match code {
                            KeyCode::Escape => self.capture(false),
                            KeyCode::F2 if !event.repeat => {
                                if let Some(editor) = &mut self.editor {
                                    editor.visible = !editor.visible;
                                }
                            }
                            KeyCode::KeyP if !event.repeat => self.toggle_painting(),
                            KeyCode::KeyG if !event.repeat => self.toggle_guide(),
                            KeyCode::KeyN => {
                                let shift = self.keys.contains(&KeyCode::ShiftLeft)
                                    || self.keys.contains(&KeyCode::ShiftRight);
                                if shift {
                                    self.year.advance(10.0);
                                } else if !event.repeat {
                                    self.year.toggle();
                                }
                            }
                            KeyCode::KeyY => {
                                let shift = self.keys.contains(&KeyCode::ShiftLeft)
                                    || self.keys.contains(&KeyCode::ShiftRight);
                                // A world without a forest over time does nothing.
                                if let Err(e) = self.scene.advance_years(if shift { 1 } else { 10 })
                                {
                                    eprintln!("cannot move the forest on: {e}");
                                }
                            }
                            _ => {}
                        }
                        self.keys.insert(code);
                    } else {
                        self.keys.remove(&code);
                    }
                }
            }
            WindowEvent::CursorMoved { position, .. } => {
                self.cursor = (position.x as f32, position.y as f32);
                if self.paint_mode {
                    let point = self.under_cursor();
                    if let Some(p) = &mut self.painting {
                        p.drag(&mut self.scene, point);
                    }
                    self.after_painting();
                }
            }
            WindowEvent::MouseInput { state, button, .. } => match (button, state) {
                (MouseButton::Left, ElementState::Pressed) if self.paint_mode => {
                    let point = self.under_cursor();
                    if let Some(p) = &mut self.painting {
                        p.press(&mut self.scene, point);
                    }
                }
                (MouseButton::Left, ElementState::Released) => {
                    if let Some(p) = &mut self.painting
                        && p.release()
                        && let Some(w) = &mut self.editor
                    {
                        w.editor.record_stroke();
                    }
                }
                (MouseButton::Left, ElementState::Pressed) => self.capture(true),
                (MouseButton::Right, s) => self.looking = s == ElementState::Pressed,
                _ => {}
            },
            WindowEvent::RedrawRequested => self.redraw(event_loop),
            _ => {}
        }
    }

    fn device_event(&mut self, _event_loop: &ActiveEventLoop, _id: DeviceId, event: DeviceEvent) {
        if let DeviceEvent::MouseMotion { delta } = event
            && (self.captured || self.looking)
        {
            if self.guide.is_some() {
                self.look += delta.0 as f32 * 0.003;
            } else {
                self.camera.yaw += delta.0 as f32 * 0.003;
            }
            self.camera.pitch = (self.camera.pitch - delta.1 as f32 * 0.003).clamp(-1.5, 1.5);
        }
    }

    fn about_to_wait(&mut self, _event_loop: &ActiveEventLoop) {
        if let Some(gpu) = &self.gpu {
            gpu.window.request_redraw();
        }
    }
}
