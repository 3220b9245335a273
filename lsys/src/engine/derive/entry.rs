//! The grammar's derivation calls: from the axiom, under limits, in an environment, and the
//! interpretation (homomorphism) of a word.

use super::{Deriver, Limits, Table};
use crate::engine::environment::Environment;
use crate::engine::lsystem::LSystem;
use crate::error::DeriveError;
use crate::model::word::Word;

impl LSystem {
    /// The axiom as a word (generation 0).
    pub fn axiom_word(&self) -> Word {
        self.axiom_word.clone()
    }

    /// Derives `generations` generations from the axiom with the default [`Limits`].
    ///
    /// The result is a pure function of the grammar, `generations` and `seed`.
    ///
    /// ```
    /// let algae: sylva_lsys::LSystem = "axiom: A\nA -> AB\nB -> A".parse().unwrap();
    /// assert_eq!(algae.derive(4, 0).unwrap().to_string(), "ABAABABA");
    /// ```
    pub fn derive(&self, generations: u32, seed: u64) -> Result<Word, DeriveError> {
        self.derive_with(generations, seed, &Limits::DEFAULT)
    }

    /// Derives `generations` generations under explicit limits.
    pub fn derive_with(
        &self,
        generations: u32,
        seed: u64,
        limits: &Limits,
    ) -> Result<Word, DeriveError> {
        let mut d = Deriver::new(self, seed, *limits);
        d.run_derivation_block(0, 0)?;
        let word = if self.decomposition.is_empty() {
            // The first step reads the axiom where it is: a large axiom (a forest's seeds, a
            // long signal) is not copied first.
            d.derive_from_ref(&self.axiom_word, 0, generations)?
        } else {
            let axiom = d.decompose(self.axiom_word(), 0)?;
            d.derive_from(axiom, 0, generations)?
        };
        d.run_derivation_block(3, generations)?;
        Ok(word)
    }

    /// As [`LSystem::derive_with`], with `environment` answering the query and
    /// communication modules after the axiom and after every step (open L-systems: the
    /// word's development can depend on where its modules are and what surrounds them).
    ///
    /// ```
    /// use sylva_lsys::{Dialect, LSystem, Limits, Word};
    /// // Grow while the query module says the apex is below height 3.
    /// let plant = LSystem::parse_dialect(
    ///     "Lsystem: 1\nAxiom: A ?P(0,0,0)\nA > ?P(x,y,z) : y < 3 --> F A\nendlsystem",
    ///     Dialect::Cpfg,
    /// )?;
    /// // An environment that knows each F is one unit up (the turtle crate's does this
    /// // for real turtle geometry).
    /// let mut height = |word: &mut Word, _generation: u32| {
    ///     let fs = word.iter().filter(|m| m.name == "F").count() as f64;
    ///     for i in 0..word.len() {
    ///         if word.iter().nth(i).is_some_and(|m| m.name == "?P") {
    ///             word.params_mut(i)[1] = fs;
    ///         }
    ///     }
    ///     Ok(())
    /// };
    /// let word = plant.derive_in(10, 0, &Limits::DEFAULT, &mut height)?;
    /// assert_eq!(word.iter().filter(|m| m.name == "F").count(), 3);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn derive_in(
        &self,
        generations: u32,
        seed: u64,
        limits: &Limits,
        environment: &mut dyn Environment,
    ) -> Result<Word, DeriveError> {
        if generations > limits.max_generations {
            return Err(DeriveError::TooManyGenerations {
                requested: generations,
                limit: limits.max_generations,
            });
        }
        let mut d = Deriver::new(self, seed, *limits);
        let ask = |word: &mut Word, generation: u32, env: &mut dyn Environment| {
            env.respond(word, generation)
                .map_err(|error| DeriveError::Environment { generation, error })
        };
        d.run_derivation_block(0, 0)?;
        let mut word = d.decompose(self.axiom_word(), 0)?;
        ask(&mut word, 0, environment)?;
        for k in 1..=generations {
            word = d.derive_from(word, k - 1, 1)?;
            ask(&mut word, k, environment)?;
            if d.rng.stop {
                break;
            }
        }
        d.run_derivation_block(3, generations)?;
        Ok(word)
    }

    /// The word the turtle draws for `word`: `word` rewritten by the homomorphism until no
    /// homomorphism production fires (at most its maximum depth of passes), or `word` itself
    /// when the grammar has no homomorphism. Random draws in homomorphism productions come
    /// from `seed`.
    ///
    /// ```
    /// let plant: sylva_lsys::LSystem = "axiom: A(3)\nA(n) -> A(n+1)\n#homomorphism depth 1\nA(n) -> F(n)+".parse()?;
    /// let word = plant.derive(1, 0)?;
    /// assert_eq!(word.to_string(), "A(4)");
    /// assert_eq!(plant.interpretation(&word, 0)?.to_string(), "F(4)+");
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn interpretation(&self, word: &Word, seed: u64) -> Result<Word, DeriveError> {
        let mut d = Deriver::new(self, seed, Limits::DEFAULT);
        d.apply_rule_set(word.clone(), Table::Homomorphism, 0)
    }
}
