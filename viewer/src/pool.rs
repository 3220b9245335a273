//! The placements of the cells drawn, kept on the GPU: each cell's instances are uploaded
//! once, when it is first drawn, into one storage buffer, so that a frame sends the GPU only
//! which of them it draws (an index and a fade each, 8 bytes) rather than the placements
//! themselves (64 bytes each, read again at random from the cells and copied twice).

use std::collections::{HashMap, HashSet};

use crate::cell::Cell;
use crate::geometry::InstanceRaw;

/// Bytes of one placement.
const INSTANCE: u64 = size_of::<InstanceRaw>() as u64;

/// Where each drawn cell's instances sit in the pool: a first-fit allocation of instance
/// slots, with no GPU in it (so it is tested on its own).
#[derive(Debug, Default)]
pub(crate) struct Layout {
    capacity: u32,
    /// The free stretches of slots, as (first, length), in order and never touching.
    free: Vec<(u32, u32)>,
    /// Each cell held, by [`Cell::id`]: where its placements start and how many there are
    /// (its proxies follow them).
    held: HashMap<u64, Held>,
}

/// Where one held cell's instances are.
#[derive(Debug, Clone, Copy)]
struct Held {
    first: u32,
    placements: u32,
    proxies: u32,
}

impl Layout {
    /// An empty layout of `capacity` slots.
    pub(crate) fn with_capacity(capacity: u32) -> Layout {
        Layout {
            capacity,
            free: if capacity > 0 {
                vec![(0, capacity)]
            } else {
                Vec::new()
            },
            held: HashMap::new(),
        }
    }

    /// Where `cell`'s placements and its proxies start in the pool; none for a cell not
    /// held.
    pub(crate) fn base(&self, cell: &Cell) -> Option<[u32; 2]> {
        self.held
            .get(&cell.id)
            .map(|h| [h.first, h.first + h.placements])
    }

    /// Holds exactly `cells`: lets go of the cells held that are not among them, and finds
    /// room for those that are not held yet. Returns the cells placed (their position in
    /// `cells` and their first slot), whose instances must now be uploaded; or, when they
    /// do not fit, the slots all of `cells` need, with nothing held.
    pub(crate) fn hold(&mut self, cells: &[&Cell]) -> Result<Vec<(usize, u32)>, u64> {
        let wanted: HashSet<u64> = cells.iter().map(|c| c.id).collect();
        let gone: Vec<u64> = (self.held.keys())
            .filter(|id| !wanted.contains(id))
            .copied()
            .collect();
        for id in gone {
            if let Some(h) = self.held.remove(&id) {
                self.give(h.first, h.placements + h.proxies);
            }
        }
        let mut placed = Vec::new();
        for (position, cell) in cells.iter().enumerate() {
            if self.held.contains_key(&cell.id) {
                continue;
            }
            let (placements, proxies) = (cell.placements.len(), cell.proxies.len());
            let first = u32::try_from(placements + proxies)
                .ok()
                .and_then(|len| self.take(len));
            let Some(first) = first else {
                let needed = (cells.iter())
                    .map(|c| (c.placements.len() + c.proxies.len()) as u64)
                    .sum();
                *self = Layout::with_capacity(self.capacity);
                return Err(needed);
            };
            self.held.insert(
                cell.id,
                Held {
                    first,
                    placements: placements as u32,
                    proxies: proxies as u32,
                },
            );
            placed.push((position, first));
        }
        Ok(placed)
    }

    /// The first slot of a free stretch of `len` slots, taken; none when no stretch is
    /// long enough. An empty cell takes no room.
    fn take(&mut self, len: u32) -> Option<u32> {
        if len == 0 {
            return Some(0);
        }
        let k = self.free.iter().position(|&(_, l)| l >= len)?;
        let (first, l) = self.free[k];
        if l == len {
            self.free.remove(k);
        } else {
            self.free[k] = (first + len, l - len);
        }
        Some(first)
    }

    /// Gives back `len` slots from `first`, merged with the free stretches beside them.
    fn give(&mut self, first: u32, len: u32) {
        if len == 0 {
            return;
        }
        let k = self.free.partition_point(|&(f, _)| f < first);
        self.free.insert(k, (first, len));
        if k + 1 < self.free.len() && first + len == self.free[k + 1].0 {
            self.free[k].1 += self.free[k + 1].1;
            self.free.remove(k + 1);
        }
        if k > 0 && self.free[k - 1].0 + self.free[k - 1].1 == first {
            self.free[k - 1].1 += self.free[k].1;
            self.free.remove(k);
        }
    }
}

