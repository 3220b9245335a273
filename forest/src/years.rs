//! A year of a forest over time drawn by a builder: living trees at the form their height
//! asks for, dead, broken and fallen ones in their damaged forms.

use sylva_base::hash::{mix, unit_f32};
use sylva_instancing::CompactTree;
use sylva_terrain::HeightField;

use std::sync::Arc;

use crate::density::Rect;
use crate::error::ForestError;
use crate::forest::ForestBuilder;
use crate::siting_report::SitingReport;
use crate::succession::{Snapshot, State, Succession, SuccessionOptions};

impl ForestBuilder {
    /// A forest over time of this builder's species over `region`, from bare ground, with
    /// the default options and the builder's seed: what `sylva forest --year` and the
    /// viewer's `--year` grow, so both draw the same forest.
    pub fn succession(&self, region: Rect) -> Result<Succession, ForestError> {
        let options = SuccessionOptions::default().with_seed(self.config().seed);
        Succession::new(self.config().species.clone(), region, options)
    }

    /// This builder drawing `forest` as it stands ([`ForestBuilder::with_snapshot`] of its
    /// [`Succession::snapshot`]).
    pub fn drawing(&self, forest: &Succession) -> Result<ForestBuilder, ForestError> {
        self.with_snapshot(Some(Arc::new(forest.snapshot())))
    }

    /// The trees of `snapshot` in `region` on `terrain`, each drawn by the variant of its
    /// species and form at the scale its height asks for (the builder must have every age,
    /// [`ForestConfig::all_ages`](crate::ForestConfig::all_ages)); trees off the terrain or
    /// where its constraints allow none are left out, as in a forest of one age.
    pub fn snapshot_trees(
        &self,
        snapshot: &Snapshot,
        terrain: &dyn HeightField,
        region: Rect,
    ) -> Vec<CompactTree> {
        self.snapshot_trees_sited(snapshot, terrain, region, &mut SitingReport::default())
    }

    /// As [`ForestBuilder::snapshot_trees`], counting each tree's verdict into `report` (the
    /// snapshot's trees are its candidates).
    pub(crate) fn snapshot_trees_sited(
        &self,
        snapshot: &Snapshot,
        terrain: &dyn HeightField,
        region: Rect,
        report: &mut SitingReport,
    ) -> Vec<CompactTree> {
        let (lo, hi) = terrain.bounds();
        let region = region.intersect(&Rect::new(lo, hi));
        let site = self.config().constraints.site(terrain);
        let trees: Vec<CompactTree> = snapshot
            .trees_in(region)
            .filter_map(|t| {
                let species = usize::from(t.species);
                let [x, z] = t.position;
                let sited = site(x, z);
                report.count(sited.map(|_| ()));
                let height = sited.ok()?;
                let (form, scale) = match t.state.damaged_form() {
                    None => self.live_form(species, t.height)?,
                    Some(form) => {
                        let &(_, drawn) = self.form_heights(species).last()?;
                        (form, t.height / drawn)
                    }
                };
                let h = mix(t.key);
                // A fallen tree lies along +X in its cache; turned by -angle about +Y it lies
                // along the way it fell.
                let yaw = if t.state == State::Fallen {
                    -(f32::from(t.fall) / 256.0) * std::f32::consts::TAU
                } else {
                    unit_f32(h) * std::f32::consts::TAU
                };
                Some(CompactTree {
                    position: [x, height, z],
                    yaw,
                    scale,
                    seed: (h >> 32) as u32,
                    variant: self.variant_of(species, form)?,
                    crown_class: 0,
                    crown_classes: 0,
                })
            })
            .collect();
        report.placed += trees.len() as u64;
        trees
    }
}
