//! Errors of forest generation: species, configurations, placement, stands and walks.

use std::path::PathBuf;

use glam::Vec2;
use sylva_base::file::FileError;
use sylva_base::range::OutOfRange;
use sylva_base::text_file::TextFileError;
use sylva_instancing::InstancingError;
use sylva_lsys::{DeriveError, ParseError};
use sylva_turtle::TurtleError;

/// Why a forest could not be built, or a species read.
///
/// Each variant carries what was wrong (the value, the limit, the place) and its message says
/// how to put it right.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ForestError {
    /// A species file (or the grammar it names) has an error at the given place.
    #[error("{}:{line}:{column}: {message}", file.display())]
    SpeciesFile {
        /// The file.
        file: PathBuf,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// What is wrong.
        message: String,
    },
    /// A species file could not be read (missing, too large, not text).
    #[error("{0}")]
    Read(#[from] TextFileError),
    /// Reading or writing a file failed.
    #[error("{0}")]
    File(#[from] FileError),
    /// A grammar given as text failed to parse.
    #[error("grammar: {0}")]
    Grammar(#[from] ParseError),
    /// No bundled grammar has this name; `sylva_lsys::presets()` lists them.
    #[error("no preset called '{name}' (the bundled presets are listed by sylva_lsys::presets)")]
    UnknownPreset {
        /// The name asked for.
        name: String,
    },
    /// A name that is neither a bundled species nor a file.
    #[error(
        "unknown species '{name}': the bundled ones are {known}; a species file is named by its path"
    )]
    UnknownSpecies {
        /// The name asked for.
        name: String,
        /// The bundled species, comma-separated.
        known: String,
    },
    /// A species' sample trees could not be derived (usually a size limit: fewer generations).
    #[error("species '{species}': {source}")]
    Derive {
        /// The species.
        species: String,
        /// Why the derivation stopped.
        source: DeriveError,
    },
    /// A species' sample trees could not be interpreted by the turtle.
    #[error("species '{species}': {source}")]
    Turtle {
        /// The species.
        species: String,
        /// What the turtle met.
        source: TurtleError,
    },
    /// A species' trees draw nothing: its grammar never moves the turtle.
    #[error(
        "species '{species}' draws nothing: its trees have no extent (does its grammar move the turtle?)"
    )]
    EmptySpecies {
        /// The species.
        species: String,
    },
    /// Building a species' instance cache failed.
    #[error("instancing: {0}")]
    Instancing(#[from] InstancingError),
    /// Growing trees in their environment failed.
    #[error("growth: {0}")]
    Growth(#[from] sylva_growth::GrowthError),
    /// A forest floor asked of a region whose cells could hold more items than the limit: ask
    /// for smaller regions (the floor joins without seams).
    #[error(
        "the floor of this region could hold {items} items, more than the limit of {limit}: ask for smaller regions"
    )]
    FloorTooLarge {
        /// The most items the region's cells could hold.
        items: u64,
        /// The limit ([`MAX_FLOOR_ITEMS`](crate::MAX_FLOOR_ITEMS)).
        limit: u64,
    },
    /// No species has a positive weight: give at least one species a weight above 0.
    #[error("a forest needs at least one species with a positive weight")]
    NoSpecies,
    /// A setting is outside its range: set it within what the message says.
    #[error(transparent)]
    OutOfRange(#[from] OutOfRange),
    /// A composition (a paint layer) was made for another number of species than the forest
    /// has: paint it for this forest's species.
    #[error("the composition is for {composition} species, the forest has {forest}")]
    CompositionSpecies {
        /// Species the composition decides among.
        composition: usize,
        /// Species of the forest.
        forest: usize,
    },
    /// A tree names a variant the forest does not have (trees of another forest).
    #[error("tree of variant {variant}, but the forest has {variants} variants")]
    UnknownVariant {
        /// The tree's variant.
        variant: u16,
        /// Variants of the forest.
        variants: usize,
    },
    /// A region too large to stream in blocks of the forest's patches: ask for a smaller one.
    #[error("a region of {} x {} m in patches of {patch} m makes more than {limit} blocks", size.x, size.y)]
    TooManyBlocks {
        /// The region's size (x, z).
        size: Vec2,
        /// The patch side.
        patch: f32,
        /// The most blocks a region may have ([`MAX_BLOCKS`](crate::limits::MAX_BLOCKS)).
        limit: usize,
    },
    /// A stand was asked for with no plantings: plant at least one tree.
    #[error("no trees to grow: plant at least one")]
    NoPlantings,
    /// A planting names a species the stand was not given.
    #[error("a planting names species {species}, but only {count} species were given")]
    PlantingSpecies {
        /// The species index named.
        species: usize,
        /// Species given.
        count: usize,
    },
    /// The terrain has no finite height under the plantings: plant them on the terrain.
    #[error("the terrain has no height under the plantings")]
    NoGround,
    /// The walker has no room inside the bounds less the margin: a larger area or a smaller
    /// margin.
    #[error("no room to walk in {min} to {max} with a margin of {margin} m")]
    NoRoomToWalk {
        /// The bounds' lower corner.
        min: Vec2,
        /// The bounds' upper corner.
        max: Vec2,
        /// The margin asked for.
        margin: f32,
    },
    /// A snapshot of a forest over time was given to a builder without every age.
    #[error(
        "a snapshot of a forest over time needs a builder with every age (ForestConfig::all_ages)"
    )]
    NotAllAges,
    /// A forest over time would simulate more area than it may.
    #[error("a forest over time of {}x{} m with a halo of {halo} m is beyond the {limit} m^2 it may simulate (or empty): simulate it as tiles", size.x, size.y)]
    SuccessionArea {
        /// The region's size.
        size: Vec2,
        /// The halo around it.
        halo: f32,
        /// The most area, square metres.
        limit: f64,
    },
    /// A year of a forest over time would hold more trees than its bound.
    #[error(
        "a forest over time would hold {stems} trees, more than its bound of {limit} (SuccessionOptions::max_stems)"
    )]
    TooManyStems {
        /// Trees it would hold.
        stems: usize,
        /// The bound.
        limit: usize,
    },
    /// Trees can be planted only before a forest over time's first year, of its species.
    #[error(
        "cannot plant species {species} in year {year}: plant before the first year, one of the forest's species"
    )]
    PlantingTooLate {
        /// The species asked for.
        species: usize,
        /// The year the forest had reached.
        year: u32,
    },
    /// A snapshot of a forest over time was given to a builder of another number of species.
    #[error(
        "a snapshot of a forest over time of {snapshot} species cannot be drawn by a builder of {forest}: build it with the succession's species"
    )]
    SnapshotSpecies {
        /// Species of the snapshot's forest.
        snapshot: usize,
        /// Species of the builder.
        forest: usize,
    },
}
