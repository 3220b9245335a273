//! The growth manager: trees sharing one voxel space, each with its own derivation, seed and
//! start time, grown branch-parallel in nature's order.

use glam::{Quat, Vec3};
use sylva_base::hash::{mix, unit_f32};
use sylva_lsys::{Deriver, Limits, Word};
use sylva_turtle::Frame;

use crate::branches::{Branch, Step, branches};
use crate::error::GrowthError;
use crate::grid::VoxelGrid;
use crate::grown::{GrownSegment, GrownTree};
use crate::light::{Light, Sky};
use crate::options::{GrowthOptions, GrowthStats, TreeSpec};
use crate::ray::march;
use crate::voxelise::{
    capsule_is_free, capsule_is_free_beyond, voxelise_capsule, voxelise_triangles,
};

/// Trees growing together in one voxel space around obstacles.
///
/// ```
/// use std::sync::Arc;
/// use sylva_growth::{GrowthOptions, Response, Stand, TreeSpec, VoxelGrid};
/// use sylva_growth::glam::Vec3;
/// use sylva_turtle::TurtleOptions;
///
/// let grammar = Arc::new("axiom: A\nA -> F(0.5)[+(30)A][-(30)A]".parse()?);
/// let grid = VoxelGrid::new(Vec3::new(-4.0, 0.0, -4.0), Vec3::new(4.0, 6.0, 4.0), 0.1)?;
/// let mut stand = Stand::new(grid, GrowthOptions::default());
/// stand.add(TreeSpec {
///     base: Vec3::new(0.0, 0.0, 0.0),
///     grammar,
///     generations: 6,
///     seed: 1,
///     start: 0,
///     turtle: TurtleOptions::default().with_width(0.05),
///     response: Response::default(),
/// });
/// let (trees, stats) = stand.grow()?;
/// assert_eq!(trees.len(), 1);
/// assert!(stats.segments > 20 && trees[0].segments.len() as u64 == stats.segments);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone)]
pub struct Stand {
    obstacles: VoxelGrid,
    options: GrowthOptions,
    trees: Vec<TreeSpec>,
}

/// A branch growing: where its turtle is and which step comes next.
#[derive(Debug, Clone)]
struct Apex {
    tree: usize,
    branch: u32,
    next: usize,
    frame: Frame,
    width: f32,
    /// Index of the last segment on this axis (for tube joins), in the tree's segments.
    last: Option<u32>,
    same_axis: bool,
    /// The branch that spawned it (for aborting subtrees).
    parent: Option<usize>,
    alive: bool,
}

impl Stand {
    /// A stand in the space of `obstacles` (voxelise ground, rocks and buildings into it
    /// first; its shape is the space the trees grow in).
    pub fn new(obstacles: VoxelGrid, options: GrowthOptions) -> Stand {
        Stand {
            obstacles,
            options,
            trees: Vec::new(),
        }
    }

    /// Adds a tree.
    pub fn add(&mut self, tree: TreeSpec) -> &mut Stand {
        self.trees.push(tree);
        self
    }

    /// The obstacles' voxels.
    pub fn obstacles(&self) -> &VoxelGrid {
        &self.obstacles
    }

