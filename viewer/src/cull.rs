//! Culling on the CPU: each placement's bounding sphere against the planes of a view volume
//! (the camera's frustum, or the sun's box for the shadow map), so that a frame draws the
//! trees in view rather than the whole forest.

use bytemuck::Zeroable;
use rayon::prelude::*;
use sylva::terrain::glam::{Mat4, Vec3, Vec4};

use crate::cell::{Cell, Level, RunBounds};
use crate::scene::Scene;
use crate::world::{InstanceRaw, MESH_LEVELS, World, world_sphere};

/// A convex view volume as inward-facing planes `n . p + d >= 0`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Volume {
    planes: [Vec4; 6],
}

impl Volume {
    /// The volume a view-projection matrix sees, with wgpu's clip space (depth 0 to 1):
    /// the Gribb-Hartmann planes, normalised so distances are in world units.
    pub(crate) fn of(view_proj: &Mat4) -> Volume {
        let m = view_proj.transpose();
        let (r0, r1, r2, r3) = (m.x_axis, m.y_axis, m.z_axis, m.w_axis);
        let planes = [r3 + r0, r3 - r0, r3 + r1, r3 - r1, r2, r3 - r2].map(|p| {
            let length = p.truncate().length();
            if length > 0.0 { p / length } else { p }
        });
        Volume { planes }
    }

    /// Whether any part of the sphere may be inside.
    pub(crate) fn touches(&self, centre: Vec3, radius: f32) -> bool {
        self.planes
            .iter()
            .all(|p| p.truncate().dot(centre) + p.w >= -radius)
    }

    /// Whether the whole sphere is inside.
    pub(crate) fn holds(&self, centre: Vec3, radius: f32) -> bool {
        self.planes
            .iter()
            .all(|p| p.truncate().dot(centre) + p.w >= radius)
    }
}

/// Placements smaller on screen than this many pixels across are not drawn: far twigs and
/// seedlings that fog would hide anyway.
const MIN_PIXELS: f32 = 2.0;

/// Which level of detail each tree is drawn at: seen from `eye` by a screen of
/// `pixels_per_radian`, allowing `pixel_error` pixels of error; levels cross-fade (dithered)
/// over `fade` of each switch distance.
#[derive(Debug, Clone, Copy)]
pub(crate) struct LodView {
    pub(crate) eye: Vec3,
    pub(crate) pixels_per_radian: f32,
    pub(crate) pixel_error: f32,
    pub(crate) fade: f32,
}

impl LodView {
    /// The levels a tree at `base` of a variant with `errors` is drawn at: one, or two
    /// fading into each other, as (level, fade) with the fade in the shader's encoding (0:
    /// whole; `f > 0`: fading out, drawn where the dither is at least `f`; `-f`: fading in,
    /// drawn where it is below `f`). Level `MESH_LEVELS` is the impostor.
    fn levels(&self, base: Vec3, errors: &[f32; MESH_LEVELS]) -> [Option<(usize, f32)>; 2] {
        let d = base.distance(self.eye);
        let scale = self.pixels_per_radian / self.pixel_error.max(1e-3);
        let mut level = 0;
        for (k, &e) in errors.iter().enumerate() {
            let from = e * scale;
            if d < from {
                break;
            }
            level = k + 1;
            let band = from * self.fade;
            if d < from + band && band > 0.0 {
                let f = ((d - from) / band).clamp(1e-3, 1.0);
                return [Some((k, f)), Some((k + 1, -f))];
            }
        }
        [Some((level, 0.0)), None]
    }
}

/// One view to gather placements for: its volume, and the eye and pixels per radian that
/// decide which placements are too small on screen to draw.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Sight {
    pub(crate) volume: Volume,
    pub(crate) eye: Vec3,
    pub(crate) pixels_per_radian: f32,
}

/// How much of a bounding sphere a sight's volume holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Cover {
    Out,
    Partly,
    /// Wholly inside: what it bounds needs no test against the planes.
    Inside,
}

