//! A year of a forest over time: its trees sorted into buckets, so that any rectangle's are
//! found at once.

use std::collections::BTreeMap;

use super::Succession;
use super::stem::State;
use crate::density::Rect;

/// Side of the buckets a snapshot sorts its trees into, metres, so a block finds its own.
const BUCKET: f32 = 32.0;

/// One tree of a snapshot.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SnapshotTree {
    /// Position (x, z).
    pub position: [f32; 2],
    /// Index of its species.
    pub species: u8,
    /// What has happened to it.
    pub state: State,
    /// Height of the whole tree, metres (a broken one was this tall).
    pub height: f32,
    /// Its identity, from which its yaw and crown are drawn.
    pub key: u64,
    /// The direction it fell, turns of a circle over 256 (fallen trees).
    pub fall: u8,
}

/// The trees of a [`Succession`]'s region in one year, sorted into buckets so that any
/// rectangle's trees are found at once. Hand it to a builder with
/// [`ForestBuilder::with_snapshot`](crate::ForestBuilder::with_snapshot) and every output (GLB, USD, tiles, the viewer) draws it.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Snapshot {
    /// The year.
    pub year: u32,
    /// How many species the forest it was taken of has.
    pub species: usize,
    buckets: BTreeMap<(i64, i64), Vec<SnapshotTree>>,
    len: usize,
}

impl Snapshot {
    /// Trees in the snapshot.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether it holds no tree.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The trees whose positions lie in `rect`, bucket by bucket (rows of 32 m, then
    /// columns), each bucket's in the order of their keys.
    pub fn trees_in(&self, rect: Rect) -> impl Iterator<Item = &SnapshotTree> + '_ {
        let lo = (
            (rect.min.x / BUCKET).floor() as i64,
            (rect.min.y / BUCKET).floor() as i64,
        );
        let hi = (
            (rect.max.x / BUCKET).floor() as i64,
            (rect.max.y / BUCKET).floor() as i64,
        );
        (lo.1..=hi.1)
            .flat_map(move |j| self.buckets.range((j, lo.0)..=(j, hi.0)))
            .flat_map(|(_, trees)| trees.iter())
            .filter(move |t| rect.contains(t.position.into()))
    }

    /// Every tree.
    pub fn trees(&self) -> impl Iterator<Item = &SnapshotTree> + '_ {
        self.buckets.values().flatten()
    }
}

impl Succession {
    /// The trees of the region as they stand this year (the halo's left out).
    pub fn snapshot(&self) -> Snapshot {
        let mut buckets: BTreeMap<(i64, i64), Vec<SnapshotTree>> = BTreeMap::new();
        let mut len = 0;
        for s in self
            .stems
            .iter()
            .filter(|s| self.region.contains(s.position.into()))
        {
            let at = (
                (s.position[0] / BUCKET).floor() as i64,
                (s.position[1] / BUCKET).floor() as i64,
            );
            buckets.entry((at.1, at.0)).or_default().push(SnapshotTree {
                position: s.position,
                species: s.species,
                state: s.state,
                height: s.height,
                key: s.key,
                fall: s.fall,
            });
            len += 1;
        }
        for trees in buckets.values_mut() {
            trees.sort_unstable_by_key(|t| t.key);
        }
        Snapshot {
            year: self.year,
            species: self.species.len(),
            buckets,
            len,
        }
    }
}