/// The GPU's copy of the drawn cells' instances, laid out by a [`Layout`].
pub(crate) struct Pool {
    pub(crate) layout: Layout,
    buffer: Option<wgpu::Buffer>,
    /// The most slots one storage binding can hold on this device.
    most: u32,
}

impl Pool {
    /// An empty pool, sized to what one storage binding of `device` takes at most.
    pub(crate) fn new(device: &wgpu::Device) -> Pool {
        let limits = device.limits();
        let bytes = (limits.max_storage_buffer_binding_size).min(limits.max_buffer_size);
        Pool {
            layout: Layout::default(),
            buffer: None,
            most: (bytes / INSTANCE).min(u64::from(u32::MAX)) as u32,
        }
    }

    /// The buffer of instances, once some cell is held.
    pub(crate) fn buffer(&self) -> Option<&wgpu::Buffer> {
        self.buffer.as_ref()
    }

    /// Holds `cells` on the GPU, uploading (through `belt`, recorded in `encoder`) those not
    /// held yet, and growing the buffer when they do not fit (everything is then uploaded
    /// again into the new one). False when they cannot all be held: more than one storage
    /// binding can hold.
    pub(crate) fn hold(
        &mut self,
        device: &wgpu::Device,
        (encoder, belt): (&mut wgpu::CommandEncoder, &mut wgpu::util::StagingBelt),
        cells: &[&Cell],
    ) -> bool {
        let placed = match self.layout.hold(cells) {
            Ok(placed) => placed,
            Err(needed) => {
                // Half as much room again as needed, so walking on does not grow it again
                // at once.
                let room = (needed + needed / 2).max(1 << 16).next_power_of_two();
                let room = room.min(u64::from(self.most));
                if needed > room {
                    return false;
                }
                self.buffer = Some(device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("instances of the cells drawn"),
                    size: room * INSTANCE,
                    usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                }));
                self.layout = Layout::with_capacity(room as u32);
                match self.layout.hold(cells) {
                    Ok(placed) => placed,
                    Err(_) => return false,
                }
            }
        };
        let Some(buffer) = &self.buffer else {
            // Nothing held takes room: only empty cells.
            return placed.iter().all(|&(c, _)| cell_len(cells[c]) == 0);
        };
        for (c, first) in placed {
            let cell = cells[c];
            let Some(size) = wgpu::BufferSize::new(cell_len(cells[c]) as u64 * INSTANCE) else {
                continue;
            };
            let mut view = belt.write_buffer(encoder, buffer, u64::from(first) * INSTANCE, size);
            let split = cell.placements.len() * INSTANCE as usize;
            let (mut placements, mut proxies) = view.slice(..).split_at(split);
            placements.copy_from_slice(bytemuck::cast_slice(&cell.placements.instances));
            proxies.copy_from_slice(bytemuck::cast_slice(&cell.proxies.instances));
        }
        true
    }
}

/// Instances in `cell`, placements and proxies.
fn cell_len(cell: &Cell) -> usize {
    cell.placements.len() + cell.proxies.len()
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// Taking and giving back stretches in any order never hands out a slot twice, never
        /// goes past the capacity, and leaves the free stretches in order, apart and whole:
        /// once everything is given back, one stretch of every slot.
        #[test]
        fn stretches_never_overlap_and_merge_when_given_back(
            steps in prop::collection::vec((1u32..40, any::<bool>(), any::<prop::sample::Index>()), 1..80),
        ) {
            let capacity = 256;
            let mut layout = Layout::with_capacity(capacity);
            let mut taken: Vec<(u32, u32)> = Vec::new();
            for (len, give, which) in steps {
                if give && !taken.is_empty() {
                    let (first, len) = taken.swap_remove(which.index(taken.len()));
                    layout.give(first, len);
                } else if let Some(first) = layout.take(len) {
                    prop_assert!(first + len <= capacity);
                    for &(f, l) in &taken {
                        prop_assert!(first + len <= f || f + l <= first, "overlap");
                    }
                    taken.push((first, len));
                } else {
                    // None fits only when no free stretch is long enough.
                    prop_assert!(layout.free.iter().all(|&(_, l)| l < len));
                }
                for pair in layout.free.windows(2) {
                    prop_assert!(pair[0].0 + pair[0].1 < pair[1].0, "{:?}", layout.free);
                }
                let free: u32 = layout.free.iter().map(|f| f.1).sum();
                let used: u32 = taken.iter().map(|t| t.1).sum();
                prop_assert_eq!(free + used, capacity);
            }
            for (first, len) in taken {
                layout.give(first, len);
            }
            prop_assert_eq!(&layout.free, &vec![(0, capacity)]);
        }
    }
}
