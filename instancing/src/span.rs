//! `Span`: a run of elements in one of the cache's buffers.

use std::ops::Range;

/// A run of elements in one of a cache's buffers: `start..start + count`. Instances name
/// their bark and leaf triangles and their exits this way.
///
/// ```
/// let s = sylva_instancing::Span::new(4, 3);
/// assert_eq!(s.range(), 4..7);
/// assert_eq!(s.end(), 7);
/// assert!(!s.is_empty());
/// ```
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
pub struct Span {
    /// First element.
    pub start: u32,
    /// Number of elements.
    pub count: u32,
}

impl Span {
    /// `count` elements from `start`.
    pub const fn new(start: u32, count: u32) -> Self {
        Span { start, count }
    }

    /// The elements from `start` up to, not including, `end` (empty when `end <= start`).
    pub const fn between(start: u32, end: u32) -> Self {
        Span {
            start,
            count: end.saturating_sub(start),
        }
    }

    /// One past the last element.
    pub const fn end(self) -> u32 {
        self.start.saturating_add(self.count)
    }

    /// Whether it holds no element.
    pub const fn is_empty(self) -> bool {
        self.count == 0
    }

    /// As an index range.
    pub fn range(self) -> Range<usize> {
        self.start as usize..self.end() as usize
    }

    /// The same run moved `offset` elements on.
    #[must_use]
    pub const fn offset(self, offset: u32) -> Self {
        Span {
            start: self.start.saturating_add(offset),
            count: self.count,
        }
    }
}
