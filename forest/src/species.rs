//! Species: a grammar with its generations, turtle settings, colours and canopy size.

use glam::Vec3;
use sylva_lsys::LSystem;
use sylva_turtle::{Mesh, MeshBuilder, Skeleton, TurtleOptions, interpret};

use crate::appearance::{BarkPattern, LeafShape};
use crate::crown_cover::CrownCover;
use crate::error::ForestError;
use crate::ground::GroundCover;
use crate::life::Life;
use crate::phenology::Phenology;

/// A tree species.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct Species {
    /// Name, for reports and exported node names. No default: the name given to [`Species::new`].
    pub name: String,
    /// The grammar. No default: the grammar given to [`Species::new`].
    pub grammar: LSystem,
    /// Generations of a canopy tree. No default: the generations given to [`Species::new`].
    pub generations: u32,
    /// Generations of a seedling (fewer than `generations`).
    /// Default: two fewer than `generations`, at least 1.
    pub seedling_generations: u32,
    /// Turtle and meshing settings, tropism included.
    /// Default: the grammar's ([`TurtleOptions::for_grammar`]) with a `min_radius` of 0.005.
    pub turtle: TurtleOptions,
    /// Bark colour, linear RGB. Default: [0.30, 0.20, 0.12].
    pub bark: [f32; 3],
    /// Leaf colour, linear RGB (multiplied with the leaf texture). Default: [0.18, 0.42, 0.12].
    pub leaf: [f32; 3],
    /// What its leaf cards show. Default: [`LeafShape::Broadleaf`].
    pub leaf_shape: LeafShape,
    /// What its bark texture shows. Default: [`BarkPattern::Furrowed`].
    pub bark_pattern: BarkPattern,
    /// Relative frequency among the forest's species. Default: 1.
    pub weight: f32,
    /// The ground cover near its canopy trees (empty: the forest floor's default mix).
    /// Default: empty.
    pub ground_cover: Vec<GroundCover>,
    /// How it grows with the years, ages, competes for light and seeds: what a forest over
    /// time ([`Succession`](crate::Succession)) runs on. Default: [`Life::default`].
    pub life: Life,
    /// When its leaves come and go and their colours through the year
    /// ([`Species::in_season`]). Default: [`Phenology::default`] (evergreen).
    pub phenology: Phenology,
}

/// Canopy size of a species, as the thesis bounds it and as measured.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Canopy {
    /// The thesis's bound on the canopy's diameter, 2 D L sin(alpha): D generations, L the
    /// longest branch (a chain of segments between branch points), alpha the widest branching
    /// angle, both measured on the skeleton.
    pub bound: f32,
    /// Twice the widest horizontal reach of the skeletons of a few sample trees.
    pub measured: f32,
    /// The mean area (m²) of ground the sample trees' leaves hide, seen straight down, each
    /// card as opaque as its texture ([`LeafShape::opacity`]): 0 for a species without
    /// leaves. A narrow or open crown hides less of the disc its reach spans than a broad
    /// dense one.
    pub cover: f32,
}

impl Canopy {
    /// The tighter of the two: the canopy diameter used for patches and spacing.
    pub fn diameter(&self) -> f32 {
        self.bound.min(self.measured)
    }

    /// Half of [`Canopy::diameter`].
    pub fn radius(&self) -> f32 {
        0.5 * self.diameter()
    }

    /// The diameter of a disc of the crown's cover ([`Canopy::cover`]), no wider than
    /// [`Canopy::diameter`]; the diameter itself for a species without leaves.
    ///
    /// ```
    /// use sylva_forest::Canopy;
    ///
    /// let open = Canopy { bound: 12.0, measured: 10.0, cover: 25.0 * std::f32::consts::PI };
    /// assert!((open.cover_diameter() - 10.0).abs() < 1e-4);
    /// let leafless = Canopy { cover: 0.0, ..open };
    /// assert_eq!(leafless.cover_diameter(), 10.0);
    /// ```
    pub fn cover_diameter(&self) -> f32 {
        let disc = 2.0 * (self.cover / std::f32::consts::PI).sqrt();
        if disc > 0.0 {
            disc.min(self.diameter())
        } else {
            self.diameter()
        }
    }
}

impl Species {
    /// A species from a grammar, with default colours and turtle settings: the grammar's
    /// dialect's symbols, and for a vlab model its surfaces and contours
    /// ([`TurtleOptions::for_grammar`]).
    pub fn new(name: impl Into<String>, grammar: LSystem, generations: u32) -> Self {
        Species {
            name: name.into(),
            turtle: TurtleOptions::for_grammar(&grammar).with_min_radius(0.005),
            grammar,
            generations,
            seedling_generations: generations.saturating_sub(2).max(1),
            bark: [0.30, 0.20, 0.12],
            leaf: [0.18, 0.42, 0.12],
            leaf_shape: LeafShape::Broadleaf,
            bark_pattern: BarkPattern::Furrowed,
            weight: 1.0,
            ground_cover: Vec::new(),
            life: Life::default(),
            phenology: Phenology::default(),
        }
    }

