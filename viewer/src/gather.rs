//! Gathering a frame's placements: for each sight (the camera, the sun), the placements of
//! the cells drawn that it sees, level by level, in one instance buffer with a range per
//! instanced draw.

use bytemuck::Zeroable;
use rayon::prelude::*;
use sylva::terrain::glam::Vec3;

use crate::cell::{Cell, Level, RunBounds};
use crate::cull::{
    Cover, Levels, LodView, MAX_SIGHTS, Sight, farthest_distance, nearest_distance, run_covers,
};
use crate::scene::Scene;
use crate::world::{InstanceRaw, MESH_LEVELS, World, world_sphere};

/// What a frame's culling gathers for each sight, kept from frame to frame so that its
/// buffers are reused rather than allocated (and their pages faulted in) every frame.
#[derive(Default)]
pub(crate) struct Gathered {
    /// Every sight's placements, sight by sight, and within one slot by slot.
    pub(crate) visible: Vec<InstanceRaw>,
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
    pub(crate) fn gather(&mut self, scene: &Scene, sights: &[Sight], lod: Option<LodView>) {
        self.gather_cells(&scene.world, &drawn(scene), sights, lod);
    }

    /// [`Gathered::gather`] over the cells `drawn` of `world`.
    fn gather_cells(
        &mut self,
        world: &World,
        drawn: &[(Level, &Cell)],
        sights: &[Sight],
        lod: Option<LodView>,
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
        // Every element is written, so only a longer tail is zeroed first.
        self.visible.truncate(first as usize);
        self.visible.resize(first as usize, InstanceRaw::zeroed());
        (self.visible.par_iter_mut().zip(&self.source)).for_each(|(out, &(c, j))| {
            *out = tagged[c as usize][j as usize].instance(cells[c as usize].1);
        });
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

/// Appends to `out` the placements of one cell that `sights` see.
fn gather_cell(
    world: &World,
    (level, cell): (Level, &Cell),
    sights: &[Sight],
    lod: Option<LodView>,
    out: &mut Vec<Seen>,
) {
    let slots = world.slots();
    let tag = |sight: usize, slot: usize| (sight * slots + slot) as u32;
    let impostors = world.groups.len() * MESH_LEVELS;
    for (k, bounds, first, run) in cell.placements.occupied() {
        let group = &world.groups[k];
        let errors = &world.lods[group.variant].errors;
        if let Some(lod) = lod
            && nearest_distance(lod.eye, bounds.bases) >= lod.reach(errors).0
        {
            continue;
        }
        let Some(covers) = run_covers(sights, bounds) else {
            continue;
        };
        let piece = Piece {
            bounds,
            first,
            run,
            sphere: group.sphere,
            tag: 0,
        };
        // Without levels of detail, each placement as it is, at full detail.
        let (levels, constant) = match lod {
            Some(lod) => (Some((lod, errors)), lod.level_across(bounds.bases, errors)),
            None => (None, Some(UNFADED[0])),
        };
        let slot = |s, level| (level < MESH_LEVELS).then(|| tag(s, k * MESH_LEVELS + level));
        gather_piece(piece, (sights, covers), levels, constant, slot, out);
    }
    // Proxies: a coarse cell draws every one as it is; a fine cell, with levels of detail,
    // those of its trees far enough to be drawn as impostors (none without).
    let far = match (level, lod) {
        (Level::Coarse, _) => None,
        (Level::Fine, Some(lod)) => Some(lod),
        (Level::Fine, None) => return,
    };
    for (k, bounds, first, run) in cell.proxies.occupied() {
        let errors = &world.lods[k].errors;
        if let Some(lod) = far
            && farthest_distance(lod.eye, bounds.bases) < lod.reach(errors).1
        {
            continue;
        }
        let Some(covers) = run_covers(sights, bounds) else {
            continue;
        };
        let piece = Piece {
            bounds,
            first,
            run,
            sphere: world.proxies[k].sphere,
            tag: PROXY,
        };
        let (levels, constant) = match far {
            Some(lod) => (Some((lod, errors)), lod.level_across(bounds.bases, errors)),
            None => (None, Some(UNFADED[MESH_LEVELS])),
        };
        let slot = |s, level| (level == MESH_LEVELS).then(|| tag(s, impostors + k));
        gather_piece(piece, (sights, covers), levels, constant, slot, out);
    }
}

/// Each level (the impostor last) alone and unfaded: the placements of a cell drawn
/// without levels of detail, and the proxies of a coarse cell. (Every instance's own fade
/// is 0; the fade a frame gives it replaces it.)
const UNFADED: [Levels; MESH_LEVELS + 1] = {
    let mut all = [[None; 2]; MESH_LEVELS + 1];
    let mut level = 0;
    while level <= MESH_LEVELS {
        all[level] = [Some((level, 0.0)), None];
        level += 1;
    }
    all
};

/// A piece of a cell's run being gathered.
struct Piece<'a> {
    bounds: &'a RunBounds,
    /// Where it starts in its cell's runs.
    first: usize,
    run: &'a [InstanceRaw],
    /// Its instances' bounding sphere in their own space.
    sphere: (Vec3, f32),
    /// The bit its [`Seen::index`]es carry: [`PROXY`] or none.
    tag: u32,
}

/// Appends to `out` what the sights see of one piece, with the `covers` of its bounds:
/// each instance at the levels its base asks for of a variant with these errors, or the
/// `constant` levels every instance has (known from the piece's bounds, or the levels
/// being off), filed in `slot(sight, level)` (none: not drawn in this pass). Instances
/// are tested only where the piece's bounds leave it open: a piece wholly seen by every
/// sight that may see it, at one level, is taken whole, in the same order.
fn gather_piece(
    piece: Piece<'_>,
    (sights, covers): (&[Sight], [Cover; MAX_SIGHTS]),
    levels: Option<(LodView, &[f32; MESH_LEVELS])>,
    constant: Option<Levels>,
    slot: impl Fn(usize, usize) -> Option<u32>,
    out: &mut Vec<Seen>,
) {
    let open = |s: usize| covers[s] != Cover::Out;
    let whole: [bool; MAX_SIGHTS] =
        std::array::from_fn(|s| s < sights.len() && sights[s].sees_whole(covers[s], piece.bounds));
    let all_whole = (0..sights.len()).all(|s| !open(s) || whole[s]);
    let index = |j: usize| (piece.first + j) as u32 | piece.tag;
    let levels_of = |i: &InstanceRaw| match (constant, levels) {
        (Some(constant), _) => constant,
        (None, Some((lod, errors))) => lod.levels(i.base(), errors),
        (None, None) => UNFADED[0],
    };
    if let (true, Some(levels)) = (all_whole, constant) {
        // Slot by slot rather than instance by instance: each slot still receives the
        // piece's instances in order, which is all the counting sort keeps.
        for s in (0..sights.len()).filter(|&s| open(s)) {
            for (level, fade) in levels.into_iter().flatten() {
                if let Some(slot) = slot(s, level) {
                    let seen = (0..piece.run.len()).map(|j| Seen {
                        slot,
                        index: index(j),
                        fade,
                    });
                    out.extend(seen);
                }
            }
        }
        return;
    }
    for (j, i) in piece.run.iter().enumerate() {
        let sphere = (!all_whole).then(|| world_sphere(i, piece.sphere));
        let seen: [bool; MAX_SIGHTS] = std::array::from_fn(|s| {
            open(s) && (whole[s] || sphere.is_some_and(|sphere| sights[s].sees(covers[s], sphere)))
        });
        // Most instances of a piece at the edge of a view are out of it: their levels are
        // not worked out.
        if !seen.contains(&true) {
            continue;
        }
        let levels = levels_of(i);
        for s in (0..sights.len()).filter(|&s| seen[s]) {
            for (level, fade) in levels.into_iter().flatten() {
                if let Some(slot) = slot(s, level) {
                    out.push(Seen {
                        slot,
                        index: index(j),
                        fade,
                    });
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cull::Volume;
    use crate::shadow::{SHADOW_TEXEL, light_view_proj};
    use crate::world::{SceneOptions, lod_chain};
    use proptest::prelude::*;
    use std::sync::{Mutex, OnceLock, PoisonError};
    use sylva::terrain::glam::Vec3;
    use sylva::terrain::glam::camera::rh::{proj::directx, view};

    /// Runs `f` on a small world with its cells streamed around its middle, built once for
    /// every test (a scene is not shared between threads, so it sits behind a lock).
    fn with_scene<R>(f: impl FnOnce(&Scene) -> R) -> R {
        static SCENE: OnceLock<Mutex<Scene>> = OnceLock::new();
        let scene = SCENE.get_or_init(|| {
            let mut scene = Scene::build(SceneOptions::small(6, 300.0)).expect("scene builds");
            let middle = Vec3::new(150.0, 40.0, 150.0);
            scene.stream(middle, false, true).expect("cells stream");
            Mutex::new(scene)
        });
        f(&scene.lock().unwrap_or_else(PoisonError::into_inner))
    }

    /// The sights of a frame seen from `eye` looking along `forward`: the camera's, and the
    /// sun's as the renderer makes it.
    fn sights(eye: Vec3, forward: Vec3) -> Vec<Sight> {
        let proj = directx::perspective(55f32.to_radians(), 16.0 / 9.0, 0.2, 2000.0);
        let camera = proj * view::look_to_mat4(eye, forward, Vec3::Y);
        let sun = Vec3::new(0.45, 0.75, 0.35).normalize();
        vec![
            Sight {
                volume: Volume::of(&camera),
                eye,
                pixels_per_radian: 720.0 / 55f32.to_radians(),
            },
            Sight {
                volume: Volume::of(&light_view_proj(eye, forward, sun)),
                eye: eye + sun * 1e4,
                pixels_per_radian: 1e4 / SHADOW_TEXEL,
            },
        ]
    }

    fn lod_view(eye: Vec3) -> LodView {
        let chain = lod_chain();
        LodView {
            eye,
            pixels_per_radian: 720.0 / 55f32.to_radians(),
            pixel_error: chain.pixel_error,
            fade: chain.fade,
        }
    }

    /// Each slot's placements as bytes, per sight: what the GPU is given.
    type Slots = Vec<Vec<Vec<u8>>>;

    /// The placements each sight sees, slot by slot, found one placement at a time: every
    /// group of every fine cell, then the impostors of fine and coarse cells, with no
    /// placement passed over unless it is tested.
    fn reference(scene: &Scene, sights: &[Sight], lod: Option<LodView>) -> Slots {
        let world = &scene.world;
        let with_fade = |i: &InstanceRaw, fade: f32| {
            let mut out = *i;
            out.tint[3] = fade;
            out
        };
        let seen = |sight: &Sight, i: &InstanceRaw, sphere| {
            let (centre, radius) = world_sphere(i, sphere);
            sight.volume.touches(centre, radius)
                && radius >= sight.min_ratio() * centre.distance(sight.eye)
        };
        let mut out = Vec::new();
        for sight in sights {
            let mut slots = vec![Vec::new(); world.slots()];
            let cells = |level| scene.cells.drawn().filter(move |(k, _)| k.level == level);
            for (k, group) in world.groups.iter().enumerate() {
                let errors = &world.lods[group.variant].errors;
                for (_, cell) in cells(Level::Fine) {
                    for i in cell.placements.run(k) {
                        if !seen(sight, i, group.sphere) {
                            continue;
                        }
                        let Some(lod) = lod else {
                            slots[k * MESH_LEVELS].push(*i);
                            continue;
                        };
                        for (level, fade) in lod.levels(i.base(), errors).into_iter().flatten() {
                            if level < MESH_LEVELS {
                                slots[k * MESH_LEVELS + level].push(with_fade(i, fade));
                            }
                        }
                    }
                }
            }
            for (k, proxy) in world.proxies.iter().enumerate() {
                let slot = &mut slots[world.groups.len() * MESH_LEVELS + k];
                if let Some(lod) = lod {
                    for (_, cell) in cells(Level::Fine) {
                        for i in cell.proxies.run(k) {
                            let levels = lod.levels(i.base(), &world.lods[k].errors);
                            for (level, fade) in levels.into_iter().flatten() {
                                if level == MESH_LEVELS && seen(sight, i, proxy.sphere) {
                                    slot.push(with_fade(i, fade));
                                }
                            }
                        }
                    }
                }
                for (_, cell) in cells(Level::Coarse) {
                    slot.extend(
                        cell.proxies
                            .run(k)
                            .iter()
                            .filter(|i| seen(sight, i, proxy.sphere)),
                    );
                }
            }
            out.push(
                slots
                    .iter()
                    .map(|s| bytemuck::cast_slice(s).to_vec())
                    .collect(),
            );
        }
        out
    }

    /// What `gathered` holds for each sight, in the reference's shape.
    fn slots_of(gathered: &Gathered, scene: &Scene, sights: usize) -> Slots {
        (0..sights)
            .map(|s| {
                let mut slots = vec![Vec::new(); scene.world.slots()];
                for r in gathered.ranges(s) {
                    let placements =
                        &gathered.visible[r.first as usize..(r.first + r.count) as usize];
                    slots[r.slot as usize] = bytemuck::cast_slice(placements).to_vec();
                }
                slots
            })
            .collect()
    }

    fn gather_with(
        threads: usize,
        gathered: &mut Gathered,
        sights: &[Sight],
        lod: Option<LodView>,
    ) {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a pool");
        with_scene(|scene| {
            let (world, drawn): (&World, _) = (&scene.world, drawn(scene));
            pool.install(|| gathered.gather_cells(world, &drawn, sights, lod));
        });
    }

    #[test]
    fn a_frame_gathers_the_same_placements_on_one_thread_as_on_four() {
        let eye = Vec3::new(120.0, 45.0, 130.0);
        let sights = sights(eye, Vec3::new(1.0, -0.2, 0.6).normalize());
        let (mut one, mut four) = (Gathered::default(), Gathered::default());
        gather_with(1, &mut one, &sights, Some(lod_view(eye)));
        gather_with(4, &mut four, &sights, Some(lod_view(eye)));
        assert!(!one.visible.is_empty(), "the view sees some of the forest");
        with_scene(|scene| assert_eq!(slots_of(&one, scene, 2), slots_of(&four, scene, 2)));
        assert_eq!(
            bytemuck::cast_slice::<_, u8>(&one.visible),
            bytemuck::cast_slice::<_, u8>(&four.visible)
        );
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

        /// Passing over whole runs and cells, and gathering cells on every core, give the
        /// placements a test of every placement gives, in the same order, from any view,
        /// with and without levels of detail; and a gathering that reuses the last frame's
        /// buffers gives the same as a fresh one.
        #[test]
        fn gathering_matches_a_placement_by_placement_reference(
            x in 0.0f32..300.0,
            z in 0.0f32..300.0,
            height in 2.0f32..120.0,
            yaw in 0.0f32..std::f32::consts::TAU,
            pitch in -1.2f32..0.3,
            lod in any::<bool>(),
        ) {
            // One gathering kept across cases, as the renderer keeps it across frames.
            static KEPT: Mutex<Option<Gathered>> = Mutex::new(None);
            let eye = Vec3::new(x, height, z);
            let forward = Vec3::new(yaw.cos() * pitch.cos(), pitch.sin(), yaw.sin() * pitch.cos());
            let sights = sights(eye, forward);
            let lod = lod.then(|| lod_view(eye));
            let mut kept = KEPT.lock().unwrap_or_else(PoisonError::into_inner);
            let gathered = kept.get_or_insert_with(Gathered::default);
            let (kept, expected, fresh) = with_scene(|scene| {
                gathered.gather(scene, &sights, lod);
                let mut fresh = Gathered::default();
                fresh.gather(scene, &sights[..1], lod);
                (
                    slots_of(gathered, scene, 2),
                    reference(scene, &sights, lod),
                    slots_of(&fresh, scene, 1),
                )
            });
            prop_assert_eq!(&kept, &expected);
            prop_assert_eq!(&fresh[..], &expected[..1]);
        }
    }
}
