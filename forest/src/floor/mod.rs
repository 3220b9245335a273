//! The forest floor: grass, ferns, low shrubs, fallen branches and rocks, grown by the same
//! patch model as the trees. Where the canopy trees stand decides how much light reaches the
//! ground, and each kind of cover answers the light its own way ([`GroundKind::light_response`]):
//! grass and shrubs fill the gaps, ferns the half shade, fallen branches gather under crowns.
//! Species may name their own cover (`ground_cover:` in species files): the ground near a
//! canopy tree grows its species' mix.
//!
//! Items are a pure function of the seed and where they stand: the floor is cut into cells
//! of [`FloorOptions::cell`] metres, each drawing its items from a hash of its coordinates,
//! so regions generated apart join without seams.

mod mesh;

use glam::Vec2;
use sylva_base::hash::{mix, unit_f32};
use sylva_instancing::CompactTree;
use sylva_terrain::HeightField;

use crate::density::Rect;
use crate::error::ForestError;
use crate::forest::ForestBuilder;

use crate::ground::{GroundCover, GroundKind};

/// Most floor items one call may generate, counted before generating as the most its cells
/// could hold (an item is 36 bytes): ask for smaller regions, which join without seams.
pub const MAX_FLOOR_ITEMS: u64 = 20_000_000;

/// Most items one cell may hold, whatever the densities say.
const MAX_ITEMS_PER_CELL: u32 = 64;

/// How the floor is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct FloorOptions {
    /// The floor's seed (items differ from the trees' even under one world seed).
    /// Default: 0x0f1e_2d3c.
    pub seed: u64,
    /// Side of the cells items are drawn in, metres (0.5 to 50). Default: 2.
    pub cell: f32,
    /// Items' scales are uniform in `1 +- scale_variation`. Default: 0.3.
    pub scale_variation: f32,
}

impl Default for FloorOptions {
    fn default() -> Self {
        FloorOptions {
            seed: 0x0f1e_2d3c,
            cell: 2.0,
            scale_variation: 0.3,
        }
    }
}

impl FloorOptions {
    /// Sets [`FloorOptions::seed`].
    #[must_use]
    pub fn with_seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }

    /// Sets [`FloorOptions::cell`].
    #[must_use]
    pub fn with_cell(mut self, cell: f32) -> Self {
        self.cell = cell;
        self
    }

    /// Sets [`FloorOptions::scale_variation`].
    #[must_use]
    pub fn with_scale_variation(mut self, scale_variation: f32) -> Self {
        self.scale_variation = scale_variation;
        self
    }
}

/// One item of ground cover where it stands.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FloorItem {
    /// What it is.
    pub kind: GroundKind,
    /// Where it stands (on the terrain).
    pub position: [f32; 3],
    /// Its turn about +Y, radians.
    pub yaw: f32,
    /// Its scale.
    pub scale: f32,
    /// A phase in `[0, 1)` for its sway.
    pub phase: f32,
}

/// The ground cover of a forest: its mixes, and where its canopy trees shade the ground.
#[derive(Debug, Clone)]
pub struct ForestFloor {
    options: FloorOptions,
    /// Densities by kind (in [`GroundKind::ALL`]'s order) where no species names its own.
    default_mix: [f32; 5],
    /// Per species of the forest: its mix.
    species_mix: Vec<[f32; 5]>,
    /// Per variant: its species, and the radius of its crown (0 for seedlings, which shade
    /// little).
    variants: Vec<(usize, f32)>,
    /// The widest crown radius.
    reach: f32,
}

/// A mix by kind from cover entries (later entries of a kind replace earlier ones).
fn mix_of(cover: &[GroundCover]) -> [f32; 5] {
    let mut out = [0.0; 5];
    for c in cover {
        if let Some(k) = GroundKind::ALL.iter().position(|&k| k == c.kind) {
            out[k] = c.density.max(0.0);
        }
    }
    out
}

