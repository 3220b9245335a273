//! The draw list: one instanced draw per group, level and material, then one per impostor
//! card, ordered so that a pass binds each variant's buffers once.

use crate::geometry::MESH_LEVELS;
use crate::world::World;

/// One instanced draw: a group's bark or leaf triangles, over the group's placements that
/// survive culling this frame.
pub(crate) struct Draw {
    pub(crate) variant: usize,
    pub(crate) group: usize,
    pub(crate) indices: (u32, u32),
    pub(crate) bark: bool,
    /// An impostor card, drawn with the impostor pipeline.
    pub(crate) impostor: bool,
}

impl Draw {
    /// Every draw `world` can make: each group's levels (numbered `group * MESH_LEVELS +
    /// level`), then each variant's impostor card (numbered after every group's levels).
    pub(crate) fn all(world: &World) -> Vec<Draw> {
        let mut draws = Vec::new();
        // Impostor cards are drawn like groups numbered after every group's levels.
        let (groups, kinds) = (world.groups.len() * MESH_LEVELS, world.variants.len());
        for (v, p) in world.proxies.iter().enumerate() {
            if !p.leaves.is_empty() {
                draws.push(Draw {
                    variant: kinds + v,
                    group: groups + v,
                    indices: (0, p.leaves.len() as u32),
                    bark: false,
                    impostor: true,
                });
            }
        }
        for (group, g) in world.groups.iter().enumerate() {
            for (level, &(bark, leaves)) in g.levels.iter().enumerate() {
                for (is_bark, span) in [(true, bark), (false, leaves)] {
                    if !span.is_empty() {
                        draws.push(Draw {
                            variant: g.variant,
                            group: group * MESH_LEVELS + level,
                            indices: (span.start, span.end()),
                            bark: is_bark,
                            impostor: false,
                        });
                    }
                }
            }
        }
        // By variant, so a pass binds each variant's buffers once.
        draws.sort_by_key(|d| (d.variant, d.bark));
        draws
    }
}

/// Which draws each slot (group level or impostor) feeds, so a frame visits the draws of
/// the few thousand slots it filled rather than the whole list.
pub(crate) struct DrawIndex {
    /// Where each slot's draws start in `positions`, and one more entry for the end.
    starts: Vec<u32>,
    /// Positions in the draw list, slot by slot, each slot's in the list's order.
    positions: Vec<u32>,
}

impl DrawIndex {
    /// The index of `draws` over `slots` slots.
    pub(crate) fn of(draws: &[Draw], slots: usize) -> DrawIndex {
        let mut starts = vec![0u32; slots + 1];
        for d in draws {
            starts[d.group + 1] += 1;
        }
        for k in 0..slots {
            starts[k + 1] += starts[k];
        }
        let mut next = starts.clone();
        let mut positions = vec![0u32; draws.len()];
        for (position, d) in draws.iter().enumerate() {
            positions[next[d.group] as usize] = position as u32;
            next[d.group] += 1;
        }
        DrawIndex { starts, positions }
    }

    /// The positions in the draw list of slot `slot`'s draws.
    pub(crate) fn of_slot(&self, slot: usize) -> &[u32] {
        match (self.starts.get(slot), self.starts.get(slot + 1)) {
            (Some(&a), Some(&b)) => &self.positions[a as usize..b as usize],
            _ => &[],
        }
    }
}