impl Sight {
    fn cover(&self, (centre, radius): (Vec3, f32)) -> Cover {
        if radius < 0.0 || !self.volume.touches(centre, radius) {
            Cover::Out
        } else if self.volume.holds(centre, radius) {
            Cover::Inside
        } else {
            Cover::Partly
        }
    }

    /// The smallest ratio of radius to distance that spans [`MIN_PIXELS`]: a sphere of
    /// radius r at distance d spans about 2 r / d radians.
    fn min_ratio(&self) -> f32 {
        0.5 * MIN_PIXELS / self.pixels_per_radian.max(1e-6)
    }

    /// How much of a run this sight may see: none when its box is out of the volume, or
    /// when its largest instance is too small at the box's nearest point.
    fn cover_run(&self, run: &RunBounds) -> Cover {
        let nearest = nearest_distance(self.eye, run.spheres);
        if run.radius < self.min_ratio() * nearest {
            return Cover::Out;
        }
        self.cover(run.sphere())
    }

    /// Whether a placement's world sphere is seen: in the volume (unless its run is wholly
    /// inside) and at least [`MIN_PIXELS`] across.
    fn sees(&self, cover: Cover, (centre, radius): (Vec3, f32)) -> bool {
        (cover == Cover::Inside || self.volume.touches(centre, radius))
            && radius >= self.min_ratio() * centre.distance(self.eye)
    }
}

/// Distance from `p` to the nearest point of the box `(lo, hi)`.
fn nearest_distance(p: Vec3, (lo, hi): (Vec3, Vec3)) -> f32 {
    p.distance(p.clamp(lo, hi))
}

/// Distance from `p` to the farthest point of the box `(lo, hi)`.
fn farthest_distance(p: Vec3, (lo, hi): (Vec3, Vec3)) -> f32 {
    (p - lo).abs().max((p - hi).abs()).length()
}

impl LodView {
    /// The distances between which a tree of a variant with `errors` may be drawn at
    /// some mesh level (nearer than the first) or as the impostor (beyond the second),
    /// fades included: bounds for passing over a run whole.
    fn reach(&self, errors: &[f32; MESH_LEVELS]) -> (f32, f32) {
        let scale = self.pixels_per_radian / self.pixel_error.max(1e-3);
        let farthest = errors.iter().fold(0.0f32, |m, &e| m.max(e * scale));
        // A thousandth to spare either way: `levels` sums a switch distance and its fade
        // band, which may round a little beyond their product.
        (
            farthest * (1.0 + self.fade.max(0.0)) * 1.001,
            farthest * 0.999,
        )
    }
}

/// Which sights may see each instance of a run, or `None` when none can.
fn run_covers(sights: &[Sight], run: &RunBounds) -> Option<[Cover; 2]> {
    let mut covers = [Cover::Out; 2];
    for (cover, sight) in covers.iter_mut().zip(sights) {
        *cover = sight.cover_run(run);
    }
    covers.iter().any(|&c| c != Cover::Out).then_some(covers)
}

