//! What the panel and the window say to each other: the panel's tabs, what the panel asks
//! of the window (which holds the world, the painting tool and the guided walk), and what
//! the window tells the panel of those tools each frame.

/// The panel's tabs (`--editor-tab` names them: species, forest, tools).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) enum Tab {
    /// The species, their grammars and the preview.
    #[default]
    Species,
    /// The terrain, density and region.
    Forest,
    /// The painting tool and the guided walk.
    Tools,
}

impl std::str::FromStr for Tab {
    type Err = String;

    fn from_str(s: &str) -> Result<Tab, String> {
        match s {
            "species" => Ok(Tab::Species),
            "forest" => Ok(Tab::Forest),
            "tools" => Ok(Tab::Tools),
            _ => Err("expected species, forest or tools".into()),
        }
    }
}

/// What the panel asks of the window, which holds the world, the painting tool and the
/// guided walk.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Request {
    /// Undo the painting tool's last stroke (the editor's history reached it).
    UndoStroke,
    /// Redo the painting tool's last undone stroke.
    RedoStroke,
    /// Turn the painting tool on or off.
    TogglePainting,
    /// Paint with species `k`: adding it, or turning trees into it.
    PaintSpecies(usize),
    /// The brush's action: add, turn into, or erase.
    PaintAction(PaintAction),
    /// The brush's radius in metres and strength.
    Brush { radius: f32, strength: f32 },
    /// Save the painted masks into the project (its `masks` folder).
    SaveMasks,
    /// Start or stop the guided walk.
    ToggleGuide,
}

/// What the brush does.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum PaintAction {
    Add,
    Turn,
    Erase,
}

/// What the window tells the panel of the tools it holds, each frame.
#[derive(Debug, Clone, Default)]
pub(crate) struct ToolsState {
    /// The painting tool's status line, if it is on.
    pub(crate) painting: Option<String>,
    /// The brush: species, action, radius and strength.
    pub(crate) brush: Option<(usize, PaintAction, f32, f32)>,
    /// The guided walk's summary, if it is on.
    pub(crate) guide: Option<String>,
    /// The forest's build: what the last rebuild did, or that one is under way.
    pub(crate) forest: String,
}
