//! A forest's trees and placements gathered block by block into columns, each handed to
//! NumPy as an array without a copy.

use pyo3::prelude::*;
use pyo3::types::PyDict;
use sylva::forest::{PlacementBlock, Variant};

use crate::arrays::{column, dict, rows};

/// Trees as columns.
#[derive(Debug, Default)]
pub(crate) struct TreeColumns {
    pub(crate) position: Vec<[f32; 3]>,
    yaw: Vec<f32>,
    scale: Vec<f32>,
    variant: Vec<u16>,
    species: Vec<u16>,
    seed: Vec<u32>,
}

impl TreeColumns {
    /// Adds `block`'s trees; their species from `variants`.
    pub(crate) fn extend(&mut self, block: &PlacementBlock, variants: &[Variant]) {
        for t in &block.trees {
            self.position.push(t.position);
            self.yaw.push(t.yaw);
            self.scale.push(t.scale);
            self.variant.push(t.variant);
            let species = variants
                .get(usize::from(t.variant))
                .map_or(0, |v| v.species);
            self.species.push(species as u16);
            self.seed.push(t.seed);
        }
    }

    /// The columns as a dict of arrays.
    pub(crate) fn into_dict(self, py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
        dict(
            py,
            [
                ("position", rows(py, self.position)?.into_any()),
                ("yaw", column(py, self.yaw).into_any()),
                ("scale", column(py, self.scale).into_any()),
                ("variant", column(py, self.variant).into_any()),
                ("species", column(py, self.species).into_any()),
                ("seed", column(py, self.seed).into_any()),
            ],
        )
    }
}

/// Placements as columns; `tree` counts trees across blocks.
#[derive(Debug, Default)]
pub(crate) struct PlacementColumns {
    /// Per variant and instance, whether it has geometry: placements of instances without
    /// any are drawn by nobody, and left out as the files leave them out.
    drawn: Vec<Vec<bool>>,
    pub(crate) position: Vec<[f32; 3]>,
    rotation: Vec<[f32; 4]>,
    scale: Vec<f32>,
    variant: Vec<u32>,
    instance: Vec<u32>,
    tree: Vec<u32>,
    trees_before: u32,
}

impl PlacementColumns {
    /// Empty columns for placements of `variants`' instances.
    pub(crate) fn drawing(variants: &[Variant]) -> PlacementColumns {
        PlacementColumns {
            drawn: variants
                .iter()
                .map(|v| v.cache.instances.iter().map(|i| i.has_geometry()).collect())
                .collect(),
            ..PlacementColumns::default()
        }
    }

    /// Adds `block`'s placements of instances with geometry.
    pub(crate) fn extend(&mut self, block: &PlacementBlock) {
        for p in &block.placements {
            let has_geometry = self
                .drawn
                .get(p.variant as usize)
                .and_then(|v| v.get(p.instance as usize))
                .copied()
                .unwrap_or(false);
            if !has_geometry {
                continue;
            }
            let x = &p.transform;
            self.position.push(x.translation.to_array());
            self.rotation.push(x.rotation.to_array());
            self.scale.push(x.scale);
            self.variant.push(p.variant);
            self.instance.push(p.instance);
            self.tree.push(self.trees_before + p.tree);
        }
        self.trees_before += block.trees.len() as u32;
    }

    /// The columns as a dict of arrays.
    pub(crate) fn into_dict(self, py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
        dict(
            py,
            [
                ("position", rows(py, self.position)?.into_any()),
                ("rotation", rows(py, self.rotation)?.into_any()),
                ("scale", column(py, self.scale).into_any()),
                ("variant", column(py, self.variant).into_any()),
                ("instance", column(py, self.instance).into_any()),
                ("tree", column(py, self.tree).into_any()),
            ],
        )
    }
}
