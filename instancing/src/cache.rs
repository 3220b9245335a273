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
    /// the instances.
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
        self.lookup_with_exits(id, age).0
    }

    /// Candidates for (id, age) and their exit counts, fewest exits first (stable), so the
    /// complete candidates are a prefix.
    #[inline]
    pub(crate) fn lookup_with_exits(&self, id: u32, age: u32) -> (&[u32], &[u32]) {
        if age >= self.ages {
            return (&[], &[]);
        }
        match self
            .table
            .get((id as usize) * self.ages as usize + age as usize)
        {
            Some(span) => (
                &self.candidates[span.range()],
                &self.candidate_exits[span.range()],
            ),
            None => (&[], &[]),
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
            self.candidate_exits
                .extend(l.iter().map(|&i| instances[i as usize].exits.count));
            self.candidates.extend(l);
        }
        self.ages = ages;
    }
}