    /// Grows every tree and returns them in the order they were added, with figures. A pure
    /// function of the stand: same trees, seeds and obstacles, same result.
    pub fn grow(&self) -> Result<(Vec<GrownTree>, GrowthStats), GrowthError> {
        let sky = Sky::new(self.options.sun, self.options.sky_rays, self.options.seed);
        let limits = Limits::DEFAULT;
        let uses_queries = self.options.query.is_some_and(|q| {
            self.trees
                .iter()
                .any(|t| t.grammar.alphabet().id(q).is_some())
        });
        let mut stats = GrowthStats::default();
        // Without queries: derive each tree once and grow once. With them: one generation
        // at a time, each grown in full so that the next derivation sees the environment.
        let mut words: Vec<Word> = Vec::with_capacity(self.trees.len());
        let mut done = Vec::with_capacity(self.trees.len());
        for t in &self.trees {
            let steps = if uses_queries { 0 } else { t.generations };
            words.push(t.grammar.derive_with(steps, t.seed, &limits)?);
            done.push(steps);
        }
        let rounds = if uses_queries {
            self.trees.iter().map(|t| t.generations).max().unwrap_or(0)
        } else {
            0
        };
        let mut grown = self.grow_round(&sky, &mut words, &mut stats)?;
        stats.rounds = 1;
        for round in 1..=rounds {
            for (i, t) in self.trees.iter().enumerate() {
                if done[i] >= t.generations {
                    continue;
                }
                // A fresh deriver per step keeps each step a pure function of the tree's
                // seed and generation.
                let mut deriver = Deriver::new(&t.grammar, mix(t.seed ^ u64::from(round)), limits);
                let word =
                    std::mem::replace(&mut words[i], Word::empty(t.grammar.alphabet().clone()));
                words[i] = deriver.derive_from(word, done[i], 1)?;
                done[i] += 1;
            }
            stats = GrowthStats {
                rounds: stats.rounds,
                ..GrowthStats::default()
            };
            grown = self.grow_round(&sky, &mut words, &mut stats)?;
            stats.rounds += 1;
        }
        Ok((grown, stats))
    }

    /// Grows every tree's current word from its base, all branches at once, in a space
    /// holding only the obstacles; fills query modules in `words`.
    fn grow_round(
        &self,
        sky: &Sky,
        words: &mut [Word],
        stats: &mut GrowthStats,
    ) -> Result<Vec<GrownTree>, GrowthError> {
        let mut grid = self.obstacles.clone();
        let plans: Vec<Vec<Branch>> = self
            .trees
            .iter()
            .zip(words.iter())
            .map(|(t, w)| branches(w, &t.turtle, self.options.query))
            .collect::<Result<_, _>>()?;
        let mut grown: Vec<GrownTree> = self.trees.iter().map(|_| GrownTree::default()).collect();
        let mut answers: Vec<Vec<(u32, [f64; 2])>> = vec![Vec::new(); self.trees.len()];
        let mut apices: Vec<Apex> = Vec::new();
        let mut started = vec![false; self.trees.len()];
        let cone = self.options.cone_degrees.clamp(0.0, 90.0).to_radians();
        let mut iteration = 0u32;
        loop {
            for (i, t) in self.trees.iter().enumerate() {
                if !started[i] && iteration >= t.start {
                    started[i] = true;
                    apices.push(Apex {
                        tree: i,
                        branch: 0,
                        next: 0,
                        frame: Frame {
                            position: t.base,
                            rotation: Quat::IDENTITY,
                        },
                        width: t.turtle.width,
                        last: None,
                        same_axis: false,
                        parent: None,
                        alive: true,
                    });
                }
            }
            let waiting = started.iter().any(|s| !s);
            if apices.iter().all(|a| !a.alive) && !waiting {
                break;
            }
            if iteration >= self.options.max_iterations {
                return Err(GrowthError::Unfinished {
                    limit: self.options.max_iterations,
                });
            }
            // Every active apex advances one segment, in an order drawn from the seed, so
            // that no branch has first claim on space and light.
            let mut order: Vec<usize> = (0..apices.len()).filter(|&a| apices[a].alive).collect();
            let key = mix(self.options.seed ^ u64::from(iteration).wrapping_mul(0x9e37_79b9));
            order.sort_by_key(|&a| mix(key ^ a as u64));
            for a in order {
                if !apices[a].alive {
                    continue;
                }
                self.advance(
                    a,
                    &mut apices,
                    &plans,
                    &mut grid,
                    sky,
                    cone,
                    &mut grown,
                    &mut answers,
                    stats,
                );
            }
            iteration += 1;
        }
        stats.iterations = iteration;
        // Write the environment's answers into the words for the next derivation.
        for (word, mut found) in words.iter_mut().zip(answers) {
            if found.is_empty() {
                continue;
            }
            // Branches answered in their growth order; the word is read in its own.
            found.sort_by_key(|f| f.0);
            let mut filled = Word::empty(word.alphabet().clone());
            let mut k = 0;
            for (i, m) in word.iter().enumerate() {
                if k < found.len() && found[k].0 as usize == i {
                    let mut params = m.params.to_vec();
                    for (p, v) in params.iter_mut().zip(found[k].1) {
                        *p = v;
                    }
                    filled.push(m.id, &params);
                    k += 1;
                } else {
                    filled.push(m.id, m.params);
                }
            }
            *word = filled;
        }
        Ok(grown)
    }