    /// The species as it looks on `day` of the year: its leaves' colour that day, its
    /// cards as many ([`TurtleOptions::leaf_keep`]) and as large as the day has, and snow
    /// on its bark (and on an evergreen's needles) in winter ([`crate::snow`]). Its shape,
    /// canopy and life are the same, so a forest stands in the same places all year.
    ///
    /// ```
    /// let mut oak = sylva_forest::Species::from_preset("sylva-oak", 4)?;
    /// oak.phenology.evergreen = false;
    /// let winter = oak.in_season(20.0);
    /// assert_eq!(winter.turtle.leaf_keep, 0.0);
    /// assert!(winter.bark[0] > oak.bark[0]); // snow on the branches
    /// assert_eq!(oak.in_season(200.0).leaf, oak.leaf);
    /// # Ok::<(), sylva_forest::ForestError>(())
    /// ```
    #[must_use]
    pub fn in_season(&self, day: f32) -> Species {
        let mut s = self.clone();
        let leaves = self.phenology.leaves(day, self.leaf);
        // Snow whitens the wood and an evergreen's needles; a shader that knows which way a
        // surface faces puts it on the upper sides only (`vertex_phenology`).
        let white = crate::snow(day);
        let snowy = |c: [f32; 3], amount: f32| c.map(|x| x + (0.85 - x) * amount * white);
        s.leaf = if self.phenology.evergreen {
            snowy(leaves.colour, 0.35)
        } else {
            leaves.colour
        };
        s.bark = snowy(self.bark, 0.5);
        s.turtle.leaf_keep = self.turtle.leaf_keep.min(leaves.share);
        s.turtle.leaf_size = self.turtle.leaf_size.map(|x| x * leaves.size);
        s
    }

    /// A species from a bundled preset, with its published angle and tropism. Tropism bends
    /// each hero's branches by their absolute direction; an instance reused elsewhere keeps
    /// the bend it had in its hero, which approximates, as in the Kenwood paper.
    pub fn from_preset(name: &str, generations: u32) -> Result<Self, ForestError> {
        let p = sylva_lsys::preset(name)
            .ok_or_else(|| ForestError::UnknownPreset { name: name.into() })?;
        let mut s = Species::new(name, p.lsystem()?, generations);
        s.turtle = s.turtle.with_angle(p.angle as f32);
        s.turtle.tropism = TurtleOptions::for_preset(p).tropism;
        Ok(s)
    }

    /// One tree of the species derived for `generations` from `seed` and meshed with its
    /// turtle settings: bark and leaf cards, with wind data, as a forest's trees are drawn.
    ///
    /// ```
    /// let oak = sylva_forest::Species::from_preset("sylva-oak", 4)?;
    /// let mesh = oak.mesh(4, 1)?;
    /// assert!(mesh.triangle_count() > 100);
    /// assert_eq!(mesh.vertices, oak.mesh(4, 1)?.vertices);
    /// # Ok::<(), sylva_forest::ForestError>(())
    /// ```
    pub fn mesh(&self, generations: u32, seed: u64) -> Result<Mesh, ForestError> {
        let mut builder = MeshBuilder::new(&self.turtle);
        self.draw_into(generations, seed, &mut builder)?;
        Ok(builder.finish())
    }

