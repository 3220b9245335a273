//! Gathering a frame's placements: for each sight (the camera, the sun), the placements of
//! the cells drawn that it sees, level by level, in one instance buffer with a range per
//! instanced draw.

mod pass;

use bytemuck::Zeroable;
use rayon::prelude::*;

use crate::cell::{Cell, Level};
use crate::cull::{Cover, LodView, MAX_SIGHTS, Sight};
use crate::geometry::InstanceRaw;
use crate::pool::Layout;
use crate::scene::Scene;
use crate::world::World;
use pass::gather_cell;

/// What a frame's culling gathers for each sight, kept from frame to frame so that its
/// buffers are reused rather than allocated (and their pages faulted in) every frame.
#[derive(Default)]
pub(crate) struct Gathered {
    /// Every sight's placements, sight by sight, and within one slot by slot; empty when
    /// they are given as `picks`.
    pub(crate) visible: Vec<InstanceRaw>,
    /// The same, as picks from the GPU's [`crate::pool::Pool`]: each placement's slot there and its
    /// fade's bits; empty when some cell gathered is not in the pool.
    pub(crate) picks: Vec<[u32; 2]>,
    /// The slots filled, in order (sight by sight).
    ranges: Vec<Range>,
    /// Where each sight's slots start in `ranges`.
    split: [usize; MAX_SIGHTS],
    /// Slots per sight: every group's levels, then every variant's impostors.
    slots: usize,
    /// Per slot of every sight, the counting sort's count and then its cursor; all zero
    /// between frames.
    cursor: Vec<u32>,
    /// The slots filled this frame.
    filled: Vec<u32>,
    /// For each placement of `visible`, its cell and its place in the cell's seen list.
    source: Vec<(u32, u32)>,
    /// Each cell's placements seen, tagged with their sight's slot.
    per_cell: Vec<Vec<Seen>>,
}

impl Gathered {
    /// Gathers, for each sight in turn, the placements it sees of every group in the fine
    /// cells drawn, level by level, then the impostors of every variant: placements whose
    /// bounding spheres touch its volume and span at least [`crate::cull::MIN_PIXELS`]. With `lod`, each
    /// tree is drawn at the level its distance asks for, and at the impostor in coarse
    /// cells; without it, every tree of a fine cell at full detail. At most
    /// [`MAX_SIGHTS`] sights are gathered.
    ///
    /// The cells are gathered on every core, and every sight in one pass over a run's
    /// placements, so each placement is read and its level chosen once; runs that no sight
    /// can see, or whose trees are all past their meshes' reach, are passed over whole. The
    /// order out is the cells' order whatever the thread count.
    ///
    /// With `pool` holding every cell gathered, the placements come out as `picks` from it;
    /// otherwise as `visible`, copied.
    pub(crate) fn gather(
        &mut self,
        scene: &Scene,
        (sights, lod): (&[Sight], Option<LodView>),
        pool: Option<&Layout>,
    ) {
        self.gather_cells(&scene.world, &drawn(scene), (sights, lod), pool);
    }