    /// Runs apex `a`'s steps up to and including its next segment (or its end).
    #[allow(
        clippy::too_many_arguments,
        reason = "the round's state, borrowed piecewise"
    )]
    fn advance(
        &self,
        a: usize,
        apices: &mut Vec<Apex>,
        plans: &[Vec<Branch>],
        grid: &mut VoxelGrid,
        sky: &Sky,
        cone: f32,
        grown: &mut [GrownTree],
        answers: &mut [Vec<(u32, [f64; 2])>],
        stats: &mut GrowthStats,
    ) {
        let tree = apices[a].tree;
        let spec = &self.trees[tree];
        let branch = &plans[tree][apices[a].branch as usize];
        loop {
            let Some(&step) = branch.steps.get(apices[a].next) else {
                apices[a].alive = false;
                return;
            };
            apices[a].next += 1;
            let ap = &mut apices[a];
            match step {
                Step::Yaw(r) => ap.frame.yaw(r),
                Step::Pitch(r) => ap.frame.pitch(r),
                Step::Roll(r) => ap.frame.roll(r),
                Step::Level => ap.frame.roll_to_horizontal(),
                Step::Width(w) => ap.width = w,
                Step::Thinner => ap.width *= spec.turtle.width_factor,
                Step::Leaf(scale) => {
                    // Leaves shade: the card occupies its voxels like any surface.
                    let size = spec.turtle.leaf_size.map(|s| s * scale);
                    let frame = ap.frame.facing_sky(spec.turtle.leaf_facing);
                    let (h, l) = (frame.heading() * size[0], frame.left() * (size[1] * 0.5));
                    let p = frame.position;
                    voxelise_triangles(
                        grid,
                        &[p + l, p - l, p - l + h, p + l + h],
                        &[0, 1, 2, 0, 2, 3],
                    );
                    grown[tree].leaves.push((frame, size));
                }
                Step::Query(index) => {
                    let light = sample(sky, grid, bud(ap, spec, grid), stats);
                    let space = free_space(grid, ap.frame.position, self.options.query_radius);
                    answers[tree].push((
                        index,
                        [
                            f64::from(light.combined(spec.response.direct_weight)),
                            f64::from(space),
                        ],
                    ));
                }
                Step::Spawn(child) => {
                    let child_apex = Apex {
                        tree,
                        branch: child,
                        next: 0,
                        frame: ap.frame,
                        width: ap.width,
                        last: ap.last,
                        same_axis: false,
                        parent: Some(a),
                        alive: true,
                    };
                    apices.push(child_apex);
                }
                Step::Move(length) => {
                    ap.frame.position += ap.frame.heading() * length;
                    ap.same_axis = false;
                }
                Step::Draw(length) => {
                    self.grow_segment(
                        a,
                        apices,
                        length,
                        branch.depth,
                        grid,
                        sky,
                        cone,
                        grown,
                        stats,
                    );
                    return;
                }
            }
        }
    }

    /// Places one segment of apex `a`: light scales it and turns it, collisions deflect or
    /// abort it.
    #[allow(
        clippy::too_many_arguments,
        reason = "the round's state, borrowed piecewise"
    )]
    fn grow_segment(
        &self,
        a: usize,
        apices: &mut [Apex],
        length: f32,
        depth: u32,
        grid: &mut VoxelGrid,
        sky: &Sky,
        cone: f32,
        grown: &mut [GrownTree],
        stats: &mut GrowthStats,
    ) {
        let tree = apices[a].tree;
        let spec = &self.trees[tree];
        let response = spec.response;
        let radius = (apices[a].width * 0.5).max(spec.turtle.min_radius);
        let bud = bud(&apices[a], spec, grid);
        let light = sample(sky, grid, bud, stats);
        let lit = light.combined(response.direct_weight);
        if lit < response.threshold {
            stats.stopped += 1;
            if response.shed {
                grown[tree].shed_axis(apices[a].last);
            }
            apices[a].alive = false;
            return;
        }
        let span = (1.0 - response.threshold).max(1e-3);
        let vigour = ((lit - response.threshold) / span).clamp(0.0, 1.0);
        let length = length * (response.min_growth + (1.0 - response.min_growth) * vigour);
        // Phototropism: turn towards where the light comes from, by an angle proportional to
        // how much of the sky is hidden, at most the species' maximum.
        let ap = &mut apices[a];
        if let Some(target) = light_direction(grid, sky, bud, &light) {
            let h = ap.frame.heading();
            let angle = h.angle_between(target);
            let turn = (response.max_turn_degrees.to_radians() * (1.0 - light.ambient)).min(angle);
            if angle > 1e-4 && turn > 0.0 {
                let full = Quat::from_rotation_arc(h, target);
                let q = Quat::IDENTITY.slerp(full, turn / angle);
                ap.frame.rotation = (q * ap.frame.rotation).normalize();
            }
        }
        if let Some(t) = spec.turtle.tropism {
            ap.frame.bend_towards(t.direction, t.susceptibility);
        }
        let start = ap.frame.position;
        // A segment continuing its axis starts at its parent's end radius: the tube it
        // sweeps is as wide as the wider end.
        let start_radius = match (ap.same_axis, ap.last) {
            (true, Some(last)) => grown[tree].segments[last as usize].end_radius,
            _ => radius,
        };
        let sweep = start_radius.max(radius);
        // The start lies inside the voxels of the segment it grows from and of its siblings
        // at the same joint: against trees, voxels within two conservative radii of the
        // joint do not count; against the obstacles, everything does.
        let reach = sweep + grid.voxel_size() * 0.5 * 3f32.sqrt();
        let clearance = 2.0 * reach + grid.voxel_size() * 0.5;
        let obstacles = &self.obstacles;
        // A trunk's first segment is rooted: it may start in the ground's voxels.
        let rooted = ap.last.is_none() && ap.branch == 0;
        let free = |grid: &VoxelGrid, heading: Vec3| {
            let end = start + heading * length;
            let obstacles_free = if rooted {
                capsule_is_free_beyond(obstacles, start, end, sweep, clearance)
            } else {
                capsule_is_free(obstacles, start, end, sweep)
            };
            obstacles_free && capsule_is_free_beyond(grid, start, end, sweep, clearance)
        };
        let mut heading = ap.frame.heading();
        if !free(grid, heading) {
            let found = (0..self.options.retries).find_map(|k| {
                let h =
                    mix(self.options.seed
                        ^ mix(stats.segments ^ (u64::from(k) << 40) ^ tree as u64));
                let candidate = deflect(heading, cone, unit_f32(h), unit_f32(mix(h)));
                free(grid, candidate).then_some(candidate)
            });
            match found {
                Some(h) => {
                    let turn = Quat::from_rotation_arc(heading, h);
                    ap.frame.rotation = (turn * ap.frame.rotation).normalize();
                    heading = h;
                    stats.deflected += 1;
                }
                None => {
                    stats.aborted += 1;
                    abort_subtree(apices, a);
                    return;
                }
            }
        }
        let ap = &mut apices[a];
        let end = start + heading * length;
        voxelise_capsule(grid, start, end, sweep);
        let id = grown[tree].segments.len() as u32;
        grown[tree].segments.push(GrownSegment {
            frame: ap.frame,
            length,
            start_radius,
            end_radius: radius,
            depth,
            parent: ap.last,
            continues_parent: ap.same_axis && ap.last.is_some(),
            shed: false,
        });
        ap.frame.position = end;
        ap.last = Some(id);
        ap.same_axis = true;
        stats.segments += 1;
    }
}