    /// The cost of its full-grown tree known before it is made: the stems its word draws
    /// (derived at [`Species::generations`] from seed 0; the word is all that is held), or
    /// the error that drawing it would meet (a word past the module limit, a tree past
    /// [`TurtleOptions::max_pieces`](sylva_turtle::TurtleOptions::max_pieces)). A front end
    /// asks it before accepting a world: a grammar bomb is refused when posted, in the
    /// memory of its word.
    ///
    /// ```
    /// let oak = sylva_forest::Species::from_preset("sylva-oak", 4)?;
    /// assert!(oak.check_cost()? > 10);
    /// let bomb = sylva_lsys::LSystem::parse("axiom: F\nF -> FF")?;
    /// assert!(sylva_forest::Species::new("bomb", bomb, 22).check_cost().is_err());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn check_cost(&self) -> Result<u64, ForestError> {
        let word = self.word(self.generations, 0)?;
        sylva_turtle::check_stems(&word, &self.turtle).map_err(|source| ForestError::Turtle {
            species: self.name.clone(),
            source,
        })
    }

    /// The word its turtle draws: derived at `generations` from `seed`, then its
    /// interpretation rules applied.
    fn word(&self, generations: u32, seed: u64) -> Result<sylva_lsys::Word, ForestError> {
        self.grammar
            .derive(generations, seed)
            .and_then(|w| self.grammar.interpretation(&w, seed))
            .map_err(|source| ForestError::Derive {
                species: self.name.clone(),
                source,
            })
    }

    /// Derives its tree at `generations` from `seed` and has the turtle draw it into `sink`.
    fn draw_into(
        &self,
        generations: u32,
        seed: u64,
        sink: &mut impl sylva_turtle::GeometrySink,
    ) -> Result<(), ForestError> {
        let word = self.word(generations, seed)?;
        interpret(&word, &self.turtle, sink).map_err(|source| ForestError::Turtle {
            species: self.name.clone(),
            source,
        })?;
        Ok(())
    }

    /// Measures the canopy on three sample trees (seeds 0 to 2): their skeletons, and the
    /// ground their leaves hide.
    pub fn canopy(&self) -> Result<Canopy, ForestError> {
        let (mut longest, mut widest, mut reach, mut cover) = (0.0f32, 0.0f32, 0.0f32, 0.0f32);
        for seed in 0..3 {
            let mut crown = CrownCover::new(self.leaf_shape.opacity());
            self.draw_into(self.generations, seed, &mut crown)?;
            cover += crown.area() / 3.0;
            let skeleton = crown.skeleton;
            reach = reach.max(skeleton.horizontal_extent());
            // A branch runs from one branch point to the next: chains of bones whose parent
            // has no other child. L is the longest such chain.
            let mut children = vec![0u32; skeleton.bones.len()];
            for b in &skeleton.bones {
                if let Some(p) = b.parent {
                    children[p as usize] += 1;
                }
            }
            let mut chain = vec![0.0f32; skeleton.bones.len()];
            for (i, bone) in skeleton.bones.iter().enumerate() {
                let dir = bone.end - bone.start;
                let parent = bone
                    .parent
                    .and_then(|p| skeleton.bones.get(p as usize).map(|b| (p as usize, b)));
                chain[i] = dir.length()
                    + match parent {
                        Some((p, _)) if children[p] == 1 => chain[p],
                        _ => 0.0,
                    };
                longest = longest.max(chain[i]);
                if let Some((_, pb)) = parent {
                    widest = widest.max(angle_between(dir, pb.end - pb.start));
                }
            }
        }
        let bound =
            2.0 * self.generations as f32 * longest * widest.min(std::f32::consts::FRAC_PI_2).sin();
        Ok(Canopy {
            bound: if bound > 0.0 { bound } else { 2.0 * reach },
            measured: (2.0 * reach).max(1e-3),
            cover,
        })
    }
}

impl Species {
    /// The skeleton of its tree at `generations` from `seed`: the segments [`Species::mesh`]
    /// draws as bark, as bones with their radii and parents.
    ///
    /// ```
    /// let oak = sylva_forest::Species::from_preset("sylva-oak", 4)?;
    /// let skeleton = oak.skeleton(4, 1)?;
    /// assert!(skeleton.bones.len() > 10);
    /// assert_eq!(skeleton.bones[0].parent, None);
    /// assert!(skeleton.bones[1..].iter().all(|b| b.parent.is_some()));
    /// # Ok::<(), sylva_forest::ForestError>(())
    /// ```
    pub fn skeleton(&self, generations: u32, seed: u64) -> Result<Skeleton, ForestError> {
        let mut skeleton = Skeleton::default();
        self.draw_into(generations, seed, &mut skeleton)?;
        Ok(skeleton)
    }

    /// The mean skeleton top of `samples` of its trees at `generations`: how tall it is
    /// drawn.
    pub(crate) fn drawn_height(&self, generations: u32, samples: u64) -> Result<f32, ForestError> {
        let mut sum = 0.0;
        for seed in 0..samples {
            sum += skeleton_top(&self.skeleton(generations, seed)?);
        }
        Ok((sum / samples as f32).max(1e-3))
    }
}

/// The top of a skeleton.
pub(crate) fn skeleton_top(skeleton: &Skeleton) -> f32 {
    skeleton
        .bones
        .iter()
        .map(|b| b.end.y.max(b.start.y))
        .fold(0.0f32, f32::max)
}

fn angle_between(a: Vec3, b: Vec3) -> f32 {
    let d = a
        .normalize_or_zero()
        .dot(b.normalize_or_zero())
        .clamp(-1.0, 1.0);
    d.acos()
}
