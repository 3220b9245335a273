//! A forest file's cells: its trees grouped by where they stand, in square cells, so that an
//! engine culls a cell's instanced nodes by their bounds instead of drawing nodes that span
//! the whole forest. A tree belongs to the cell its root stands in, with all its
//! placements; seedlings, which are many small prototypes and are drawn only near the eye,
//! go in cells [`SEEDLING_CELL_FACTOR`] times as wide, which keeps the file's node count
//! (a seedling cell holds most of a cache's hundreds of prototypes) in bounds.

use glam::Vec2;
use sylva_forest::{ForestBuilder, Rect, StreamStats, Variant};
use sylva_instancing::CompactTree;
use sylva_terrain::HeightField;

use crate::census::Node;
use crate::error::ExportError;
use crate::spill::TreeSpill;

/// Default side of a cell, metres ([`GltfOptions::cell_size`](super::GltfOptions::cell_size)).
pub const CELL_SIZE: f32 = 64.0;

/// Most cells along either side of a forest: a larger forest gets wider cells, so that a
/// file's node count (about a hundred canopy prototypes a cell) stays in bounds.
pub const MAX_CELLS_PER_SIDE: u32 = 32;

/// How many canopy cells wide a seedling cell is.
pub const SEEDLING_CELL_FACTOR: u32 = 8;

/// One of the two grids of cells: its side, columns and rows.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Grid {
    side: f32,
    columns: u32,
    rows: u32,
}

impl Grid {
    fn over(size: Vec2, side: f32) -> Grid {
        let n = |extent: f32| ((extent / side).ceil() as u32).max(1);
        Grid {
            side,
            columns: n(size.x),
            rows: n(size.y),
        }
    }

    fn count(&self) -> u32 {
        self.columns * self.rows
    }

    /// The cell of a point `d` from the grid's origin, clamped to the grid.
    fn cell_at(&self, d: Vec2) -> u32 {
        let at = |x: f32, n: u32| ((x / self.side).floor().max(0.0) as u32).min(n - 1);
        at(d.y, self.rows) * self.columns + at(d.x, self.columns)
    }
}

/// Where a forest's cells are: canopy cells first (row by row from the region's low corner),
/// then seedling cells. A cell's number is its bin in the counts and its group in the file.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct CellGrid {
    origin: Vec2,
    canopy: Grid,
    seedling: Grid,
    /// Whether there are cells at all: without, every tree is in cell 0.
    split: bool,
}

/// A cell's place: its number, column, row, rectangle and whether it holds seedlings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Cell {
    pub(crate) column: u32,
    pub(crate) row: u32,
    pub(crate) rect: Rect,
    pub(crate) seedlings: bool,
}

impl CellGrid {
    /// Cells of about `size` metres over `region` (wider where the region would need more
    /// than [`MAX_CELLS_PER_SIDE`] along a side); `None`: one cell holding everything.
    pub(crate) fn new(region: Rect, size: Option<f32>) -> CellGrid {
        let extent = (region.max - region.min).max(Vec2::splat(1e-3));
        let whole = Grid {
            side: extent.max_element(),
            columns: 1,
            rows: 1,
        };
        let Some(size) = size.filter(|s| s.is_finite() && *s > 0.0) else {
            return CellGrid {
                origin: region.min,
                canopy: whole,
                seedling: whole,
                split: false,
            };
        };
        let side = size.max(extent.max_element() / MAX_CELLS_PER_SIDE as f32);
        CellGrid {
            origin: region.min,
            canopy: Grid::over(extent, side),
            seedling: Grid::over(extent, side * SEEDLING_CELL_FACTOR as f32),
            split: true,
        }
    }

    /// The side of a canopy cell, metres.
    pub(crate) fn side(&self) -> f32 {
        self.canopy.side
    }

    /// Cells in all (canopy and seedling).
    pub(crate) fn count(&self) -> u32 {
        if self.split {
            self.canopy.count() + self.seedling.count()
        } else {
            1
        }
    }

    /// The cell of a tree of a variant that is (`seedling`) or is not a seedling form.
    pub(crate) fn cell_of(&self, tree: &CompactTree, seedling: bool) -> u32 {
        if !self.split {
            return 0;
        }
        let d = Vec2::new(tree.position[0], tree.position[2]) - self.origin;
        if seedling {
            self.canopy.count() + self.seedling.cell_at(d)
        } else {
            self.canopy.cell_at(d)
        }
    }

    /// Where cell `cell` is.
    pub(crate) fn cell(&self, cell: u32) -> Cell {
        let (grid, k, seedlings) = if cell < self.canopy.count() || !self.split {
            (&self.canopy, cell, false)
        } else {
            (&self.seedling, cell - self.canopy.count(), true)
        };
        let (column, row) = (k % grid.columns, k / grid.columns);
        let min = self.origin + Vec2::new(column as f32, row as f32) * grid.side;
        Cell {
            column,
            row,
            rect: Rect::new(min, min + Vec2::splat(grid.side)),
            seedlings,
        }
    }
}

