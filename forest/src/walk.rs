//! The guided walk (Garden of Eden thesis, section 7.4): a walker led through the forest by an
//! attractor at a random target and repelled by the trunks around it, as point charges.

use std::collections::HashMap;

use glam::Vec2;
use sylva_base::hash::{mix, unit_f32 as unit};
use sylva_base::range::check;
use sylva_instancing::CompactTree;
use sylva_terrain::HeightField;

use crate::density::{Rect, distance_to_segment};
use crate::error::ForestError;
use crate::forest::ForestBuilder;

/// Settings of a [`GuidedWalk`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct WalkOptions {
    /// Metres per step. Default: 0.1.
    pub step: f32,
    /// Trunks farther than this (metres) do not push. Default: 5.
    pub influence: f32,
    /// Strength of a trunk's push against the target's pull of 1, at one metre beyond the
    /// trunk's clearance (it grows as the inverse square of that distance). Default: 0.6.
    pub repulsion: f32,
    /// The walker's own radius, added to every trunk's. Default: 0.35.
    pub body: f32,
    /// Within this distance (metres) of the target it counts as reached. Default: 3.
    pub arrival: f32,
    /// Targets and the walk keep this far (metres) inside the terrain's edge. Default: 10.
    pub margin: f32,
    /// Most the heading turns in one step, radians. Default: 0.08.
    pub turn: f32,
    /// Most the walker's own steering can bend the heading, radians. Default: 0.35.
    pub deviation: f32,
    /// Steps without coming 1 m closer to the target before another target is drawn. Default: 300.
    pub patience: u32,
}

impl Default for WalkOptions {
    fn default() -> Self {
        WalkOptions {
            step: 0.1,
            influence: 5.0,
            repulsion: 0.6,
            body: 0.35,
            arrival: 3.0,
            margin: 10.0,
            turn: 0.08,
            deviation: 0.35,
            patience: 300,
        }
    }
}

impl WalkOptions {
    /// Sets [`WalkOptions::step`].
    #[must_use]
    pub fn with_step(mut self, step: f32) -> Self {
        self.step = step;
        self
    }

    /// Sets [`WalkOptions::influence`].
    #[must_use]
    pub fn with_influence(mut self, influence: f32) -> Self {
        self.influence = influence;
        self
    }

    /// Sets [`WalkOptions::repulsion`].
    #[must_use]
    pub fn with_repulsion(mut self, repulsion: f32) -> Self {
        self.repulsion = repulsion;
        self
    }

    /// Sets [`WalkOptions::body`].
    #[must_use]
    pub fn with_body(mut self, body: f32) -> Self {
        self.body = body;
        self
    }

    /// Sets [`WalkOptions::arrival`].
    #[must_use]
    pub fn with_arrival(mut self, arrival: f32) -> Self {
        self.arrival = arrival;
        self
    }

    /// Sets [`WalkOptions::margin`].
    #[must_use]
    pub fn with_margin(mut self, margin: f32) -> Self {
        self.margin = margin;
        self
    }

    /// Sets [`WalkOptions::turn`].
    #[must_use]
    pub fn with_turn(mut self, turn: f32) -> Self {
        self.turn = turn;
        self
    }

    /// Sets [`WalkOptions::deviation`].
    #[must_use]
    pub fn with_deviation(mut self, deviation: f32) -> Self {
        self.deviation = deviation;
        self
    }

    /// Sets [`WalkOptions::patience`].
    #[must_use]
    pub fn with_patience(mut self, patience: u32) -> Self {
        self.patience = patience;
        self
    }
}

/// Where trunks stand: anything that can list the trunks near a point.
pub trait Trunks {
    /// Appends the trunks (centre, radius) within `reach` of `p`; more may be given.
    fn near(&mut self, p: Vec2, reach: f32, out: &mut Vec<(Vec2, f32)>);
}

/// Trunks in a uniform grid, for a fixed set of trees.
#[derive(Debug, Clone)]
pub struct TrunkGrid {
    cell: f32,
    cells: HashMap<(i64, i64), Vec<(Vec2, f32)>>,
}

impl TrunkGrid {
    /// A grid of `trunks` (centre, radius) in cells of `cell` metres.
    pub fn new(trunks: impl IntoIterator<Item = (Vec2, f32)>, cell: f32) -> Self {
        let cell = if cell.is_finite() && cell > 0.0 {
            cell
        } else {
            10.0
        };
        let mut cells: HashMap<(i64, i64), Vec<(Vec2, f32)>> = HashMap::new();
        for (p, r) in trunks {
            if p.is_finite() && r.is_finite() {
                let key = ((p.x / cell).floor() as i64, (p.y / cell).floor() as i64);
                cells.entry(key).or_default().push((p, r));
            }
        }
        TrunkGrid { cell, cells }
    }

