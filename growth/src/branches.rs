//! An L-string restructured as the paper does: one command list per branch (each `[ ... ]`
//! is a branch of its own), so that every branch can grow at once, a step at a time, instead
//! of the turtle finishing each branch before the next starts.

use sylva_lsys::Word;
use sylva_turtle::{Command, Sign, TurtleOptions};

use crate::error::GrowthError;

/// One turtle step of a branch, with its lengths and angles resolved.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Step {
    /// Grow a segment of this length.
    Draw(f32),
    /// Move without drawing (the branch's next segment starts a new axis).
    Move(f32),
    /// Turn about the turtle's up (`Yaw`), left (`Pitch`) or heading (`Roll`) axis, radians.
    Yaw(f32),
    Pitch(f32),
    Roll(f32),
    /// Roll so that the left vector is level.
    Level,
    /// Set the width (diameter).
    Width(f32),
    /// Scale the width by the turtle's width factor (`!` without a parameter).
    Thinner,
    /// A leaf card, scaled.
    Leaf(f32),
    /// Start the child branch with this index, from here.
    Spawn(u32),
    /// An environmental query module at this word index: filled with light and free space.
    Query(u32),
}

/// A branch: its steps, and the bracket depth it was written at.
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct Branch {
    pub(crate) steps: Vec<Step>,
    pub(crate) depth: u32,
}

/// Most branches one word may give.
const MAX_BRANCHES: usize = 1 << 22;

/// Splits `word` into branches (index 0 is the trunk), resolving symbols through the turtle
/// options' table; `query` is the environmental query symbol, if any. Unmatched `]` are
/// ignored; branches still open at the end close there.
pub(crate) fn branches(
    word: &Word,
    options: &TurtleOptions,
    query: Option<char>,
) -> Result<Vec<Branch>, GrowthError> {
    let mut out = vec![Branch::default()];
    let mut open: Vec<usize> = vec![0];
    let angle = options.angle.to_radians();
    for (index, module) in word.iter().enumerate() {
        let current = *open.last().unwrap_or(&0);
        let arg = |k: usize| {
            module
                .params
                .get(k)
                .map(|&v| v as f32)
                .filter(|v| v.is_finite())
        };
        if Some(module.symbol) == query {
            out[current].steps.push(Step::Query(index as u32));
            continue;
        }
        let Some(command) = options.symbols.get(module.name) else {
            continue;
        };
        let turn = |sign: Sign| {
            let a = arg(0).map_or(angle, f32::to_radians);
            if sign == Sign::Positive { a } else { -a }
        };
        let step = match command {
            Command::Draw => Step::Draw(arg(0).map_or(options.step, |l| l * options.length_unit)),
            Command::Move => Step::Move(arg(0).map_or(options.step, |l| l * options.length_unit)),
            Command::Yaw(s) => Step::Yaw(turn(s)),
            Command::Pitch(s) => Step::Pitch(turn(s)),
            Command::Roll(s) => Step::Roll(turn(s)),
            Command::TurnAround => Step::Yaw(std::f32::consts::PI),
            Command::RollToHorizontal => Step::Level,
            Command::Width => match arg(0) {
                Some(w) => Step::Width((w * options.width_unit).max(0.0)),
                None => Step::Thinner,
            },
            Command::Leaf => Step::Leaf(arg(0).unwrap_or(1.0).abs()),
            Command::Push => {
                if out.len() >= MAX_BRANCHES {
                    return Err(GrowthError::TooManyBranches {
                        limit: MAX_BRANCHES,
                    });
                }
                let child = out.len();
                out[current].steps.push(Step::Spawn(child as u32));
                out.push(Branch {
                    steps: Vec::new(),
                    depth: open.len() as u32,
                });
                open.push(child);
                continue;
            }
            Command::Pop => {
                if open.len() > 1 {
                    open.pop();
                }
                continue;
            }
            // Polygons, length and angle scaling and markers do not shape growth.
            _ => continue,
        };
        out[current].steps.push(step);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn brackets_become_branches_spawned_where_they_stood() {
        let word: Word = "F(2)[+F][-F E]F".parse().unwrap();
        let b = branches(&word, &TurtleOptions::default(), Some('E')).unwrap();
        assert_eq!(b.len(), 3);
        assert_eq!(b[0].steps[0], Step::Draw(2.0));
        assert_eq!(b[0].steps[1], Step::Spawn(1));
        assert_eq!(b[0].steps[2], Step::Spawn(2));
        assert!(matches!(b[0].steps[3], Step::Draw(_)));
        assert!(matches!(b[1].steps[0], Step::Yaw(a) if a > 0.0));
        assert_eq!(b[2].steps[2], Step::Query(8));
        assert_eq!((b[1].depth, b[2].depth), (1, 1));
    }
}
