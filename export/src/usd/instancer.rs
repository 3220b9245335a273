//! The point instancer's arrays (prototype indices, positions, orientations, scales, and each
//! placement's tree phase for the seasons), made
//! in one streaming pass: each block's placements are spelt as text on the core that placed
//! them and appended to one scratch file per array beside the destination, which the file
//! then takes in order. Memory holds a wave of blocks' text, however many trees there are.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use sylva_base::file::{AtomicFile, FileError};
use sylva_forest::{ForestBuilder, PlacementBlock, Rect, tree_wind};
use sylva_terrain::HeightField;
use sylva_terrain::glam::Vec3;

use super::text::{float, half, tuple};
use crate::census::{check_transform, kept_trees};
use crate::error::{ExportError, Invalid};
use crate::spill::{TreeSpill, scratch_beside};

/// The instancer's arrays, in the order the file holds them, with their USD types. The last
/// is a primvar, one value per instance: the phase of the tree each placement belongs to,
/// which moves the tree's day in the year (`sylva_forest::tree_day`), as glTF's
/// `_WIND_TREE` w does.
pub(super) const ARRAYS: [(&str, &str); 5] = [
    ("int[]", "protoIndices"),
    ("point3f[]", "positions"),
    ("quath[]", "orientations"),
    ("float3[]", "scales"),
    ("float[]", "primvars:sylva:tree_phase"),
];

/// One block's placements as the arrays' text, each element led by a separator (a comma,
/// and a line break every eighth), and the box they reach.
#[derive(Debug, Default)]
struct BlockText {
    arrays: [String; 5],
    lo: Vec3,
    hi: Vec3,
    placements: usize,
}

/// Spells `block`'s placements: those of instances with a prototype (`prototype_of`, per
/// variant and instance, `u32::MAX` for none), each reaching `radius[prototype]` times its
/// scale from its translation.
fn block_text(
    block: PlacementBlock,
    prototype_of: &[Vec<u32>],
    radius: &[f32],
) -> Result<BlockText, Invalid> {
    let mut text = BlockText {
        lo: Vec3::INFINITY,
        hi: Vec3::NEG_INFINITY,
        ..BlockText::default()
    };
    let [ids, positions, orientations, scales, phases] = &mut text.arrays;
    let tree_phases: Vec<f32> = block.trees.iter().map(|t| tree_wind(t)[3]).collect();
    for p in &block.placements {
        let Some(&proto) = prototype_of
            .get(p.variant as usize)
            .and_then(|v| v.get(p.instance as usize))
            .filter(|&&k| k != u32::MAX)
        else {
            continue;
        };
        // usda takes line breaks after a list's commas, not before them.
        let separator = if text.placements.is_multiple_of(8) {
            ",\n"
        } else {
            ", "
        };
        let x = &p.transform;
        check_transform(x)?;
        ids.push_str(separator);
        ids.push_str(&proto.to_string());
        positions.push_str(separator);
        tuple(positions, &x.translation.to_array());
        // USD spells a quaternion real part first.
        let q = x.rotation.normalize();
        orientations.push_str(separator);
        orientations.push('(');
        for (k, c) in [q.w, q.x, q.y, q.z].into_iter().enumerate() {
            if k > 0 {
                orientations.push_str(", ");
            }
            half(orientations, c);
        }
        orientations.push(')');
        scales.push_str(separator);
        tuple(scales, &[x.scale; 3]);
        phases.push_str(separator);
        float(
            phases,
            tree_phases.get(p.tree as usize).copied().unwrap_or(0.5),
        );
        let reach = x.scale * radius.get(proto as usize).copied().unwrap_or(0.0);
        text.lo = text.lo.min(x.translation - reach);
        text.hi = text.hi.max(x.translation + reach);
        text.placements += 1;
    }
    Ok(text)
}

/// A file beside the destination holding one array's text while the forest streams; removed
/// when dropped, whatever happened.
#[derive(Debug)]
struct Scratch {
    path: PathBuf,
    writer: Option<BufWriter<File>>,
}

impl Scratch {
    fn create(destination: &Path, array: &str) -> Result<Scratch, FileError> {
        let path = scratch_beside(destination, array);
        let file = File::create(&path).map_err(FileError::at(&path))?;
        Ok(Scratch {
            writer: Some(BufWriter::with_capacity(1 << 20, file)),
            path,
        })
    }

    fn put(&mut self, text: &str) -> Result<(), FileError> {
        match &mut self.writer {
            Some(w) => w
                .write_all(text.as_bytes())
                .map_err(FileError::at(&self.path)),
            None => Ok(()),
        }
    }