    /// The trunks of `trees`, each of radius `radius(tree)`.
    pub fn of_trees<'a>(
        trees: impl IntoIterator<Item = &'a CompactTree>,
        radius: impl Fn(&CompactTree) -> f32,
    ) -> Self {
        TrunkGrid::new(
            trees
                .into_iter()
                .map(|t| (Vec2::new(t.position[0], t.position[2]), radius(t))),
            10.0,
        )
    }
}

impl TrunkGrid {
    /// The cells within `reach` of `p`.
    fn keys(&self, p: Vec2, reach: f32) -> impl Iterator<Item = (i64, i64)> + use<> {
        let cell = self.cell;
        let span =
            move |v: f32| ((v - reach) / cell).floor() as i64..=((v + reach) / cell).floor() as i64;
        let xs = span(p.x);
        span(p.y).flat_map(move |j| xs.clone().map(move |i| (i, j)))
    }
}

impl Trunks for TrunkGrid {
    fn near(&mut self, p: Vec2, reach: f32, out: &mut Vec<(Vec2, f32)>) {
        for key in self.keys(p, reach) {
            if let Some(c) = self.cells.get(&key) {
                out.extend_from_slice(c);
            }
        }
    }
}

/// The trunks of a generated (or painted) forest, generated on demand in 50 m squares as the
/// walker comes near them, so a walk through a world of millions of trees holds only the
/// trunks around it.
pub struct ForestTrunks<'a> {
    trees: Box<dyn FnMut(Rect) -> Vec<CompactTree> + 'a>,
    radius: Box<dyn Fn(&CompactTree) -> f32 + 'a>,
    /// The squares generated so far, as a grid of their side.
    grid: TrunkGrid,
}

/// Side of the squares [`ForestTrunks`] generates.
const TRUNK_SQUARE: f32 = 50.0;

/// Most squares [`ForestTrunks`] keeps (a long walk forgets the oldest).
const MAX_TRUNK_SQUARES: usize = 4096;

impl<'a> ForestTrunks<'a> {
    /// Trunks from `trees`, which gives the trees of a rectangle (as
    /// [`ForestBuilder::trees`] does), each of radius `radius(tree)`.
    pub fn new(
        trees: impl FnMut(Rect) -> Vec<CompactTree> + 'a,
        radius: impl Fn(&CompactTree) -> f32 + 'a,
    ) -> Self {
        ForestTrunks {
            trees: Box::new(trees),
            radius: Box::new(radius),
            grid: TrunkGrid::new(Vec::new(), TRUNK_SQUARE),
        }
    }

    /// The trunks of `builder`'s forest on `terrain`: `canopy` metres across for canopy
    /// trees, `seedling` for seedlings, times each tree's scale.
    pub fn by_maturity(
        builder: &'a ForestBuilder,
        terrain: &'a dyn HeightField,
        canopy: f32,
        seedling: f32,
    ) -> Self {
        let young: Vec<bool> = builder.variants().iter().map(|v| v.seedling).collect();
        ForestTrunks::new(
            move |rect| builder.trees(terrain, rect),
            move |t: &CompactTree| {
                let seedling_form = young.get(usize::from(t.variant)).copied().unwrap_or(false);
                t.scale * if seedling_form { seedling } else { canopy }
            },
        )
    }

    /// Forgets the trunks generated so far (after the forest changed, as painting does).
    pub fn forget(&mut self) {
        self.grid.cells.clear();
    }
}

impl std::fmt::Debug for ForestTrunks<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ForestTrunks")
            .field("squares", &self.grid.cells.len())
            .finish_non_exhaustive()
    }
}

impl Trunks for ForestTrunks<'_> {
    fn near(&mut self, p: Vec2, reach: f32, out: &mut Vec<(Vec2, f32)>) {
        // A long walk forgets what it generated, before this call's squares come in.
        if self.grid.cells.len() >= MAX_TRUNK_SQUARES {
            self.grid.cells.clear();
        }
        // Squares not generated yet are generated (an empty square is kept too).
        for key in self.grid.keys(p, reach) {
            if self.grid.cells.contains_key(&key) {
                continue;
            }
            let min = Vec2::new(key.0 as f32, key.1 as f32) * TRUNK_SQUARE;
            let trunks = (self.trees)(Rect::new(min, min + TRUNK_SQUARE))
                .iter()
                .map(|t| (Vec2::new(t.position[0], t.position[2]), (self.radius)(t)))
                .collect();
            self.grid.cells.insert(key, trunks);
        }
        self.grid.near(p, reach, out);
    }
}