impl ForestFloor {
    /// The floor of `builder`'s forest: each species' cover (its `ground_cover`, or the
    /// default mix), and its canopy trees' crowns.
    ///
    /// ```
    /// use sylva_forest::{FloorOptions, ForestBuilder, ForestConfig, ForestFloor, GroundKind, Rect, Species};
    /// use sylva_terrain::{FlatPlane, glam::Vec2};
    /// let config = ForestConfig::new(vec![Species::from_preset("sylva-hazel", 3)?])
    ///     .with_budget(1 << 20);
    /// let builder = ForestBuilder::new(config)?;
    /// let floor = ForestFloor::of(&builder, FloorOptions::default());
    /// let ground = FlatPlane { height: 0.0, min: Vec2::splat(-40.0), max: Vec2::splat(40.0) };
    /// let region = Rect::new(Vec2::ZERO, Vec2::splat(20.0));
    /// let trees = builder.trees(&ground, region.expanded(floor.reach()));
    /// let items = floor.items(&ground, region, &trees)?;
    /// assert!(items.iter().any(|i| i.kind == GroundKind::Grass));
    /// // The same region gives the same items.
    /// assert_eq!(items, floor.items(&ground, region, &trees)?);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn of(builder: &ForestBuilder, options: FloorOptions) -> ForestFloor {
        let default_mix = GroundKind::ALL.map(GroundKind::default_density);
        let species = &builder.config().species;
        let species_mix = species
            .iter()
            .map(|s| {
                if s.ground_cover.is_empty() {
                    default_mix
                } else {
                    mix_of(&s.ground_cover)
                }
            })
            .collect();
        let canopies = builder.canopies();
        let variants: Vec<(usize, f32)> = builder
            .variants()
            .iter()
            .map(|v| {
                let radius = if v.seedling {
                    0.0
                } else {
                    canopies.get(v.species).map_or(0.0, |c| 0.5 * c.diameter())
                };
                (v.species, radius)
            })
            .collect();
        let reach = variants.iter().map(|v| v.1).fold(0.0f32, f32::max)
            * (1.0 + builder.config().scale_variation.max(0.0));
        ForestFloor {
            options,
            default_mix,
            species_mix,
            variants,
            reach,
        }
    }

    /// How far a canopy tree's crown reaches: pass [`ForestFloor::items`] the trees of the
    /// region grown by this.
    pub fn reach(&self) -> f32 {
        self.reach
    }

    /// The cover at `at` (0: open sky; 1 and more: closed canopy) and the species whose crown
    /// shades it most, from `trees` bucketed in `grid`.
    fn shade(
        &self,
        at: Vec2,
        trees: &[CompactTree],
        (grid, near): (&TreeGrid, &mut Vec<u32>),
    ) -> (f32, Option<usize>) {
        let (mut cover, mut strongest, mut species) = (0.0f32, 0.0f32, None);
        grid.near(at, near);
        for &i in near.iter() {
            let t = &trees[i as usize];
            let Some(&(s, radius)) = self.variants.get(usize::from(t.variant)) else {
                continue;
            };
            let r = radius * t.scale;
            if r <= 0.0 {
                continue;
            }
            let d = at.distance(Vec2::new(t.position[0], t.position[2])) / r;
            if d < 1.0 {
                let w = 1.0 - d * d;
                cover += w;
                if w > strongest {
                    (strongest, species) = (w, Some(s));
                }
            }
        }
        (cover.min(1.0), species)
    }

    /// The items of `region` on `terrain`, under `trees` (the forest's trees of the region
    /// grown by [`ForestFloor::reach`]; trees elsewhere are passed over): a pure function of
    /// the options, the trees and where each cell is. An error when the region's cells could
    /// hold more than [`MAX_FLOOR_ITEMS`] items.
    pub fn items(
        &self,
        terrain: &dyn HeightField,
        region: Rect,
        trees: &[CompactTree],
    ) -> Result<Vec<FloorItem>, ForestError> {
        let cell = self.options.cell.clamp(0.5, 50.0);
        if region.is_empty() {
            return Ok(Vec::new());
        }
        let (columns, rows) = region.cells(cell);
        let cells = columns.clone().count() as u64 * rows.clone().count() as u64;
        // The most a cell can hold: each kind at its densest mix and full response, capped.
        let per_cell: u64 = (0..GroundKind::ALL.len())
            .map(|k| {
                let densest = self
                    .species_mix
                    .iter()
                    .chain(std::iter::once(&self.default_mix))
                    .map(|m| m[k])
                    .fold(0.0f32, f32::max);
                ((densest * cell * cell).ceil() as u64).min(u64::from(MAX_ITEMS_PER_CELL))
            })
            .sum();
        let most = cells.saturating_mul(per_cell);
        if most > MAX_FLOOR_ITEMS {
            return Err(ForestError::FloorTooLarge {
                items: most,
                limit: MAX_FLOOR_ITEMS,
            });
        }
        let grid = TreeGrid::new(trees, self.reach.max(1.0));
        let mut near = Vec::new();
        let (lo, hi) = terrain.bounds();
        let variation = self.options.scale_variation.clamp(0.0, 0.9);
        let mut out = Vec::new();
        for cz in rows {
            for cx in columns.clone() {
                let cell_hash = mix(self.options.seed
                    ^ mix((cx as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15)
                        ^ (cz as u64).wrapping_mul(0xc2b2_ae3d_27d4_eb4f)));
                let centre = Vec2::new((cx as f32 + 0.5) * cell, (cz as f32 + 0.5) * cell);
                let (cover, species) = self.shade(centre, trees, (&grid, &mut near));
                let densities = species
                    .and_then(|s| self.species_mix.get(s))
                    .unwrap_or(&self.default_mix);
                let mut draw = 0u64;
                let mut next = || {
                    draw += 1;
                    unit_f32(mix(
                        cell_hash.wrapping_add(draw.wrapping_mul(0x632b_e59b_d9b4_e019))
                    ))
                };
                for (k, kind) in GroundKind::ALL.into_iter().enumerate() {
                    let expected = densities[k] * kind.light_response(cover) * cell * cell;
                    let whole = expected.floor();
                    let count = (whole as u32 + u32::from(next() < expected - whole))
                        .min(MAX_ITEMS_PER_CELL);
                    for _ in 0..count {
                        let p = Vec2::new(cx as f32 + next(), cz as f32 + next()) * cell;
                        let (yaw, scale, phase) = (
                            next() * std::f32::consts::TAU,
                            1.0 + variation * (2.0 * next() - 1.0),
                            next().min(0.999),
                        );
                        // Only items inside the region (cells overhang it) and the terrain.
                        if !region.contains(p) || p.cmplt(lo).any() || p.cmpgt(hi).any() {
                            continue;
                        }
                        out.push(FloorItem {
                            kind,
                            position: [p.x, terrain.height(p.x, p.y), p.y],
                            yaw,
                            scale,
                            phase,
                        });
                    }
                }
            }
        }
        Ok(out)
    }
}