/// The light at `point`, counted in `stats`.
fn sample(sky: &Sky, grid: &VoxelGrid, point: Vec3, stats: &mut GrowthStats) -> Light {
    let light = sky.light_at(grid, point);
    stats.samples += 1;
    stats.ray_steps += light.steps;
    light
}

/// Where a branch senses light: the bud sits inside its own wood's voxels, so it looks out
/// from just beyond them along its heading.
fn bud(apex: &Apex, spec: &TreeSpec, grid: &VoxelGrid) -> Vec3 {
    let radius = (apex.width * 0.5).max(spec.turtle.min_radius);
    let reach = radius + grid.voxel_size() * 0.5 * 3f32.sqrt();
    apex.frame.position + apex.frame.heading() * (reach + grid.voxel_size())
}

/// The direction light comes from at `point`: the mean escaping ray, or where that mean
/// points into an occluder (an overhang above a gap, the paper's figure 3), the escaping
/// sky ray nearest to it. `None` in full darkness.
fn light_direction(grid: &VoxelGrid, sky: &Sky, point: Vec3, light: &Light) -> Option<Vec3> {
    let mean = light.towards.try_normalize()?;
    if march(grid, point, mean, true).escaped {
        return Some(mean);
    }
    sky.hemisphere
        .iter()
        .chain(&sky.sun)
        .copied()
        .filter(|&d| march(grid, point, d, true).escaped)
        .max_by(|a, b| a.dot(mean).total_cmp(&b.dot(mean)))
}

