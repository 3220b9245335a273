//! The cells' pass of a frame's gathering: each cell's placements that the sights see, as
//! small records tagged with their slot, testing whole pieces of runs where their bounds
//! decide and single placements only where they do not.

use sylva::terrain::glam::Vec3;

use super::{PROXY, Seen};
use crate::cell::{Cell, Level, RunBounds};
use crate::cull::{
    Cover, Levels, LodView, MAX_SIGHTS, Sight, farthest_distance, nearest_distance, run_covers,
};
use crate::geometry::{InstanceRaw, MESH_LEVELS, world_sphere};
use crate::world::World;

/// Appends to `out` the placements of one cell that `sights` see.
pub(super) fn gather_cell(
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
        let levels = lod.map_or(Choice::Fixed(0), |lod| Choice::ByDistance(lod, errors));
        let slot = |s, level| (level < MESH_LEVELS).then(|| tag(s, k * MESH_LEVELS + level));
        gather_piece(piece, (sights, covers), levels, slot, out);
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
        let levels = far.map_or(Choice::Fixed(MESH_LEVELS), |lod| {
            Choice::ByDistance(lod, errors)
        });
        let slot = |s, level| (level == MESH_LEVELS).then(|| tag(s, impostors + k));
        gather_piece(piece, (sights, covers), levels, slot, out);
    }
}

/// How a piece's instances choose their level of detail.
#[derive(Clone, Copy)]
enum Choice<'a> {
    /// Each by its base's distance, for a variant with these errors.
    ByDistance(LodView, &'a [f32; MESH_LEVELS]),
    /// All at this level, unfaded: a cell drawn without levels of detail, or a coarse
    /// cell's proxies. (Every instance's own fade is 0; the fade a frame gives it replaces
    /// it.)
    Fixed(usize),
}

impl Choice<'_> {
    /// The levels of an instance whose tree stands at `base`.
    fn at(self, base: Vec3) -> Levels {
        match self {
            Choice::ByDistance(lod, errors) => lod.levels(base, errors),
            Choice::Fixed(level) => [Some((level, 0.0)), None],
        }
    }

    /// The levels every instance with its base in the box `bases` has, when there is one.
    fn across(self, bases: (Vec3, Vec3)) -> Option<Levels> {
        match self {
            Choice::ByDistance(lod, errors) => lod.level_across(bases, errors),
            Choice::Fixed(level) => Some([Some((level, 0.0)), None]),
        }
    }
}

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
/// each instance at the levels `levels` chooses, filed in `slot(sight, level)` (none: not
/// drawn in this pass). Instances are tested only where the piece's bounds leave it open:
/// a piece wholly seen by every sight that may see it, at one level across its bases, is
/// taken whole, in the same order.
fn gather_piece(
    piece: Piece<'_>,
    (sights, covers): (&[Sight], [Cover; MAX_SIGHTS]),
    levels: Choice<'_>,
    slot: impl Fn(usize, usize) -> Option<u32>,
    out: &mut Vec<Seen>,
) {
    let open = |s: usize| covers[s] != Cover::Out;
    let whole: [bool; MAX_SIGHTS] =
        std::array::from_fn(|s| s < sights.len() && sights[s].sees_whole(covers[s], piece.bounds));
    let all_whole = (0..sights.len()).all(|s| !open(s) || whole[s]);
    let index = |j: usize| (piece.first + j) as u32 | piece.tag;
    let constant = levels.across(piece.bounds.bases);
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
        let levels = constant.unwrap_or_else(|| levels.at(i.base()));
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