/// Trees bucketed in square cells of a side at least the widest crown's radius, so the trees
/// that can shade a point are in the 3 x 3 cells around it.
struct TreeGrid {
    side: f32,
    origin: Vec2,
    columns: i64,
    rows: i64,
    /// Tree indices by cell, and where each cell's run starts.
    order: Vec<u32>,
    starts: Vec<u32>,
}

impl TreeGrid {
    fn new(trees: &[CompactTree], side: f32) -> TreeGrid {
        let at = |t: &CompactTree| Vec2::new(t.position[0], t.position[2]);
        let (mut lo, mut hi) = (Vec2::splat(f32::INFINITY), Vec2::splat(f32::NEG_INFINITY));
        for t in trees {
            lo = lo.min(at(t));
            hi = hi.max(at(t));
        }
        if trees.is_empty() {
            (lo, hi) = (Vec2::ZERO, Vec2::ZERO);
        }
        // A bounded grid however far apart the trees stand.
        let side = side.max((hi - lo).max_element() / 4096.0).max(1e-3);
        let columns = ((hi.x - lo.x) / side).floor() as i64 + 1;
        let rows = ((hi.y - lo.y) / side).floor() as i64 + 1;
        let cell_of = |p: Vec2| {
            let c = ((p - lo) / side).floor();
            (c.y as i64).clamp(0, rows - 1) * columns + (c.x as i64).clamp(0, columns - 1)
        };
        let mut counts = vec![0u32; (columns * rows) as usize + 1];
        for t in trees {
            counts[cell_of(at(t)) as usize + 1] += 1;
        }
        for k in 1..counts.len() {
            counts[k] += counts[k - 1];
        }
        let mut fill = counts.clone();
        let mut order = vec![0u32; trees.len()];
        for (i, t) in trees.iter().enumerate() {
            let c = cell_of(at(t)) as usize;
            order[fill[c] as usize] = i as u32;
            fill[c] += 1;
        }
        TreeGrid {
            side,
            origin: lo,
            columns,
            rows,
            order,
            starts: counts,
        }
    }

    /// The trees in the 3 x 3 cells around `p`, into `out`.
    fn near(&self, p: Vec2, out: &mut Vec<u32>) {
        out.clear();
        let c = ((p - self.origin) / self.side).floor();
        let (cx, cz) = (c.x as i64, c.y as i64);
        for z in (cz - 1).max(0)..=(cz + 1).min(self.rows - 1) {
            for x in (cx - 1).max(0)..=(cx + 1).min(self.columns - 1) {
                let k = (z * self.columns + x) as usize;
                let (a, b) = (self.starts[k] as usize, self.starts[k + 1] as usize);
                out.extend_from_slice(&self.order[a..b]);
            }
        }
    }
}
