//! The environment a derivation asks between steps: query modules (cpfg's `?P`, `?H`, `?L`,
//! `?U`: where the turtle is and how it is turned) and communication modules (`?E`: what
//! the world around answers), filled in by whoever can answer them. The turtle crate fills
//! the queries; a light model (the growth crate's) can fill `?E`. lsys itself knows no
//! geometry.

use crate::model::word::Word;

/// Answers a word's query and communication modules by writing their parameters.
pub trait Environment {
    /// Called with the word after the axiom's decomposition and after each step (and its
    /// decomposition), before the next step reads it. `generation` is the word's generation.
    /// Errors stop the derivation with [`DeriveError::Environment`](crate::DeriveError).
    fn respond(&mut self, word: &mut Word, generation: u32) -> Result<(), String>;
}

impl<F: FnMut(&mut Word, u32) -> Result<(), String>> Environment for F {
    fn respond(&mut self, word: &mut Word, generation: u32) -> Result<(), String> {
        self(word, generation)
    }
}
