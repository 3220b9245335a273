//! What can go wrong in the viewer, with the library's errors kept as sources so the message
//! says what failed and why.

use std::path::PathBuf;

use sylva::forest::ForestError;
use sylva::paint::PaintError;
use sylva::terrain::TerrainError;

/// A viewer error: the command line, the world, the GPU, the window or a screenshot file.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub(crate) enum ViewerError {
    /// A flag or its value is wrong; the message says which and what is expected.
    #[error("{0}")]
    Usage(String),
    /// The species editor could not open its species or its project folder.
    #[error("the species editor: {0}")]
    Editor(String),
    /// Building the forest or streaming its cells failed.
    #[error(transparent)]
    Forest(#[from] ForestError),
    /// Loading or applying a painting failed.
    #[error(transparent)]
    Paint(#[from] PaintError),
    /// Making or meshing the terrain failed.
    #[error(transparent)]
    Terrain(#[from] TerrainError),
    /// The world could not be assembled (its ground, species, paint or year).
    #[error(transparent)]
    World(#[from] sylva::world::WorldError),
    /// No graphics adapter was found.
    #[error(
        "no graphics adapter ({0}); without a GPU install Mesa's software drivers (Debian: libvulkan1 mesa-vulkan-drivers, or libegl1 libegl-mesa0 libgl1-mesa-dri with WGPU_BACKEND=gl)"
    )]
    NoAdapter(#[source] wgpu::RequestAdapterError),
    /// The adapter would not open a device.
    #[error("cannot open the graphics device: {0}")]
    Device(#[source] wgpu::RequestDeviceError),
    /// The world's materials do not fit the adapter's uniform buffers.
    #[error(
        "{materials} materials need {bytes} bytes of uniforms; this adapter binds at most {most}"
    )]
    TooManyMaterials {
        /// Materials of the world.
        materials: usize,
        /// Bytes they need.
        bytes: u64,
        /// Bytes the adapter binds.
        most: u64,
    },
    /// Waiting for the GPU failed.
    #[error("waiting for the graphics device: {0}")]
    Poll(#[source] wgpu::PollError),
    /// A rendered frame could not be read back.
    #[error("reading the frame back: {0}")]
    Readback(#[source] wgpu::BufferAsyncError),
    /// A read-back frame's memory could not be reached.
    #[error("reading the frame back: {0}")]
    MappedRange(#[source] wgpu::MapRangeError),
    /// A screenshot could not be written.
    #[error("{}: {source}", path.display())]
    Image {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        #[source]
        source: png::EncodingError,
    },
    /// No window can be opened (no display).
    #[error(
        "cannot open a window ({0}); on a machine without a display, render headless with --screenshot PATH"
    )]
    NoDisplay(#[source] winit::error::EventLoopError),
    /// The adapter found cannot present to the window.
    #[error("the adapter cannot present to this window")]
    CannotPresent,
    /// The graphics device was lost while the window was open.
    #[error("the graphics device was lost")]
    DeviceLost,
    /// The window's surface failed validation.
    #[error("the window surface failed validation")]
    SurfaceInvalid,
    /// The window's event loop failed.
    #[error("event loop: {0}")]
    EventLoop(#[source] winit::error::EventLoopError),
    /// The window could not be created.
    #[error("cannot create a window: {0}")]
    Window(#[source] winit::error::OsError),
    /// The window cannot be drawn into.
    #[error("cannot draw into the window: {0}")]
    Surface(#[source] wgpu::CreateSurfaceError),
}
