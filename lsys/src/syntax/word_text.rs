//! Reading words from grammar notation.

use std::str::FromStr;
use std::sync::Arc;

use crate::error::ParseError;
use crate::model::alphabet::{Alphabet, SymbolId};
use crate::model::word::Word;
use crate::syntax::parser::parse_modules;

impl Word {
    /// Parses modules written in grammar notation, with symbols of `alphabet` only.
    /// Parameters may be constant expressions (`F(2*3)`).
    ///
    /// ```
    /// let plant: sylva_lsys::LSystem = "axiom: F\nF -> F[+F]".parse()?;
    /// let word = sylva_lsys::Word::parse("F(2*3)[+F]", plant.alphabet().clone())?;
    /// assert_eq!(word.params(0), &[6.0]);
    /// # Ok::<(), sylva_lsys::ParseError>(())
    /// ```
    pub fn parse(text: &str, alphabet: Arc<Alphabet>) -> Result<Word, ParseError> {
        let mut word = Word::empty(alphabet.clone());
        let mut long_names: Vec<(Vec<char>, SymbolId)> = alphabet
            .names()
            .enumerate()
            .filter(|(_, n)| n.chars().nth(1).is_some())
            .map(|(k, n)| (n.chars().collect(), SymbolId(k as u16)))
            .collect();
        long_names.sort_by_key(|(n, _)| std::cmp::Reverse(n.len()));
        parse_modules(text, &long_names, &mut |c| alphabet.id(c), &mut word)?;
        Ok(word)
    }
}

impl FromStr for Word {
    type Err = ParseError;

    /// Parses a word, building an alphabet of the symbols it uses.
    fn from_str(text: &str) -> Result<Word, ParseError> {
        let mut alphabet = Alphabet::new();
        let mut scratch = Word::empty(Arc::new(Alphabet::new()));
        parse_modules(text, &[], &mut |c| alphabet.intern(c), &mut scratch)?;
        scratch.alphabet = Arc::new(alphabet);
        Ok(scratch)
    }
}
