//! Errors of painting: layers, brushes, strokes and mask files.

use std::path::PathBuf;

use glam::Vec2;
use sylva_base::file::FileError;
use sylva_base::range::OutOfRange;
use sylva_forest::{ForestError, Rect};

/// Why a layer could not be made, a stroke painted or masks read or saved.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum PaintError {
    /// The forest refused the painted layer or its trees.
    #[error(transparent)]
    Forest(#[from] ForestError),
    /// Reading or writing a file failed.
    #[error("{0}")]
    File(#[from] FileError),
    /// A setting is outside its range: set it within what the message says.
    #[error(transparent)]
    OutOfRange(#[from] OutOfRange),
    /// A layer's rectangle has no area: give the terrain's rectangle.
    #[error("a paint layer needs a rectangle with area, not {min} to {max}")]
    NoArea {
        /// The lower corner given.
        min: Vec2,
        /// The upper corner given.
        max: Vec2,
    },
    /// A layer needs at least one species channel.
    #[error("a paint layer needs at least one species")]
    NoSpecies,
    /// A layer would hold more values than [`MAX_PAINT_VALUES`](crate::MAX_PAINT_VALUES):
    /// use larger cells.
    #[error(
        "a paint layer of {width} x {depth} cells for {species} species holds more than {limit} values (use larger cells)"
    )]
    TooLarge {
        /// Cells across.
        width: f64,
        /// Cells deep.
        depth: f64,
        /// Species channels.
        species: usize,
        /// The limit.
        limit: usize,
    },
    /// A filled layer needs a species with positive weight.
    #[error("a filled paint layer needs a positive species weight")]
    NoWeight,
    /// The layer has another number of species channels than the forest has species.
    #[error("the paint layer has {layer} species channels, the forest {forest} species")]
    SpeciesCount {
        /// Channels of the layer.
        layer: usize,
        /// Species of the forest.
        forest: usize,
    },
    /// A cell index or its values do not fit the layer.
    #[error("cell {index} with {values} values: the layer has {cells} cells of {species} values")]
    BadCell {
        /// The cell asked for.
        index: usize,
        /// Values given.
        values: usize,
        /// Cells of the layer.
        cells: usize,
        /// Species channels of the layer.
        species: usize,
    },
    /// A channel index or its values do not fit the layer.
    #[error(
        "channel {channel} of {values} values: the layer has {species} species of {cells} cells"
    )]
    BadChannel {
        /// The channel asked for.
        channel: usize,
        /// Values given.
        values: usize,
        /// Species channels of the layer.
        species: usize,
        /// Cells of the layer.
        cells: usize,
    },
    /// The brush names a species the forest does not have.
    #[error("no species {species} to paint: the forest has {count} ({names})")]
    UnknownSpecies {
        /// The species index.
        species: usize,
        /// Species of the forest.
        count: usize,
        /// Their names, comma-separated.
        names: String,
    },
    /// The brush names a species with no trees (weight 0, so no instance cache).
    #[error("species '{species}' has no trees to paint (its weight is 0); loaded: {loaded}")]
    NotLoaded {
        /// The species' name.
        species: String,
        /// The species that can be painted, comma-separated.
        loaded: String,
    },
    /// A stroke was continued without one begun: begin one with a brush.
    #[error("no stroke under way (begin one with a brush)")]
    NoStroke,
    /// A stroke needs at least one point.
    #[error("a stroke needs a point")]
    EmptyStroke,
    /// The brush position is not finite.
    #[error("brush position ({}, {}) is not a point on the terrain", at.x, at.y)]
    NotAPoint {
        /// The position given.
        at: Vec2,
    },
    /// The brush touches no cell of the layer: paint on the terrain.
    #[error("the brush at ({:.1}, {:.1}) with radius {radius} m misses the terrain ({:.0} to {:.0} in x, {:.0} to {:.0} in z)", at.x, at.y, bounds.min.x, bounds.max.x, bounds.min.y, bounds.max.y)]
    MissesTerrain {
        /// The brush's position.
        at: Vec2,
        /// Its radius.
        radius: f32,
        /// The layer's rectangle.
        bounds: Rect,
    },
    /// The layer and the terrain do not overlap.
    #[error("the paint layer does not overlap the terrain")]
    NoOverlap,
    /// The terrain is too large to paint in tiles of the forest's patches.
    #[error("a terrain of {} x {} m in tiles of {tile} m is too many tiles to paint", size.x, size.y)]
    TooManyTiles {
        /// The terrain's size (x, z).
        size: Vec2,
        /// The tile side.
        tile: f32,
    },
    /// Two species would share a mask file name: rename one.
    #[error("species '{first}' and '{second}' would share the mask file {file}; rename one")]
    SharedMaskFile {
        /// The first species.
        first: String,
        /// The second.
        second: String,
        /// The file both map to.
        file: String,
    },
    /// Saving masks needs a name per channel.
    #[error("{names} species names for a layer of {species} species")]
    Names {
        /// Names given.
        names: usize,
        /// Channels of the layer.
        species: usize,
    },
    /// A mask file is not what [`load_masks`](crate::load_masks) reads.
    #[error("{}: {problem}", path.display())]
    Mask {
        /// The file.
        path: PathBuf,
        /// What is wrong with it.
        problem: MaskProblem,
    },
    /// A folder holds no masks of the forest's species.
    #[error("{}: no masks here (expected one or more of {expected})", folder.display())]
    NoMasks {
        /// The folder.
        folder: PathBuf,
        /// The file names looked for, comma-separated.
        expected: String,
    },
    /// A save was stopped while it replaced the masks: the previous set is whole, aside.
    #[error("{}: a save was interrupted while replacing these masks; the previous set is whole in {}: rename it to {} (or save again)", folder.display(), previous.display(), folder.display())]
    Interrupted {
        /// The masks' folder.
        folder: PathBuf,
        /// Where the previous set is.
        previous: PathBuf,
    },
    /// Masks are saved into a folder of their own, replaced whole; this one holds other files.
    #[error("{}: the folder holds '{entry}', which is not a mask; save masks into an empty or new folder", folder.display())]
    NotMaskFolder {
        /// The folder.
        folder: PathBuf,
        /// The first entry that is not a mask.
        entry: String,
    },
}

