//! `Word`: a derived string of modules in structure-of-arrays form.

use std::sync::Arc;

use crate::model::alphabet::{Alphabet, SymbolId};

/// A string of modules: symbol ids, and all parameters in one flat array.
///
/// Module `i` has symbol `symbols()[i]` and parameters `params(i)`. `Display` writes the word
/// in grammar notation; [`Word::parse`] reads it back to an equal word.
///
/// ```
/// use sylva_lsys::Word;
/// let w: Word = "F(1.5)[+F]A".parse().unwrap();
/// assert_eq!(w.len(), 6);
/// assert_eq!(w.params(0), &[1.5]);
/// assert_eq!(w.to_string(), "F(1.5)[+F]A");
/// ```
#[derive(Debug, Clone)]
pub struct Word {
    pub(crate) alphabet: Arc<Alphabet>,
    pub(crate) symbols: Vec<SymbolId>,
    /// `offsets[i]..offsets[i + 1]` are module `i`'s parameters; `offsets.len() == len() + 1`.
    pub(crate) offsets: Vec<u32>,
    pub(crate) params: Vec<f64>,
}

impl PartialEq for Word {
    fn eq(&self, other: &Self) -> bool {
        self.len() == other.len()
            && self.params == other.params
            && self.offsets == other.offsets
            && self
                .symbols
                .iter()
                .zip(&other.symbols)
                .all(|(&a, &b)| self.alphabet.name(a) == other.alphabet.name(b))
    }
}

/// A borrowed view of one module of a [`Word`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Module<'a> {
    /// The symbol's id in the word's alphabet.
    pub id: SymbolId,
    /// The symbol's character (`'\u{FFFD}'` for a name of several characters).
    pub symbol: char,
    /// The symbol's name (the character for one-character symbols).
    pub name: &'a str,
    /// The actual parameters.
    pub params: &'a [f64],
}

impl Word {
    /// An empty word over `alphabet`.
    pub fn empty(alphabet: Arc<Alphabet>) -> Word {
        Word {
            alphabet,
            symbols: Vec::new(),
            offsets: vec![0],
            params: Vec::new(),
        }
    }

    /// The alphabet the symbol ids refer to.
    pub fn alphabet(&self) -> &Arc<Alphabet> {
        &self.alphabet
    }

    /// Number of modules.
    pub fn len(&self) -> usize {
        self.symbols.len()
    }

    /// Whether the word has no modules.
    pub fn is_empty(&self) -> bool {
        self.symbols.is_empty()
    }

    /// All symbol ids in order.
    pub fn symbols(&self) -> &[SymbolId] {
        &self.symbols
    }

    /// Parameters of module `i`. Panics if `i >= len()`, like slice indexing.
    pub fn params(&self, i: usize) -> &[f64] {
        &self.params[self.offsets[i] as usize..self.offsets[i + 1] as usize]
    }

    /// Parameters of module `i`, to change (an [`Environment`](crate::Environment) answering
    /// a query module writes them). Panics if `i >= len()`.
    pub fn params_mut(&mut self, i: usize) -> &mut [f64] {
        &mut self.params[self.offsets[i] as usize..self.offsets[i + 1] as usize]
    }

    /// Total number of parameters over all modules.
    pub fn param_count(&self) -> usize {
        self.params.len()
    }

    /// Module `i`, or `None` past the end.
    pub fn get(&self, i: usize) -> Option<Module<'_>> {
        let id = *self.symbols.get(i)?;
        Some(Module {
            id,
            symbol: self.alphabet.char(id),
            name: self.alphabet.name(id),
            params: self.params(i),
        })
    }

    /// The modules in order.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = Module<'_>> + '_ {
        (0..self.len()).map(|i| Module {
            id: self.symbols[i],
            symbol: self.alphabet.char(self.symbols[i]),
            name: self.alphabet.name(self.symbols[i]),
            params: self.params(i),
        })
    }

    /// Appends a module. The id must belong to this word's alphabet.
    pub fn push(&mut self, symbol: SymbolId, params: &[f64]) {
        self.symbols.push(symbol);
        extend_short(&mut self.params, params);
        self.offsets.push(self.params.len() as u32);
    }

    /// Removes all modules, keeping the allocations.
    pub fn clear(&mut self) {
        self.symbols.clear();
        self.params.clear();
        self.offsets.clear();
        self.offsets.push(0);
    }

    /// Bytes of heap memory held by the word's buffers.
    pub fn heap_bytes(&self) -> usize {
        self.symbols.capacity() * 2 + self.offsets.capacity() * 4 + self.params.capacity() * 8
    }
}

/// `dst.extend_from_slice(src)`, for the few values a module has: a copy that short is
/// cheaper as a loop than as a call to `memcpy`, and rewriting makes one per module.
#[inline]
pub(crate) fn extend_short<T: Copy>(dst: &mut Vec<T>, src: &[T]) {
    if src.len() <= 4 {
        for &v in src {
            dst.push(v);
        }
    } else {
        dst.extend_from_slice(src);
    }
}
