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

/// The symbols of a grammar, numbered in order of first appearance. A symbol is one
/// character (`F`, `+`) or a name of several (`Apex`, `@Gs`, `?P`) that a dialect declares.
///
/// Words store [`SymbolId`]s rather than names so that per-symbol lookups are array
/// indexing. The brackets `[` and `]` and the cut symbol `%` are always present, with fixed ids.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Alphabet {
    names: Vec<Box<str>>,
    ids: HashMap<Box<str>, SymbolId>,
}

/// Id of `[` in every alphabet.
pub const PUSH: SymbolId = SymbolId(0);
/// Id of `]` in every alphabet.
pub const POP: SymbolId = SymbolId(1);
/// Id of the cut symbol `%` in every alphabet.
pub const CUT: SymbolId = SymbolId(2);

/// Characters that can never be module symbols because the notation uses them.
pub const RESERVED: &[char] = &['(', ')', ',', '<', '>', ':', '?', '#'];

/// Longest symbol name, in characters.
pub const MAX_NAME_CHARS: usize = 64;

impl Default for Alphabet {
    fn default() -> Self {
        Self::new()
    }
}

impl Alphabet {
    /// An alphabet holding only `[`, `]` and `%`.
    pub fn new() -> Self {
        let mut a = Alphabet {
            names: Vec::new(),
            ids: HashMap::new(),
        };
        for c in ['[', ']', '%'] {
            a.intern(c).expect("three symbols always fit");
        }
        a
    }

    /// Whether `c` can be a one-character module symbol (not whitespace, not a control
    /// character, not reserved).
    pub fn is_symbol_char(c: char) -> bool {
        !c.is_whitespace() && !c.is_control() && !RESERVED.contains(&c)
    }

    /// Whether `name` can be a symbol named by a dialect: one to [`MAX_NAME_CHARS`]
    /// characters without whitespace, control characters or parentheses, and no brackets or
    /// commas in a name of several. (A dialect may use one of sylva's reserved characters as
    /// a module, as cpfg uses `#` and `,`; sylva's notation cannot print such a grammar back.)
    pub fn is_symbol_name(name: &str) -> bool {
        let n = name.chars().count();
        let plain = |c: char| !c.is_whitespace() && !c.is_control() && !"()".contains(c);
        n == 1 && name.chars().all(plain)
            || (2..=MAX_NAME_CHARS).contains(&n)
                && name.chars().all(|c| plain(c) && !",[]".contains(c))
    }

    /// The id of `c`, adding it if new. `None` when `c` cannot be a symbol or the alphabet is full.
    pub fn intern(&mut self, c: char) -> Option<SymbolId> {
        if !Self::is_symbol_char(c) {
            return None;
        }
        self.intern_name(c.encode_utf8(&mut [0; 4]))
    }

    /// The id of the symbol `name`, adding it if new. `None` when `name` cannot be a symbol
    /// ([`Alphabet::is_symbol_name`]) or the alphabet is full.
    pub fn intern_name(&mut self, name: &str) -> Option<SymbolId> {
        if let Some(&id) = self.ids.get(name) {
            return Some(id);
        }
        if !Self::is_symbol_name(name) || self.names.len() >= u16::MAX as usize {
            return None;
        }
        let id = SymbolId(self.names.len() as u16);
        self.names.push(name.into());
        self.ids.insert(name.into(), id);
        Some(id)
    }

    /// The id of `c` if it is in the alphabet.
    pub fn id(&self, c: char) -> Option<SymbolId> {
        self.ids.get(c.encode_utf8(&mut [0; 4]) as &str).copied()
    }

    /// The id of the symbol `name` if it is in the alphabet.
    pub fn id_of(&self, name: &str) -> Option<SymbolId> {
        self.ids.get(name).copied()
    }

    /// The character of a one-character symbol; `'\u{FFFD}'` for a longer name or an id
    /// from another alphabet.
    pub fn char(&self, id: SymbolId) -> char {
        let name = self.name(id);
        let mut chars = name.chars();
        match (chars.next(), chars.next()) {
            (Some(c), None) => c,
            _ => '\u{FFFD}',
        }
    }

    /// The symbol's name; `"\u{FFFD}"` for an id from another alphabet.
    pub fn name(&self, id: SymbolId) -> &str {
        self.names.get(id.index()).map_or("\u{FFFD}", |n| n)
    }

    /// Number of symbols.
    pub fn len(&self) -> usize {
        self.names.len()
    }

    /// Always false: the brackets and the cut symbol are always present.
    pub fn is_empty(&self) -> bool {
        self.names.is_empty()
    }

    /// The symbols' names in id order.
    pub fn names(&self) -> impl ExactSizeIterator<Item = &str> + '_ {
        self.names.iter().map(|n| &**n)
    }

    /// Whether any symbol is a name of several characters, or a character sylva's notation
    /// reserves (then words print with spaces between modules).
    pub fn has_long_names(&self) -> bool {
        self.names
            .iter()
            .skip(3)
            .any(|n| n.chars().nth(1).is_some() || !n.chars().all(Self::is_symbol_char))
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

    #[test]
    fn names_of_several_characters_are_symbols_too() {
        let mut a = Alphabet::new();
        let apex = a.intern_name("Apex").unwrap();
        assert_eq!(a.intern_name("Apex"), Some(apex));
        assert_eq!(a.id_of("Apex"), Some(apex));
        assert_eq!(a.name(apex), "Apex");
        assert_eq!(a.char(apex), '\u{FFFD}');
        assert!(a.intern_name("@Gs").is_some());
        assert!(a.has_long_names());
        assert!(a.intern_name("#").is_some(), "cpfg's width module");
        for bad in ["", "a b", "F(", "x,y", "(", &"A".repeat(65)] {
            assert_eq!(a.intern_name(bad), None, "{bad}");
        }
    }
}