/// One step of a walk.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WalkStep {
    /// Where the walker is (x, z).
    pub position: Vec2,
    /// Which way it faces (unit, x-z).
    pub heading: Vec2,
    /// Whether it moved (it stands still only when boxed in, and then draws a new target).
    pub moved: bool,
    /// Whether a new target was drawn this step.
    pub new_target: bool,
}

/// A walker led through the forest: pulled toward a random target, pushed away from the trunks
/// within reach by an inverse-square charge each, never closer to a trunk than its radius plus
/// the walker's body; on arrival (or when it makes no progress) it draws a new target.
///
/// ```
/// use sylva_forest::{GuidedWalk, Rect, TrunkGrid, WalkOptions};
/// use sylva_terrain::glam::Vec2;
///
/// let trunks: Vec<(Vec2, f32)> = (0..400)
///     .map(|k| (Vec2::new((k % 20) as f32 * 5.0 + 2.5, (k / 20) as f32 * 5.0 + 2.5), 0.3))
///     .collect();
/// let mut grid = TrunkGrid::new(trunks.clone(), 10.0);
/// let bounds = Rect::new(Vec2::ZERO, Vec2::splat(100.0));
/// let mut walk = GuidedWalk::new(bounds, &mut grid, Vec2::splat(50.0), 7, WalkOptions::default())?;
/// for _ in 0..2000 {
///     let step = walk.step(&mut grid, 0.0);
///     assert!(trunks.iter().all(|(t, r)| step.position.distance(*t) >= r + 0.35 - 1e-4));
/// }
/// # Ok::<(), sylva_forest::ForestError>(())
/// ```
#[derive(Debug, Clone)]
pub struct GuidedWalk {
    bounds: Rect,
    options: WalkOptions,
    seed: u64,
    draws: u64,
    position: Vec2,
    heading: Vec2,
    target: Vec2,
    best: f32,
    waiting: u32,
    targets: u64,
    arrivals: u64,
    near: Vec<(Vec2, f32)>,
}

impl GuidedWalk {
    /// A walk over `bounds` starting at `start` (moved to the nearest free spot if a trunk
    /// stands there). An error when the bounds leave no room inside the margin or the options
    /// are out of range.
    pub fn new(
        bounds: Rect,
        trunks: &mut dyn Trunks,
        start: Vec2,
        seed: u64,
        options: WalkOptions,
    ) -> Result<Self, ForestError> {
        let o = &options;
        check(
            "step",
            o.step.into(),
            o.step > 0.0 && o.step <= 10.0,
            "0 < step <= 10 m",
        )?;
        for (name, v) in [
            ("influence", o.influence),
            ("arrival", o.arrival),
            ("turn", o.turn),
            ("deviation", o.deviation),
        ] {
            check(name, v.into(), v > 0.0, "a positive number")?;
        }
        for (name, v) in [
            ("repulsion", o.repulsion),
            ("body", o.body),
            ("margin", o.margin),
        ] {
            check(name, v.into(), v >= 0.0, "zero or more")?;
        }
        let inner = Rect::new(bounds.min + o.margin, bounds.max - o.margin);
        if inner.is_empty() || !start.is_finite() {
            return Err(ForestError::NoRoomToWalk {
                min: bounds.min,
                max: bounds.max,
                margin: o.margin,
            });
        }
        let mut walk = GuidedWalk {
            bounds: inner,
            options,
            seed,
            draws: 0,
            position: start.clamp(inner.min, inner.max),
            heading: Vec2::X,
            target: start,
            best: f32::INFINITY,
            waiting: 0,
            targets: 0,
            arrivals: 0,
            near: Vec::new(),
        };
        walk.position = walk.free_spot(trunks, walk.position);
        walk.new_target(trunks);
        walk.heading = (walk.target - walk.position).normalize_or(Vec2::X);
        Ok(walk)
    }

    /// Where the walker is.
    pub fn position(&self) -> Vec2 {
        self.position
    }

    /// Which way it faces.
    pub fn heading(&self) -> Vec2 {
        self.heading
    }

    /// Where it is heading for.
    pub fn target(&self) -> Vec2 {
        self.target
    }

    /// Targets drawn so far (the first included).
    pub fn targets(&self) -> u64 {
        self.targets
    }

    /// Targets reached so far (the others were given up: behind a thicket, or boxed in).
    pub fn arrivals(&self) -> u64 {
        self.arrivals
    }

