//! One tree of a forest over time, as compactly as the simulation allows.

use crate::form::TreeForm;

/// A tree in the simulation: 32 bytes, all a year needs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stem {
    /// Position (x, z), metres.
    pub position: [f32; 2],
    /// Height of the whole tree, metres (a broken top reaches less: [`Stem::top`]).
    pub height: f32,
    /// The share of its potential growth it made last year (0 to 1): its vigour.
    pub vigour: f32,
    /// Identity: a hash of where and when it germinated, so a tree keeps its identity and
    /// its draws in any run that holds it (tiles included).
    pub key: u64,
    /// Age, years.
    pub age: u16,
    /// Index into the simulation's species.
    pub species: u8,
    /// Its damage and state.
    pub state: State,
    /// Consecutive years it grew at under a tenth of its potential.
    pub suppressed: u8,
    /// Years since it died (dead trees only).
    pub dead_years: u8,
    /// The direction it fell in, turns of a circle (fallen trees only); otherwise unused.
    pub fall: u8,
}

/// What has happened to a tree.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum State {
    /// Alive and whole.
    Live,
    /// Alive, its top snapped by a storm.
    BrokenTop,
    /// Alive and diseased: its crown dying back.
    Dieback,
    /// Dead and standing.
    Dead,
    /// Dead, its trunk split and snapped (lightning, or decay).
    Snag,
    /// Thrown by a storm, lying on the ground.
    Fallen,
}

impl State {
    /// Whether the tree is alive.
    pub fn is_alive(self) -> bool {
        matches!(self, State::Live | State::BrokenTop | State::Dieback)
    }

    /// The damaged form it is drawn in, `None` for a whole living tree (drawn at its age).
    pub fn damaged_form(self) -> Option<TreeForm> {
        match self {
            State::Live => None,
            State::BrokenTop => Some(TreeForm::BrokenTop),
            State::Dieback => Some(TreeForm::Dieback),
            State::Dead => Some(TreeForm::Dead),
            State::Snag => Some(TreeForm::Snag),
            State::Fallen => Some(TreeForm::Fallen),
        }
    }
}

impl Stem {
    /// The height its crown reaches: a broken top or a snag is shorter than the tree was.
    pub fn top(&self) -> f32 {
        match self.state {
            State::BrokenTop => self.height * 0.6,
            State::Snag => self.height * 0.4,
            State::Fallen => 0.0,
            _ => self.height,
        }
    }

    /// The yaw it falls along, radians (fallen trees).
    pub fn fall_yaw(&self) -> f32 {
        f32::from(self.fall) / 256.0 * std::f32::consts::TAU
    }
}

/// Why a tree died.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Cause {
    /// Too little light for too long.
    Suppression,
    /// Old age.
    Age,
    /// Thrown by a storm.
    Storm,
    /// Struck by lightning.
    Lightning,
    /// Killed by disease.
    Disease,
}

impl Cause {
    /// Every cause, in the order statistics list them.
    pub const ALL: [Cause; 5] = [
        Cause::Suppression,
        Cause::Age,
        Cause::Storm,
        Cause::Lightning,
        Cause::Disease,
    ];

    /// Its name in statistics: `suppression`, `age`, `storm`, `lightning`, `disease`.
    pub fn name(self) -> &'static str {
        match self {
            Cause::Suppression => "suppression",
            Cause::Age => "age",
            Cause::Storm => "storm",
            Cause::Lightning => "lightning",
            Cause::Disease => "disease",
        }
    }
}
