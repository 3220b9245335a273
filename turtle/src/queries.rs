//! The turtle as the environment of a derivation: it answers cpfg's query modules.

use sylva_lsys::{Environment, EnvironmentError, Word};

use crate::error::TurtleError;
use crate::frame::Frame;
use crate::interpret::interpret;
use crate::options::TurtleOptions;
use crate::sink::{GeometrySink, Segment};
use crate::symbols::Command;

/// Answers the query modules of a word between derivation steps (cpfg's `?P(x,y,z)`,
/// `?H`, `?L`, `?U`: the turtle's position, heading, left and up vectors where the module
/// stands), by interpreting the word with `options`. Pass it to
/// [`LSystem::derive_in`](sylva_lsys::LSystem::derive_in).
///
/// ```
/// use sylva_lsys::{Dialect, LSystem, Limits};
/// use sylva_turtle::{Queries, TurtleOptions};
///
/// // The apex grows while it is below 3 units (the turtle starts heading up +Y).
/// let plant = LSystem::parse_dialect(
///     "Lsystem: 1\nAxiom: A ?P(0,0,0)\nA > ?P(x,y,z) : y < 3 --> F(1) A\nendlsystem",
///     Dialect::Cpfg,
/// )?;
/// let mut queries = Queries::new(&TurtleOptions::default());
/// let word = plant.derive_in(10, 0, &Limits::DEFAULT, &mut queries)?;
/// assert_eq!(word.to_string(), "F(1) F(1) F(1) A ?P(0,3,0)");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone)]
pub struct Queries {
    options: TurtleOptions,
}

impl Queries {
    /// Queries answered by a turtle with `options` (its symbol table gains the query
    /// modules).
    pub fn new(options: &TurtleOptions) -> Queries {
        Queries {
            options: options.clone(),
        }
    }
}

/// Records the frame at each query module.
#[derive(Default)]
struct Frames(Vec<(usize, Frame)>);

impl GeometrySink for Frames {
    fn segment(&mut self, _segment: &Segment) {}
    fn query(&mut self, index: usize, frame: &Frame) {
        self.0.push((index, *frame));
    }
}

/// Where the turtle stands at each module named in `names`: (index in the word, frame),
/// in word order, from interpreting `word` with `options` (those names made queries). The
/// growth crate answers `?E` with the light at these frames.
pub fn query_frames(
    word: &Word,
    options: &TurtleOptions,
    names: &[&str],
) -> Result<Vec<(usize, Frame)>, TurtleError> {
    let mut options = options.clone();
    for name in names {
        options.symbols.set(*name, Command::Query);
    }
    let mut frames = Frames::default();
    interpret(word, &options, &mut frames)?;
    let wanted: Vec<bool> = word.iter().map(|m| names.contains(&m.name)).collect();
    frames
        .0
        .retain(|(i, _)| wanted.get(*i).copied().unwrap_or(false));
    Ok(frames.0)
}

impl Environment for Queries {
    fn respond(&mut self, word: &mut Word, _generation: u32) -> Result<(), EnvironmentError> {
        if !word.iter().any(|m| m.name.starts_with('?')) {
            return Ok(());
        }
        let frames = query_frames(word, &self.options, &["?P", "?H", "?L", "?U"])
            .map_err(|e| EnvironmentError::Interpretation(e.to_string()))?;
        for (index, frame) in frames {
            let value = match word.get(index).map(|m| m.name) {
                Some("?P") => frame.position,
                Some("?H") => frame.heading(),
                Some("?L") => frame.left(),
                Some("?U") => frame.up(),
                _ => continue,
            };
            for (p, v) in word.params_mut(index).iter_mut().zip(value.to_array()) {
                *p = f64::from(v);
            }
        }
        Ok(())
    }
}
