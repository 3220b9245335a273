//! Trees kept between a writer's two passes. Placing a block's trees on the terrain is most of
//! what streaming a forest costs; the counting pass places them once and spills them to a
//! scratch file beside the destination, and the writing pass reads them back instead of
//! placing them again. Memory holds an index entry per block, however many trees there are.

use std::fs::File;
use std::io::{Read, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use sylva_base::file::FileError;
use sylva_instancing::CompactTree;

/// The name of a writer's scratch file `tag` beside `destination`: hidden, so that folders
/// checked for foreign files (a tileset's) take it for their own; unique to the process and
/// the call, so that two runs writing one path never share one (they did: the first failed);
/// removed by its owner, or by a later run once its owner is gone
/// ([`sylva_base::file::sweep_abandoned`]).
pub(crate) fn scratch_beside(destination: &Path, tag: &str) -> PathBuf {
    sylva_base::file::scratch_beside(destination, &format!("sylva-scratch-{tag}"))
}

/// The scratch file and where each block's trees are in it.
#[derive(Debug)]
struct Spilled {
    file: File,
    /// Bytes written so far: the next block goes here.
    end: u64,
    /// Per block, (offset, trees), once kept.
    at: Vec<Option<(u64, usize)>>,
}

/// Blocks' trees in a scratch file beside a destination; the file is removed when this is
/// dropped, whatever happened.
#[derive(Debug)]
pub(crate) struct TreeSpill {
    path: PathBuf,
    spilled: Mutex<Spilled>,
}

impl TreeSpill {
    /// A spill beside `destination` for `blocks` blocks.
    pub(crate) fn create(destination: &Path, blocks: usize) -> Result<TreeSpill, FileError> {
        let path = scratch_beside(destination, "trees");
        let file = File::options()
            .read(true)
            .write(true)
            .create(true)
            .truncate(true)
            .open(&path)
            // Named by the file the user asked for: the scratch file is ours.
            .map_err(FileError::at(destination))?;
        Ok(TreeSpill {
            path,
            spilled: Mutex::new(Spilled {
                file,
                end: 0,
                at: vec![None; blocks],
            }),
        })
    }

    fn lock(&self) -> Result<std::sync::MutexGuard<'_, Spilled>, FileError> {
        self.spilled.lock().map_err(|_| {
            FileError::new(
                &self.path,
                std::io::Error::other("a thread failed while holding the spill"),
            )
        })
    }

    /// Keeps `trees` as block `block`'s.
    pub(crate) fn keep(&self, block: usize, trees: &[CompactTree]) -> Result<(), FileError> {
        let at = FileError::at(&self.path);
        let mut s = self.lock()?;
        let offset = s.end;
        s.file.seek(SeekFrom::Start(offset)).map_err(&at)?;
        s.file.write_all(bytemuck::cast_slice(trees)).map_err(&at)?;
        s.end += size_of_val(trees) as u64;
        if let Some(slot) = s.at.get_mut(block) {
            *slot = Some((offset, trees.len()));
        }
        Ok(())
    }

    /// Block `block`'s trees as kept, or `None` if they were not.
    pub(crate) fn trees(&self, block: usize) -> Result<Option<Vec<CompactTree>>, FileError> {
        let at = FileError::at(&self.path);
        let mut s = self.lock()?;
        let Some(Some((offset, count))) = s.at.get(block).copied() else {
            return Ok(None);
        };
        let mut trees = vec![CompactTree::default(); count];
        s.file.seek(SeekFrom::Start(offset)).map_err(&at)?;
        s.file
            .read_exact(bytemuck::cast_slice_mut(&mut trees))
            .map_err(at)?;
        Ok(Some(trees))
    }
}

impl Drop for TreeSpill {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.path);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kept_trees_come_back_as_they_were_in_any_order() {
        let dir = std::env::temp_dir().join(format!("sylva-spill-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let destination = dir.join("forest.glb");
        let tree = |seed: u32| CompactTree {
            seed,
            scale: 1.5,
            position: [seed as f32, 2.0, 3.0],
            ..CompactTree::default()
        };
        let spill = TreeSpill::create(&destination, 3).unwrap();
        spill.keep(2, &[tree(7), tree(8)]).unwrap();
        spill.keep(0, &[tree(1)]).unwrap();
        assert_eq!(spill.trees(0).unwrap(), Some(vec![tree(1)]));
        assert_eq!(spill.trees(2).unwrap(), Some(vec![tree(7), tree(8)]));
        assert_eq!(spill.trees(1).unwrap(), None, "never kept");
        assert_eq!(spill.trees(9).unwrap(), None, "no such block");
        let scratch = spill.path.clone();
        assert!(scratch.exists());
        drop(spill);
        assert!(!scratch.exists(), "the scratch file is removed");
        std::fs::remove_dir_all(&dir).ok();
    }
}