/// The most sights [`Gathered::gather`] gathers for in one pass: the camera and the sun.
pub(crate) const MAX_SIGHTS: usize = 2;

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
    /// bounding spheres touch its volume and span at least [`MIN_PIXELS`]. With `lod`, each
    /// tree is drawn at the level its distance asks for, and at the impostor in coarse
    /// cells; without it, every tree of a fine cell at full detail. At most
    /// [`MAX_SIGHTS`] sights are gathered.
    ///
    /// The cells are gathered on every core, and every sight in one pass over a run's
    /// placements, so each placement is read and its level chosen once; runs that no sight
    /// can see, or whose trees are all past their meshes' reach, are passed over whole. The
    /// order out is the cells' order whatever the thread count.
    pub(crate) fn gather(&mut self, scene: &Scene, sights: &[Sight], lod: Option<LodView>) {
        let drawn: Vec<(Level, &Cell)> = (scene.cells.drawn()).map(|(k, c)| (k.level, c)).collect();
        self.gather_cells(&scene.world, &drawn, sights, lod);
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
        for (j, i) in run.iter().enumerate() {
            // Without levels of detail, the placement as it is, at full detail.
            let levels = match lod {
                Some(lod) => lod.levels(i.base(), errors),
                None => [Some((0, i.tint[3])), None],
            };
            let sphere = world_sphere(i, group.sphere);
            for (s, sight) in sights.iter().enumerate() {
                if covers[s] == Cover::Out || !sight.sees(covers[s], sphere) {
                    continue;
                }
                for (level, fade) in levels.into_iter().flatten() {
                    if level < MESH_LEVELS {
                        out.push(Seen {
                            slot: tag(s, k * MESH_LEVELS + level),
                            index: (first + j) as u32,
                            fade,
                        });
                    }
                }
            }
        }
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
        for (j, i) in run.iter().enumerate() {
            let levels = match far {
                Some(lod) => lod.levels(i.base(), errors),
                None => [Some((MESH_LEVELS, i.tint[3])), None],
            };
            let sphere = world_sphere(i, world.proxies[k].sphere);
            for (s, sight) in sights.iter().enumerate() {
                if covers[s] == Cover::Out || !sight.sees(covers[s], sphere) {
                    continue;
                }
                for (level, fade) in levels.into_iter().flatten() {
                    if level == MESH_LEVELS {
                        out.push(Seen {
                            slot: tag(s, impostors + k),
                            index: (first + j) as u32 | PROXY,
                            fade,
                        });
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shadow::{SHADOW_TEXEL, light_view_proj};
    use crate::world::{SceneOptions, lod_chain};
    use proptest::prelude::*;
    use std::sync::{Mutex, OnceLock, PoisonError};
    use sylva::terrain::glam::camera::rh::{proj::directx, view};

    #[test]
    fn spheres_in_front_are_kept_and_spheres_behind_or_aside_are_culled() {
        let proj = directx::perspective(60f32.to_radians(), 1.0, 0.2, 500.0);
        let look = view::look_to_mat4(Vec3::ZERO, Vec3::X, Vec3::Y);
        let v = Volume::of(&(proj * look));
        assert!(v.touches(Vec3::new(50.0, 0.0, 0.0), 1.0));
        assert!(!v.touches(Vec3::new(-50.0, 0.0, 0.0), 1.0));
        assert!(!v.touches(Vec3::new(50.0, 0.0, 60.0), 1.0));
        // Half a field of view is 30 degrees: a sphere just outside the edge, larger than
        // its distance to the plane, is kept.
        assert!(v.touches(Vec3::new(50.0, 0.0, 31.0), 5.0));
        assert!(!v.touches(Vec3::new(600.0, 0.0, 0.0), 1.0));
    }

    #[test]
    fn a_sphere_is_held_only_when_no_part_of_it_is_outside() {
        let proj = directx::perspective(60f32.to_radians(), 1.0, 0.2, 500.0);
        let v = Volume::of(&(proj * view::look_to_mat4(Vec3::ZERO, Vec3::X, Vec3::Y)));
        assert!(v.holds(Vec3::new(50.0, 0.0, 0.0), 10.0));
        // Touching the edge of the view is not being held by it.
        assert!(v.touches(Vec3::new(50.0, 0.0, 28.0), 5.0));
        assert!(!v.holds(Vec3::new(50.0, 0.0, 28.0), 5.0));
        assert!(!v.holds(Vec3::new(0.5, 0.0, 0.0), 1.0));
    }

    #[test]
    fn box_distances_are_to_the_nearest_and_farthest_corner() {
        let b = (Vec3::ZERO, Vec3::new(2.0, 2.0, 2.0));
        assert_eq!(nearest_distance(Vec3::new(1.0, 1.0, 1.0), b), 0.0);
        assert_eq!(nearest_distance(Vec3::new(5.0, 1.0, 1.0), b), 3.0);
        assert_eq!(
            farthest_distance(Vec3::new(5.0, 0.0, 0.0), b),
            Vec3::new(5.0, 2.0, 2.0).length()
        );
    }

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
            let drawn: Vec<(Level, &Cell)> =
                (scene.cells.drawn()).map(|(k, c)| (k.level, c)).collect();
            let world: &World = &scene.world;
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