    /// Appends everything written to `out`.
    fn copy_into(&mut self, out: &mut AtomicFile) -> Result<(), ExportError> {
        if let Some(w) = self.writer.take() {
            w.into_inner()
                .map_err(|e| FileError::new(&self.path, e.into_error()))?;
        }
        let mut file = File::open(&self.path).map_err(FileError::at(&self.path))?;
        std::io::copy(&mut file, out).map_err(FileError::at(out.destination()))?;
        Ok(())
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        self.writer = None;
        let _ = std::fs::remove_file(&self.path);
    }
}

/// The instancer's arrays, streamed once into scratch files beside `destination`.
#[derive(Debug)]
pub(super) struct Arrays {
    scratch: Vec<Scratch>,
    /// The box every placed prototype stays within.
    pub(super) extent: [[f32; 3]; 2],
    /// Placements written.
    pub(super) placements: usize,
}

impl Arrays {
    /// Streams the forest of `region` once (its trees as the counting pass kept them in the
    /// spill) and spells every placement of an instance with a prototype.
    pub(super) fn stream(
        builder: &ForestBuilder,
        (terrain, region, spill): (&(dyn HeightField + Sync), Rect, &TreeSpill),
        (prototype_of, radius): (&[Vec<u32>], &[f32]),
        destination: &Path,
    ) -> Result<Arrays, ExportError> {
        let mut scratch = ARRAYS
            .iter()
            .map(|(_, name)| Scratch::create(destination, &name.replace(':', "_")))
            .collect::<Result<Vec<_>, _>>()?;
        let (mut lo, mut hi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
        let mut placements = 0usize;
        let map = |block: PlacementBlock| block_text(block, prototype_of, radius);
        let trees = |block: usize, rect: Rect| kept_trees(builder, terrain, spill, (block, rect));
        builder.stream_map_from(region, &trees, &|_| true, &map, &mut |text| {
            let text = text?;
            if text.placements == 0 {
                return Ok(());
            }
            for (file, array) in scratch.iter_mut().zip(&text.arrays) {
                // Elements are led by separators; the array's first has none.
                let array = match placements {
                    0 => array.trim_start_matches([',', '\n']),
                    _ => array,
                };
                file.put(array)?;
            }
            placements += text.placements;
            (lo, hi) = (lo.min(text.lo), hi.max(text.hi));
            Ok(())
        })?;
        let extent = if placements == 0 {
            [[0.0; 3]; 2]
        } else {
            [lo.to_array(), hi.to_array()]
        };
        Ok(Arrays {
            scratch,
            extent,
            placements,
        })
    }

    /// Writes the arrays, each `{indent}type name = [...]` (a primvar one value per
    /// instance), to `out`; the scratch files are removed.
    pub(super) fn write(mut self, out: &mut AtomicFile, indent: &str) -> Result<(), ExportError> {
        for ((kind, name), scratch) in ARRAYS.iter().zip(&mut self.scratch) {
            out.put(format!("{indent}{kind} {name} = [").as_bytes())?;
            scratch.copy_into(out)?;
            if name.starts_with("primvars:") {
                out.put(
                    format!("] (\n{indent}    interpolation = \"vertex\"\n{indent})\n").as_bytes(),
                )?;
            } else {
                out.put(b"]\n")?;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use sylva_forest::Placement;
    use sylva_instancing::Similarity;
    use sylva_terrain::glam::Quat;

    fn placement(instance: u32, x: f32) -> Placement {
        Placement {
            variant: 0,
            instance,
            transform: Similarity {
                translation: Vec3::new(x, 1.0, 2.0),
                rotation: Quat::from_rotation_y(std::f32::consts::FRAC_PI_2),
                scale: 0.5,
            },
            tree: 0,
        }
    }

    #[test]
    fn a_block_spells_each_placement_with_a_prototype() {
        let block = PlacementBlock {
            index: 0,
            region: Rect::new(Default::default(), Default::default()),
            trees: Vec::new(),
            placements: vec![placement(0, 10.0), placement(1, 20.0), placement(2, 30.0)],
        };
        // Instance 1 has no prototype (no geometry).
        let text = block_text(block, &[vec![4, u32::MAX, 0]], &[2.0, 0.0, 0.0, 0.0, 6.0]).unwrap();
        assert_eq!(text.placements, 2);
        assert_eq!(text.arrays[0], ",\n4, 0");
        assert_eq!(text.arrays[1], ",\n(10, 1, 2), (30, 1, 2)");
        assert_eq!(
            text.arrays[2],
            ",\n(0.7071, 0, 0.7071, 0), (0.7071, 0, 0.7071, 0)"
        );
        assert_eq!(text.arrays[3], ",\n(0.5, 0.5, 0.5), (0.5, 0.5, 0.5)");
        // Prototype 4 reaches 6 x 0.5 from (10, 1, 2); prototype 0 reaches 2 x 0.5 from 30.
        assert_eq!(text.lo, Vec3::new(7.0, -2.0, -1.0));
        assert_eq!(text.hi, Vec3::new(31.0, 4.0, 5.0));
    }
}