    /// [`Gathered::gather`] over the cells `drawn` of `world`.
    fn gather_cells(
        &mut self,
        world: &World,
        drawn: &[(Level, &Cell)],
        (sights, lod): (&[Sight], Option<LodView>),
        pool: Option<&Layout>,
    ) {
        let sights = &sights[..sights.len().min(MAX_SIGHTS)];
        let slots = world.slots();
        self.slots = slots;
        // Fine cells first, then coarse ones; cells no sight touches are skipped before
        // their runs are looked at.
        let mut cells = Vec::new();
        for wanted in [Level::Fine, Level::Coarse] {
            for &(level, cell) in drawn {
                let touched = sights.iter().any(|s| s.cover(cell.sphere) != Cover::Out);
                if level == wanted && touched {
                    cells.push((level, cell));
                }
            }
        }
        self.per_cell.resize_with(cells.len(), Vec::new);
        (cells.par_iter().zip(&mut self.per_cell)).for_each(|(&(level, cell), out)| {
            out.clear();
            gather_cell(world, (level, cell), sights, lod, out);
        });
        // A counting sort by slot, stable, so each slot keeps the cells' order. Of the
        // world's hundreds of thousands of slots a frame fills a few thousand: only those
        // are visited, and `cursor` is left all zero for the next frame.
        let all = sights.len() * slots;
        if self.cursor.len() != all {
            self.cursor = vec![0; all];
        }
        let tagged = &self.per_cell[..cells.len()];
        self.filled.clear();
        for seen in tagged.iter().flatten() {
            let count = &mut self.cursor[seen.slot as usize];
            if *count == 0 {
                self.filled.push(seen.slot);
            }
            *count += 1;
        }
        self.filled.sort_unstable();
        self.ranges.clear();
        let mut first = 0;
        for &slot in &self.filled {
            let count = std::mem::replace(&mut self.cursor[slot as usize], first);
            self.ranges.push(Range { slot, first, count });
            first += count;
        }
        self.split = [self.ranges.len(); MAX_SIGHTS];
        for (s, split) in self.split.iter_mut().enumerate() {
            *split = (self.ranges).partition_point(|r| (r.slot as usize) < s * slots);
        }
        // Where each placement goes, worked out in order (cheap: the seen records are
        // small); then the placements themselves, scattered about the cells, are read on
        // every core.
        self.source.clear();
        self.source.resize(first as usize, (0, 0));
        for (c, seen) in tagged.iter().enumerate() {
            for (j, seen) in seen.iter().enumerate() {
                let next = &mut self.cursor[seen.slot as usize];
                self.source[*next as usize] = (c as u32, j as u32);
                *next += 1;
            }
        }
        // With every cell's instances on the GPU, only which of them each slot draws.
        let bases: Option<Vec<[u32; 2]>> =
            pool.and_then(|pool| cells.iter().map(|(_, cell)| pool.base(cell)).collect());
        let count = first as usize;
        if let Some(bases) = bases {
            self.visible.clear();
            self.picks.resize(count, [0; 2]);
            (self.picks.par_iter_mut().zip(&self.source)).for_each(|(out, &(c, j))| {
                *out = tagged[c as usize][j as usize].pick(bases[c as usize]);
            });
        } else {
            self.picks.clear();
            // Every element is written, so only a longer tail is zeroed first.
            self.visible.truncate(count);
            self.visible.resize(count, InstanceRaw::zeroed());
            (self.visible.par_iter_mut().zip(&self.source)).for_each(|(out, &(c, j))| {
                *out = tagged[c as usize][j as usize].instance(cells[c as usize].1);
            });
        }
        for &slot in &self.filled {
            self.cursor[slot as usize] = 0;
        }
    }

    /// The slots sight `sight` filled, in order of slot: group `k`'s level `l` is slot
    /// `k * MESH_LEVELS + l`, then each variant's impostors; empty for a sight not
    /// gathered.
    pub(crate) fn ranges(&self, sight: usize) -> impl Iterator<Item = Range> + '_ {
        let from = self.split.get(sight).copied().unwrap_or(self.ranges.len());
        let to = self
            .split
            .get(sight + 1)
            .copied()
            .unwrap_or(self.ranges.len());
        let offset = (sight * self.slots) as u32;
        self.ranges[from..to.max(from)].iter().map(move |r| Range {
            slot: r.slot - offset,
            ..*r
        })
    }
}

/// The cells a scene draws, with their levels, in its order.
fn drawn(scene: &Scene) -> Vec<(Level, &Cell)> {
    (scene.cells.drawn()).map(|(k, c)| (k.level, c)).collect()
}

/// One slot's placements in [`Gathered::visible`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Range {
    pub(crate) slot: u32,
    pub(crate) first: u32,
    pub(crate) count: u32,
}

/// One placement a sight sees: its slot (of every sight's, see [`Gathered::ranges`]), where
/// it is in its cell, and its fade. Under a fifth of the placement's own bytes, so the cells'
/// pass writes little and the sort moves little.
#[derive(Debug, Clone, Copy)]
struct Seen {
    slot: u32,
    /// Its index in the cell's placements, or with [`PROXY`] set in its proxies.
    index: u32,
    fade: f32,
}

/// The bit of [`Seen::index`] that says the placement is a proxy.
const PROXY: u32 = 1 << 31;

impl Seen {
    /// The placement as a pick from the pool, where its cell's placements and proxies start
    /// at `bases`.
    fn pick(&self, bases: [u32; 2]) -> [u32; 2] {
        let base = bases[usize::from(self.index & PROXY != 0)];
        [base + (self.index & !PROXY), self.fade.to_bits()]
    }

    /// The placement as the GPU draws it.
    fn instance(&self, cell: &Cell) -> InstanceRaw {
        let runs = if self.index & PROXY != 0 {
            &cell.proxies
        } else {
            &cell.placements
        };
        let mut out = runs.instances[(self.index & !PROXY) as usize];
        out.tint[3] = self.fade;
        out
    }
}

#[cfg(test)]
mod tests;
