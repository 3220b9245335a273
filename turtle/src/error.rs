//! Errors of turtle interpretation.

/// A word the turtle cannot interpret.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum TurtleError {
    /// A `]` without a matching `[`. Balance the brackets in the grammar's successors.
    #[error("module {index}: ']' without a matching '['")]
    UnbalancedPop {
        /// Index of the module in the word.
        index: usize,
    },
    /// Brackets or polygons nested deeper than [`TurtleOptions::max_depth`](crate::TurtleOptions::max_depth).
    #[error("module {index}: nesting deeper than the limit of {limit}")]
    TooDeep {
        /// Index of the module in the word.
        index: usize,
        /// The limit in force.
        limit: usize,
    },
    /// The word draws more pieces of geometry (segments, leaves, polygons) than
    /// [`TurtleOptions::max_pieces`](crate::TurtleOptions::max_pieces): derive fewer
    /// generations, or raise the limit if the tree is meant to be that large.
    #[error(
        "module {index}: the word draws more than {limit} pieces (segments, leaves, polygons); derive fewer generations"
    )]
    TooManyPieces {
        /// Index of the module in the word where the limit was passed.
        index: usize,
        /// The limit in force.
        limit: u64,
    },
    /// A parameter is NaN or infinite, or moves the turtle beyond the representable range
    /// (more than 1e9 units from the origin).
    #[error("module {index} ('{symbol}'): parameter {value} is out of range")]
    OutOfRange {
        /// Index of the module in the word.
        index: usize,
        /// The module's symbol.
        symbol: char,
        /// The offending value.
        value: f64,
    },
}
