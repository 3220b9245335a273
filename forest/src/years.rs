//! A year of a forest over time drawn by a builder: living trees at the form their height
//! asks for, dead, broken and fallen ones in their damaged forms.

use sylva_base::hash::{mix, unit_f32};
use sylva_instancing::CompactTree;
use sylva_terrain::HeightField;

use crate::density::Rect;
use crate::forest::ForestBuilder;
use crate::succession::{Snapshot, State};

impl ForestBuilder {
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
        let (lo, hi) = terrain.bounds();
        let region = region.intersect(&Rect::new(lo, hi));
        let c = &self.config().constraints;
        let min_up = c.max_slope_degrees.clamp(0.0, 90.0).to_radians().cos();
        snapshot
            .trees_in(region)
            .filter_map(|t| {
                let species = usize::from(t.species);
                let [x, z] = t.position;
                let height = terrain.height(x, z);
                if !(height >= c.min_height && height <= c.max_height)
                    || terrain.normal(x, z).y < min_up - 1e-6
                {
                    return None;
                }
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
            .collect()
    }
}