/// A direction within `cone` radians of `heading`, uniform over the cone's solid angle,
/// from two uniform numbers.
fn deflect(heading: Vec3, cone: f32, u: f32, v: f32) -> Vec3 {
    let cos_max = cone.cos();
    let cos_t = 1.0 - u * (1.0 - cos_max);
    let sin_t = (1.0 - cos_t * cos_t).max(0.0).sqrt();
    let phi = v * std::f32::consts::TAU;
    let (a, b) = heading.any_orthonormal_pair();
    (heading * cos_t + (a * phi.cos() + b * phi.sin()) * sin_t).normalize()
}

/// Stops apex `a` and every apex it spawned, directly or not.
fn abort_subtree(apices: &mut [Apex], a: usize) {
    apices[a].alive = false;
    // Children always come after their parents in the list.
    let mut dead = vec![false; apices.len()];
    dead[a] = true;
    for i in a + 1..apices.len() {
        if let Some(p) = apices[i].parent
            && dead[p]
        {
            dead[i] = true;
            apices[i].alive = false;
        }
    }
}

/// Fraction of free voxels in the cube of half side `radius` around `point`.
fn free_space(grid: &VoxelGrid, point: Vec3, radius: f32) -> f32 {
    let v = grid.voxel_size();
    let r = (radius / v).ceil().clamp(0.0, 16.0) as i32;
    let centre = grid.cell_coords(point);
    let (mut free, mut total) = (0u32, 0u32);
    for z in -r..=r {
        for y in -r..=r {
            for x in -r..=r {
                let c = centre + glam::IVec3::new(x, y, z);
                total += 1;
                if !grid.contains(c) || !grid.is_occupied(c.as_uvec3()) {
                    free += 1;
                }
            }
        }
    }
    free as f32 / total.max(1) as f32
}