/// What is wrong with one mask file.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum MaskProblem {
    /// Masks are 16-bit grayscale PNGs.
    #[error("a mask must be a 16-bit grayscale PNG, this is {color} at {bits} bits")]
    NotGray16 {
        /// The image's colour type.
        color: String,
        /// Its bit depth.
        bits: u8,
    },
    /// The image is too large for a layer.
    #[error("a mask of {width} x {depth} for {species} species is too large")]
    TooLarge {
        /// Pixels across.
        width: usize,
        /// Pixels deep.
        depth: usize,
        /// Species of the forest.
        species: usize,
    },
    /// The rectangle stored in the mask is not the terrain's: paint on this terrain.
    #[error("the mask covers {mask} but the terrain covers {} {} {} {} (min x, min z, max x, max z)", terrain[0], terrain[1], terrain[2], terrain[3])]
    OtherTerrain {
        /// The rectangle the mask names.
        mask: String,
        /// The terrain's rectangle.
        terrain: [f32; 4],
    },
    /// The file is named after no species of the forest.
    #[error("this mask names no species of the forest (expected {expected})")]
    NoSpecies {
        /// The file names looked for, comma-separated.
        expected: String,
    },
    /// A layer's masks share one size.
    #[error(
        "this mask is {width} x {depth}, the others {others_width} x {others_depth}; a layer's masks share one size"
    )]
    OtherSize {
        /// This mask's width.
        width: usize,
        /// This mask's depth.
        depth: usize,
        /// The others' width.
        others_width: usize,
        /// The others' depth.
        others_depth: usize,
    },
    /// The PNG could not be decoded (cut short, corrupt): save the masks again.
    #[error("not a readable PNG: {0}")]
    Decode(String),
}