/// The nodes of a forest in cells, and how a placement finds its node.
pub(crate) struct CellNodes {
    /// Nodes in file order: by cell, then variant, then instance, each variant's impostor
    /// (when it has one) after its instances.
    pub(crate) nodes: Vec<Node>,
    /// Per cell, its place in `table` (`u32::MAX`: a cell without trees).
    slot_of_cell: Vec<u32>,
    /// Per cell slot, variant and instance, its node (`u32::MAX`: none); each variant's
    /// last entry is its impostor's node.
    table: Vec<Vec<Vec<u32>>>,
    /// Placements (impostors' included) in all.
    pub(crate) placements: usize,
    /// Placements of instances (impostors not included).
    pub(crate) instance_placements: usize,
    /// Placements of instances with no geometry, left out.
    pub(crate) empty_placements: usize,
    /// Branch triangles the instance placements draw at full detail.
    pub(crate) triangles: u64,
    /// What the counting pass streamed.
    pub(crate) stats: StreamStats,
    /// Per variant, whether it is a seedling form and its instance count.
    variants: Vec<(bool, usize)>,
    /// The cells.
    grid: CellGrid,
}

impl CellNodes {
    /// Counts the forest of `region` by cell (its trees kept in `spill` for the writing
    /// pass) and lays its nodes out: a node per cell and instance placed there with
    /// geometry, and per cell and variant with `impostor[variant]` a node of one placement
    /// per tree.
    pub(crate) fn count(
        builder: &ForestBuilder,
        (terrain, region): (&(dyn HeightField + Sync), Rect),
        grid: &CellGrid,
        impostor: &[bool],
        spill: &TreeSpill,
    ) -> Result<CellNodes, ExportError> {
        let variants = builder.variants();
        let seedling: Vec<bool> = variants.iter().map(|v| v.seedling).collect();
        let bin_of = |t: &CompactTree| {
            let s = seedling
                .get(usize::from(t.variant))
                .copied()
                .unwrap_or(false);
            grid.cell_of(t, s)
        };
        let keep = |block: usize, trees: &[CompactTree]| -> Result<(), ExportError> {
            Ok(spill.keep(block, trees)?)
        };
        let counted = builder.count_instances_binned(terrain, region, &bin_of, &keep)?;
        let mut out = CellNodes {
            nodes: Vec::new(),
            slot_of_cell: vec![u32::MAX; grid.count() as usize],
            table: Vec::with_capacity(counted.bins.len()),
            placements: 0,
            instance_placements: 0,
            empty_placements: 0,
            triangles: 0,
            stats: counted.stats,
            variants: variants
                .iter()
                .map(|v| (v.seedling, v.cache.instances.len()))
                .collect(),
            grid: *grid,
        };
        for bin in &counted.bins {
            if let Some(slot) = out.slot_of_cell.get_mut(bin.bin as usize) {
                *slot = out.table.len() as u32;
            }
            let mut per_variant = Vec::with_capacity(variants.len());
            for (v, variant) in variants.iter().enumerate() {
                let trees = bin.trees[v] as usize;
                let with_impostor = impostor.get(v).copied().unwrap_or(false);
                per_variant.push(out.lay_out_variant(
                    (bin.bin, v, variant),
                    &bin.counts[v],
                    (trees > 0 && with_impostor).then_some(trees),
                ));
            }
            out.table.push(per_variant);
        }
        Ok(out)
    }

    /// Nodes of one variant in one cell: one per instance placed with geometry, then the
    /// impostor's of `impostor_trees` placements; returns the instances' nodes and, last,
    /// the impostor's.
    fn lay_out_variant(
        &mut self,
        (cell, v, variant): (u32, usize, &Variant),
        counts: &[u32],
        impostor_trees: Option<usize>,
    ) -> Vec<u32> {
        let mut map = vec![u32::MAX; variant.cache.instances.len() + 1];
        for (i, inst) in variant.cache.instances.iter().enumerate() {
            let count = counts.get(i).copied().unwrap_or(0) as usize;
            if count == 0 {
                continue;
            }
            if !inst.has_geometry() {
                self.empty_placements += count;
                continue;
            }
            map[i] = self.push(Node {
                variant: v,
                instance: i,
                first: self.placements,
                count,
                cell,
                impostor: false,
            });
            self.instance_placements += count;
            self.triangles += count as u64 * u64::from((inst.bark.count + inst.leaves.count) / 3);
        }
        if let Some(trees) = impostor_trees {
            let instance = variant.cache.instances.len();
            map[instance] = self.push(Node {
                variant: v,
                instance,
                first: self.placements,
                count: trees,
                cell,
                impostor: true,
            });
        }
        map
    }

