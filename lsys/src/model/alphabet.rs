//! Interning of module symbols into small integer ids.

use std::collections::HashMap;

/// A module symbol's id: an index into its [`Alphabet`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SymbolId(pub u16);

impl SymbolId {
    /// The id as an index into per-symbol tables.
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// The symbols of a grammar, each a single character, numbered in order of first appearance.
///
/// Words store [`SymbolId`]s rather than characters so that per-symbol lookups are array
/// indexing. The brackets `[` and `]` and the cut symbol `%` are always present, with fixed ids.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Alphabet {
    chars: Vec<char>,
    ids: HashMap<char, SymbolId>,
}

/// Id of `[` in every alphabet.
pub const PUSH: SymbolId = SymbolId(0);
/// Id of `]` in every alphabet.
pub const POP: SymbolId = SymbolId(1);
/// Id of the cut symbol `%` in every alphabet.
pub const CUT: SymbolId = SymbolId(2);

/// Characters that can never be module symbols because the notation uses them.
pub const RESERVED: &[char] = &['(', ')', ',', '<', '>', ':', '?', '#'];

impl Default for Alphabet {
    fn default() -> Self {
        Self::new()
    }
}

impl Alphabet {
    /// An alphabet holding only `[`, `]` and `%`.
    pub fn new() -> Self {
        let mut a = Alphabet {
            chars: Vec::new(),
            ids: HashMap::new(),
        };
        for c in ['[', ']', '%'] {
            a.intern(c).expect("three symbols always fit");
        }
        a
    }

    /// Whether `c` can be a module symbol (not whitespace, not a control character, not reserved).
    pub fn is_symbol_char(c: char) -> bool {
        !c.is_whitespace() && !c.is_control() && !RESERVED.contains(&c)
    }

    /// The id of `c`, adding it if new. `None` when `c` cannot be a symbol or the alphabet is full.
    pub fn intern(&mut self, c: char) -> Option<SymbolId> {
        if let Some(&id) = self.ids.get(&c) {
            return Some(id);
        }
        if !Self::is_symbol_char(c) || self.chars.len() >= u16::MAX as usize {
            return None;
        }
        let id = SymbolId(self.chars.len() as u16);
        self.chars.push(c);
        self.ids.insert(c, id);
        Some(id)
    }

    /// The id of `c` if it is in the alphabet.
    pub fn id(&self, c: char) -> Option<SymbolId> {
        self.ids.get(&c).copied()
    }

    /// The character of `id`. Ids from another alphabet give `'\u{FFFD}'`.
    pub fn char(&self, id: SymbolId) -> char {
        self.chars.get(id.index()).copied().unwrap_or('\u{FFFD}')
    }

    /// Number of symbols.
    pub fn len(&self) -> usize {
        self.chars.len()
    }

    /// Always false: the brackets and the cut symbol are always present.
    pub fn is_empty(&self) -> bool {
        self.chars.is_empty()
    }

    /// The symbols in id order.
    pub fn chars(&self) -> &[char] {
        &self.chars
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn brackets_and_cut_have_fixed_ids() {
        let a = Alphabet::new();
        assert_eq!(a.id('['), Some(PUSH));
        assert_eq!(a.id(']'), Some(POP));
        assert_eq!(a.id('%'), Some(CUT));
    }

    #[test]
    fn reserved_characters_are_refused() {
        let mut a = Alphabet::new();
        for &c in RESERVED {
            assert_eq!(a.intern(c), None);
        }
        assert_eq!(a.intern(' '), None);
        assert_eq!(a.intern('F'), Some(SymbolId(3)));
        assert_eq!(a.intern('F'), Some(SymbolId(3)));
        assert_eq!(a.char(SymbolId(3)), 'F');
    }
}
