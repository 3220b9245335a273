//! The instance cache: one shared vertex and index buffer per species, instances as index
//! ranges with their hero frame and exit points, and an O(1) lookup by (branch id, age).

use sylva_turtle::Vertex;

use crate::similarity::Similarity;
use crate::span::Span;

/// A cached branch instance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Instance {
    /// Branch id (0: a whole tree).
    pub id: u32,
    /// Generation at which the branch was introduced.
    pub age: u32,
    /// Bark triangles: a span of the cache's bark index buffer.
    pub bark: Span,
    /// Leaf triangles: a span of the cache's leaf index buffer.
    pub leaves: Span,
    /// The inverse of the instance's frame M in its hero tree: placing it at a desired frame D
    /// uses T = D * M^-1.
    pub frame_inverse: Similarity,
    /// Its exit points: a span of the cache's exits.
    pub exits: Span,
}

impl Instance {
    /// Whether it draws anything: an instance of no bark and no leaf triangles (a bud, a
    /// branch shed) is placed but left out of files and frames.
    ///
    /// ```
    /// use sylva_instancing::{Instance, Similarity, Span};
    /// let bud = Instance {
    ///     id: 3,
    ///     age: 1,
    ///     bark: Span::new(0, 0),
    ///     leaves: Span::new(0, 0),
    ///     frame_inverse: Similarity::IDENTITY,
    ///     exits: Span::new(0, 0),
    /// };
    /// assert!(!bud.has_geometry());
    /// assert!(Instance { leaves: Span::new(6, 3), ..bud }.has_geometry());
    /// ```
    pub fn has_geometry(&self) -> bool {
        !(self.bark.is_empty() && self.leaves.is_empty())
    }
}

/// An exit point of an instance: where a sub-branch of (id, age) must be attached, as a frame
/// E relative to the instance's own frame (so the sub-branch goes to D * E).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Exit {
    /// Branch id wanted.
    pub id: u32,
    /// Age wanted.
    pub age: u32,
    /// Frame relative to the instance.
    pub frame: Similarity,
}

/// Bytes one instance's metadata costs against the budget.
pub const INSTANCE_BYTES: usize = size_of::<Instance>();
/// Bytes one exit point costs against the budget.
pub const EXIT_BYTES: usize = size_of::<Exit>();
/// Bytes one lookup candidate costs against the budget (its index and its exit count).
pub const CANDIDATE_BYTES: usize = 8;

/// The bit of a key's first `candidate_exits` entry that says it counts the key's whole
/// branches rather than giving an exit count.
const WHOLE_COUNT: u32 = 1 << 31;

/// One key's candidates, as assembly chooses among them.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Candidates<'a> {
    /// Indices into [`InstanceCache::instances`], fewest exits first (stable), so the whole
    /// branches are a prefix.
    pub(crate) indices: &'a [u32],
    /// How many of them are whole branches (no exits).
    pub(crate) whole: usize,
    /// Their exit counts, when none is a whole branch (`whole` 0); otherwise not exit
    /// counts, and not to be read.
    pub(crate) exits: &'a [u32],
}

/// The cache of one species: geometry, instances, exits and the lookup table.
#[derive(Debug, Clone, Default)]
pub struct InstanceCache {
    /// The shared vertex buffer.
    pub vertices: Vec<Vertex>,
    /// The shared bark index buffer.
    pub bark: Vec<u32>,
    /// The shared leaf index buffer.
    pub leaves: Vec<u32>,
    /// All instances.
    pub instances: Vec<Instance>,
    /// All exit points.
    pub exits: Vec<Exit>,
    /// Per (id, age): range into `candidates`; dense, `table[id * ages + age]`.
    table: Vec<Span>,
    candidates: Vec<u32>,
    /// Exit counts of `candidates`, side by side so assembly compares them without touching
    /// the instances; except that where a key's first candidate is a whole branch (no
    /// exits) its entry holds, with [`WHOLE_COUNT`] set, how many of the key's candidates
    /// are whole branches. Assembly then knows them from the one entry it reads, with no
    /// search of a key that mixes whole branches and branches with exits (a binary search
    /// whose every step waited on memory), and the cache is no larger.
    candidate_exits: Vec<u32>,
    ages: u32,
    budget: usize,
}

impl InstanceCache {
    pub(crate) fn new(budget: usize) -> Self {
        InstanceCache {
            budget,
            ..Default::default()
        }
    }

    /// The byte budget the cache was built under.
    pub fn budget(&self) -> usize {
        self.budget
    }

