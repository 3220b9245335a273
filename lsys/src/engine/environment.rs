//! The environment a derivation asks between steps: query modules (cpfg's `?P`, `?H`, `?L`,
//! `?U`: where the turtle is and how it is turned) and communication modules (`?E`: what
//! the world around answers), filled in by whoever can answer them. The turtle crate fills
//! the queries; a light model (the growth crate's) can fill `?E`. lsys itself knows no
//! geometry.

use crate::model::word::Word;

/// Why an [`Environment`] could not answer a word.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum EnvironmentError {
    /// The word could not be interpreted to find where its query or communication modules
    /// stand (the turtle's error, as text).
    #[error("the word could not be interpreted: {0}")]
    Interpretation(String),
    /// The world around could not answer (a light model outside its grid, say).
    #[error("{0}")]
    Unanswered(String),
}

/// Answers a word's query and communication modules by writing their parameters. A closure
/// `FnMut(&mut Word, u32) -> Result<(), EnvironmentError>` is one (see
/// [`LSystem::derive_in`](crate::LSystem::derive_in)); the turtle crate answers the queries
/// and the growth crate's light model the communication modules.
pub trait Environment {
    /// Called with the word after the axiom's decomposition and after each step (and its
    /// decomposition), before the next step reads it. `generation` is the word's generation.
    /// Errors stop the derivation with [`DeriveError::Environment`](crate::DeriveError).
    fn respond(&mut self, word: &mut Word, generation: u32) -> Result<(), EnvironmentError>;
}

impl<F: FnMut(&mut Word, u32) -> Result<(), EnvironmentError>> Environment for F {
    fn respond(&mut self, word: &mut Word, generation: u32) -> Result<(), EnvironmentError> {
        self(word, generation)
    }
}