    /// Takes one step. `steer` (-1 to 1; clamped) is the walker's own wish to bend left
    /// (negative) or right, by at most [`WalkOptions::deviation`].
    pub fn step(&mut self, trunks: &mut dyn Trunks, steer: f32) -> WalkStep {
        let o = self.options;
        let mut new_target = false;
        let to_target = self.target - self.position;
        if to_target.length() < o.arrival {
            self.arrivals += 1;
            self.new_target(trunks);
            new_target = true;
        }
        self.near.clear();
        trunks.near(self.position, o.influence + o.body + 2.0, &mut self.near);
        // In one order whatever the source's, so the forces sum to the same bits.
        self.near.sort_unstable_by(|a, b| {
            (a.0.x.total_cmp(&b.0.x))
                .then(a.0.y.total_cmp(&b.0.y))
                .then(a.1.total_cmp(&b.1))
        });
        self.near.dedup();
        // The target pulls with strength 1; each trunk pushes as a point charge.
        let mut force = (self.target - self.position).normalize_or(self.heading);
        for &(t, r) in &self.near {
            let away = self.position - t;
            let d = away.length();
            let gap = (d - r - o.body).max(0.05);
            if d > 0.0 && d < o.influence + r {
                let fade = 1.0 - d / (o.influence + r);
                force += away / d * (o.repulsion * fade * fade / (gap * gap)).min(50.0);
            }
        }
        // The terrain's edge pushes like a wall of charges.
        for (gap, push) in [
            (self.position.x - self.bounds.min.x, Vec2::X),
            (self.bounds.max.x - self.position.x, -Vec2::X),
            (self.position.y - self.bounds.min.y, Vec2::Y),
            (self.bounds.max.y - self.position.y, -Vec2::Y),
        ] {
            if gap < o.influence {
                force += push * (o.repulsion / gap.max(0.05).powi(2)).min(50.0);
            }
        }
        let wish = Vec2::from_angle(steer.clamp(-1.0, 1.0) * o.deviation);
        let desired = wish.rotate(force.normalize_or(self.heading));
        // Turn toward the desired heading by at most `turn`.
        let angle = self.heading.angle_to(desired);
        self.heading = Vec2::from_angle(angle.clamp(-o.turn, o.turn))
            .rotate(self.heading)
            .normalize_or(Vec2::X);
        // The step itself never comes closer to a trunk than its clearance: if the heading
        // is blocked, the nearest free direction is taken (the side the heading leans to first).
        let side = if angle >= 0.0 { 1.0 } else { -1.0 };
        let free = (0..=12).flat_map(|k| [k, -k]).skip(1).find_map(|k: i32| {
            let turned = Vec2::from_angle(side * k as f32 * 0.2618).rotate(self.heading);
            let next = self.position + turned * o.step;
            self.clear(self.position, next).then_some((turned, next))
        });
        let moved = match free {
            Some((heading, next)) => {
                self.heading = heading;
                self.position = next;
                true
            }
            None => {
                self.new_target(trunks);
                new_target = true;
                false
            }
        };
        // No progress toward the target for a while: it is behind something; draw another.
        let d = self.target.distance(self.position);
        if d < self.best - 1.0 {
            self.best = d;
            self.waiting = 0;
        } else {
            self.waiting += 1;
            if self.waiting > o.patience {
                self.new_target(trunks);
                new_target = true;
            }
        }
        WalkStep {
            position: self.position,
            heading: self.heading,
            moved,
            new_target,
        }
    }

    /// Whether the segment from `a` to `b` keeps clear of every trunk near and of the edge.
    fn clear(&self, a: Vec2, b: Vec2) -> bool {
        let inside = b.cmpge(self.bounds.min).all() && b.cmple(self.bounds.max).all();
        inside
            && self
                .near
                .iter()
                .all(|&(t, r)| distance_to_segment(t, a, b) >= r + self.options.body)
    }

    /// A point near `p` clear of every trunk (p itself when it is).
    fn free_spot(&mut self, trunks: &mut dyn Trunks, p: Vec2) -> Vec2 {
        for k in 0..64u64 {
            let q = if k == 0 {
                p
            } else {
                let h = mix(self.seed ^ 0xf1ee ^ (k << 8));
                let r = 0.5 * k as f32;
                (p + Vec2::from_angle(unit(h) * std::f32::consts::TAU) * r)
                    .clamp(self.bounds.min, self.bounds.max)
            };
            self.near.clear();
            trunks.near(q, 4.0 + self.options.body, &mut self.near);
            if self.clear(q, q) {
                return q;
            }
        }
        p
    }

    fn new_target(&mut self, trunks: &mut dyn Trunks) {
        let h = mix(self.seed ^ mix(self.draws.wrapping_add(1)));
        self.draws += 1;
        let span = self.bounds.max - self.bounds.min;
        let t = self.bounds.min + Vec2::new(unit(h), unit(mix(h))) * span;
        self.target = self.free_spot(trunks, t);
        self.best = self.target.distance(self.position);
        self.waiting = 0;
        self.targets += 1;
    }
}