    /// Bytes used: geometry, instance metadata, exits and lookup candidates.
    pub fn bytes(&self) -> usize {
        self.vertices.len() * size_of::<Vertex>()
            + (self.bark.len() + self.leaves.len()) * 4
            + self.instances.len() * INSTANCE_BYTES
            + self.exits.len() * EXIT_BYTES
            + self.candidates.len() * CANDIDATE_BYTES
            + self.table.len() * 8
    }

    /// Candidates for (id, age) in O(1): indices into [`InstanceCache::instances`].
    #[inline]
    pub fn lookup(&self, id: u32, age: u32) -> &[u32] {
        self.candidates_of(id, age).indices
    }

    /// The candidates for (id, age), fewest exits first (stable), with how many are whole
    /// branches.
    #[inline]
    pub(crate) fn candidates_of(&self, id: u32, age: u32) -> Candidates<'_> {
        let span = (age < self.ages)
            .then(|| {
                self.table
                    .get((id as usize) * self.ages as usize + age as usize)
            })
            .flatten();
        let Some(span) = span else {
            return Candidates {
                indices: &[],
                whole: 0,
                exits: &[],
            };
        };
        let exits = &self.candidate_exits[span.range()];
        let whole = match exits.first() {
            Some(&first) if first & WHOLE_COUNT != 0 => (first & !WHOLE_COUNT) as usize,
            _ => 0,
        };
        Candidates {
            indices: &self.candidates[span.range()],
            whole,
            exits,
        }
    }

    /// The exit points of instance `i`.
    #[inline]
    pub fn exits_of(&self, instance: &Instance) -> &[Exit] {
        &self.exits[instance.exits.range()]
    }

    /// Rebuilds the dense lookup table over `ids` ids and `ages` ages (bytes counted).
    pub(crate) fn index(&mut self, ids: u32, ages: u32) {
        let mut lists: Vec<Vec<u32>> = vec![Vec::new(); (ids * ages) as usize];
        for (i, inst) in self.instances.iter().enumerate() {
            if inst.id < ids && inst.age < ages {
                lists[(inst.id * ages + inst.age) as usize].push(i as u32);
            }
        }
        self.candidates.clear();
        self.candidate_exits.clear();
        self.table.clear();
        for mut l in lists {
            // Complete candidates (no exits) first, so assembly finds them as a prefix.
            l.sort_by_key(|&i| self.instances[i as usize].exits.count);
            self.table
                .push(Span::new(self.candidates.len() as u32, l.len() as u32));
            let instances = &self.instances;
            let whole = l.partition_point(|&i| instances[i as usize].exits.count == 0);
            let exits = l.iter().enumerate().map(|(k, &i)| match (k, whole) {
                // The count fits below the flag: a key has fewer candidates than 2^31.
                (0, 1..) => WHOLE_COUNT | whole as u32,
                _ => instances[i as usize].exits.count,
            });
            self.candidate_exits.extend(exits);
            self.candidates.extend(l);
        }
        self.ages = ages;
    }
}

#[cfg(test)]
mod tests {
    use crate::{HeroOptions, build_cache};

    /// Each key knows how many of its candidates are whole branches, and they come first;
    /// a key with none gives its candidates' exit counts. Across these caches there are
    /// keys of every kind: all whole branches, none, and a mix.
    #[test]
    fn each_key_counts_its_whole_branches() {
        let mut kinds = [0usize; 3];
        for (preset, budget) in [("sylva-birch", 256 << 10), ("kenwood-leafy", 2 << 20)] {
            let grammar = sylva_lsys::preset(preset)
                .expect("preset")
                .lsystem()
                .expect("parses");
            let options = HeroOptions::default()
                .with_budget(budget)
                .with_generations(5);
            let cache = build_cache(&grammar, &options).expect("fits").cache;
            let ids = cache.instances.iter().map(|i| i.id + 1).max().unwrap_or(0);
            for id in 0..ids {
                for age in 0..cache.ages {
                    let key = cache.candidates_of(id, age);
                    let exits: Vec<u32> = (key.indices.iter())
                        .map(|&i| cache.instances[i as usize].exits.count)
                        .collect();
                    let whole = exits.iter().filter(|&&e| e == 0).count();
                    assert_eq!(key.whole, whole, "key ({id}, {age}): {exits:?}");
                    assert!(exits[..whole].iter().all(|&e| e == 0), "{exits:?}");
                    if whole == 0 {
                        assert_eq!(key.exits, &exits[..]);
                    }
                    if !exits.is_empty() {
                        kinds[usize::from(whole > 0) + usize::from(whole == exits.len())] += 1;
                    }
                }
            }
        }
        assert!(kinds.iter().all(|&k| k > 0), "none, mixed, all: {kinds:?}");
    }
}