    fn push(&mut self, node: Node) -> u32 {
        self.placements += node.count;
        self.nodes.push(node);
        self.nodes.len() as u32 - 1
    }

    /// The cell a tree stands in.
    pub(crate) fn cell_of(&self, tree: &CompactTree) -> u32 {
        let v = usize::from(tree.variant);
        let seedling = self.variants.get(v).is_some_and(|v| v.0);
        self.grid.cell_of(tree, seedling)
    }

    /// The node of variant `variant`'s impostor in cell `cell`.
    pub(crate) fn impostor(&self, cell: u32, variant: usize) -> Option<u32> {
        let instances = self.variants.get(variant)?.1;
        self.node(cell, variant, instances)
    }

    /// The node of instance `instance` of variant `variant` in cell `cell`; the impostor's
    /// when `instance` is the variant's instance count.
    pub(crate) fn node(&self, cell: u32, variant: usize, instance: usize) -> Option<u32> {
        let slot = *self.slot_of_cell.get(cell as usize)?;
        let node = *self.table.get(slot as usize)?.get(variant)?.get(instance)?;
        (node != u32::MAX).then_some(node)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tree(x: f32, z: f32) -> CompactTree {
        CompactTree {
            position: [x, 0.0, z],
            ..CompactTree::default()
        }
    }

    /// Cells tile the region row by row; seedlings go in the wider grid after the canopy's;
    /// points on the far edge fall in the last cell.
    #[test]
    fn trees_fall_in_the_cell_they_stand_in() {
        let grid = CellGrid::new(Rect::new(Vec2::ZERO, Vec2::splat(200.0)), Some(64.0));
        assert_eq!(grid.side(), 64.0);
        // 4 x 4 canopy cells, then 1 seedling cell (512 m wide).
        assert_eq!(grid.count(), 16 + 1);
        assert_eq!(grid.cell_of(&tree(10.0, 10.0), false), 0);
        assert_eq!(grid.cell_of(&tree(70.0, 10.0), false), 1);
        assert_eq!(grid.cell_of(&tree(10.0, 70.0), false), 4);
        assert_eq!(grid.cell_of(&tree(200.0, 200.0), false), 15);
        assert_eq!(grid.cell_of(&tree(199.0, 3.0), true), 16);
        let cell = grid.cell(5);
        assert_eq!((cell.column, cell.row, cell.seedlings), (1, 1, false));
        assert_eq!(cell.rect.min, Vec2::splat(64.0));
        assert!(grid.cell(16).seedlings);
        // Every tree in the region is in the cell whose rectangle holds it.
        for k in 0..40 {
            let (x, z) = (k as f32 * 4.9, 199.0 - k as f32 * 3.7);
            let c = grid.cell(grid.cell_of(&tree(x, z), false));
            assert!(
                c.rect.min.x <= x && x <= c.rect.max.x && c.rect.min.y <= z && z <= c.rect.max.y
            );
        }
    }

    proptest::proptest! {
        /// Any tree in any region falls in a cell of its grid whose rectangle holds it, and
        /// the cells' numbers stay below the count.
        #[test]
        fn every_tree_is_in_the_cell_that_holds_it(
            side in 20.0f32..3000.0,
            size in 8.0f32..300.0,
            (u, v) in (0.0f32..=1.0, 0.0f32..=1.0),
            seedling: bool,
        ) {
            let origin = Vec2::new(-side * 0.3, 17.0);
            let grid = CellGrid::new(Rect::new(origin, origin + Vec2::splat(side)), Some(size));
            let (x, z) = (origin.x + u * side, origin.y + v * side);
            let k = grid.cell_of(&tree(x, z), seedling);
            proptest::prop_assert!(k < grid.count());
            let c = grid.cell(k);
            proptest::prop_assert_eq!(c.seedlings, seedling);
            let slack = 1e-3 * side;
            proptest::prop_assert!(c.rect.min.x - slack <= x && x <= c.rect.max.x + slack);
            proptest::prop_assert!(c.rect.min.y - slack <= z && z <= c.rect.max.y + slack);
        }
    }

    /// A forest too wide for 64 m cells gets wider ones, at most 32 a side; no cells means
    /// one cell.
    #[test]
    fn wide_forests_get_wider_cells() {
        let grid = CellGrid::new(Rect::new(Vec2::ZERO, Vec2::splat(6400.0)), Some(64.0));
        assert_eq!(grid.side(), 200.0);
        assert_eq!(grid.count(), 32 * 32 + 4 * 4);
        let one = CellGrid::new(Rect::new(Vec2::ZERO, Vec2::splat(6400.0)), None);
        assert_eq!(one.count(), 1);
        assert_eq!(one.cell_of(&tree(5000.0, 10.0), true), 0);
    }
}
