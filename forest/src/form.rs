//! The forms a tree is drawn in: alive at one of its generations, or damaged by what
//! happened to it (a broken top, crown dieback, dead standing, a snapped snag, fallen).

/// How one of a forest's trees looks: which cache ([`Variant`](crate::Variant)) draws it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum TreeForm {
    /// Alive and whole, the species' grammar derived for this many generations.
    Live(u32),
    /// Alive, its trunk snapped by a storm at about three fifths of its height: the crown
    /// above is gone, the branches below stay in leaf.
    BrokenTop,
    /// Alive, its crown dying back (disease): three leaves in ten left.
    Dieback,
    /// Dead and standing, every branch bare.
    Dead,
    /// Dead and standing, its trunk split and snapped at two fifths of its height
    /// (lightning, or an old dead tree decaying).
    Snag,
    /// Thrown by a storm: the bare tree lying on the ground along its yaw (the wind's
    /// direction).
    Fallen,
}

impl TreeForm {
    /// The damaged forms, in a fixed order.
    pub const DAMAGED: [TreeForm; 5] = [
        TreeForm::BrokenTop,
        TreeForm::Dieback,
        TreeForm::Dead,
        TreeForm::Snag,
        TreeForm::Fallen,
    ];

    /// A short name, for node names and reports: `live-5`, `broken-top`, `dieback`, `dead`,
    /// `snag`, `fallen`.
    pub fn name(&self) -> String {
        match self {
            TreeForm::Live(g) => format!("live-{g}"),
            TreeForm::BrokenTop => "broken-top".into(),
            TreeForm::Dieback => "dieback".into(),
            TreeForm::Dead => "dead".into(),
            TreeForm::Snag => "snag".into(),
            TreeForm::Fallen => "fallen".into(),
        }
    }

    /// Whether the tree is alive.
    pub fn is_alive(&self) -> bool {
        matches!(
            self,
            TreeForm::Live(_) | TreeForm::BrokenTop | TreeForm::Dieback
        )
    }

    /// Where its trunk breaks, as a share of its height, if it does.
    pub fn break_share(&self) -> Option<f32> {
        match self {
            TreeForm::BrokenTop => Some(0.6),
            TreeForm::Snag => Some(0.4),
            _ => None,
        }
    }

    /// The share of leaf cards it keeps.
    pub fn leaf_keep(&self) -> f32 {
        match self {
            TreeForm::Live(_) | TreeForm::BrokenTop => 1.0,
            TreeForm::Dieback => 0.3,
            TreeForm::Dead | TreeForm::Snag | TreeForm::Fallen => 0.0,
        }
    }
}
