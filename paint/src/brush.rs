//! Brushes: what a stroke does to the paint layer's cells, and how strongly where.

use sylva_base::range::check;

use crate::error::PaintError;
use crate::layer::{FULL, quantize_mix};

/// Widest brush, metres.
pub const MAX_BRUSH_RADIUS: f32 = 1000.0;

/// What a brush does.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BrushAction {
    /// Raises the density toward full, the new trees of this species (existing ones stay).
    Add {
        /// Index of the species painted.
        species: usize,
    },
    /// Lowers the density of every species toward none.
    Erase,
    /// Turns the trees there into this species, keeping the density.
    Species {
        /// Index of the species painted.
        species: usize,
    },
}

/// A brush: its action, size and strength.
///
/// A stroke covers each cell by the brush's falloff at the cell centre's distance from the
/// stroke's path: `strength` within `hardness * radius`, easing to 0 at `radius`. Within one
/// stroke a cell takes the strongest cover any part of the path gives it, so going over a
/// spot twice in one stroke does not paint it twice.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Brush {
    /// What it does. No default: the action given to [`Brush::new`].
    pub action: BrushAction,
    /// Radius, metres (0 to [`MAX_BRUSH_RADIUS`]). No default: the radius given to [`Brush::new`].
    pub radius: f32,
    /// How far one stroke goes toward the action's end (0 to 1): 1 paints full density or
    /// erases everything at the centre. Default: 1.
    pub strength: f32,
    /// The share of the radius painted at full strength (0 to 1); 1 is a hard-edged disc.
    /// Default: 0.5.
    pub hardness: f32,
}

impl Brush {
    /// A brush with strength 1 and hardness 0.5.
    pub fn new(action: BrushAction, radius: f32) -> Self {
        Brush {
            action,
            radius,
            strength: 1.0,
            hardness: 0.5,
        }
    }

    /// The species it paints, if any.
    pub fn species(&self) -> Option<usize> {
        match self.action {
            BrushAction::Add { species } | BrushAction::Species { species } => Some(species),
            BrushAction::Erase => None,
        }
    }

    /// Checks the settings; the message names the one out of range.
    pub fn validate(&self) -> Result<(), PaintError> {
        check(
            "brush radius",
            self.radius.into(),
            self.radius > 0.0 && self.radius <= MAX_BRUSH_RADIUS,
            "above 0 and at most MAX_BRUSH_RADIUS (1000 m)",
        )?;
        check(
            "brush strength",
            self.strength.into(),
            self.strength > 0.0 && self.strength <= 1.0,
            "above 0 and at most 1",
        )?;
        check(
            "brush hardness",
            self.hardness.into(),
            (0.0..=1.0).contains(&self.hardness),
            "from 0 to 1",
        )?;
        Ok(())
    }

    /// The cover at distance `d` from the path, 0 to `strength`.
    pub fn cover(&self, d: f32) -> f32 {
        let inner = self.hardness * self.radius;
        if d <= inner {
            self.strength
        } else if d < self.radius {
            let t = 1.0 - (d - inner) / (self.radius - inner);
            self.strength * t * t * (3.0 - 2.0 * t)
        } else {
            0.0
        }
    }

    /// A cell's values after the action at cover `a`, from its values `before`.
    pub fn apply(&self, before: &[u16], a: f32) -> Vec<u16> {
        let m: Vec<f32> = before
            .iter()
            .map(|&v| f32::from(v) / f32::from(FULL))
            .collect();
        let total: f32 = m.iter().sum::<f32>().min(1.0);
        let after: Vec<f32> = match self.action {
            BrushAction::Erase => m.iter().map(|v| v * (1.0 - a)).collect(),
            BrushAction::Add { species } => {
                let mut out = m.clone();
                if let Some(v) = out.get_mut(species) {
                    *v += a * (1.0 - total);
                }
                out
            }
            BrushAction::Species { species } => m
                .iter()
                .enumerate()
                .map(|(s, v)| v * (1.0 - a) + if s == species { a * total } else { 0.0 })
                .collect(),
        };
        let sum: f32 = after.iter().sum();
        // A full cell stays exactly full (rounding each share could leave it a little short).
        if (sum - 1.0).abs() < 1e-4 {
            quantize_mix(after.into_iter())
        } else {
            after
                .iter()
                .map(|v| (v.clamp(0.0, 1.0) * f32::from(FULL)).round() as u16)
                .collect()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn total(v: &[u16]) -> u32 {
        v.iter().map(|&x| u32::from(x)).sum()
    }

    #[test]
    fn cover_is_full_inside_and_eases_out() {
        let b = Brush::new(BrushAction::Erase, 10.0);
        assert_eq!(b.cover(0.0), 1.0);
        assert_eq!(b.cover(5.0), 1.0);
        assert!(b.cover(7.5) > 0.0 && b.cover(7.5) < 1.0);
        assert_eq!(b.cover(10.0), 0.0);
        assert!(b.cover(6.0) > b.cover(8.0));
    }

    #[test]
    fn actions_do_what_they_say() {
        let add = Brush::new(BrushAction::Add { species: 1 }, 1.0);
        let empty = [0u16, 0];
        assert_eq!(add.apply(&empty, 1.0), vec![0, FULL]);
        let half = add.apply(&empty, 0.5);
        assert!(half[0] == 0 && (i32::from(half[1]) - i32::from(FULL / 2)).abs() <= 1);
        // Adding to a full cell changes nothing.
        assert_eq!(add.apply(&[FULL, 0], 1.0), vec![FULL, 0]);
        let erase = Brush::new(BrushAction::Erase, 1.0);
        assert_eq!(erase.apply(&[FULL / 2, FULL / 2], 1.0), vec![0, 0]);
        let species = Brush::new(BrushAction::Species { species: 0 }, 1.0);
        let turned = species.apply(&[0, FULL / 2], 1.0);
        assert_eq!(turned[1], 0);
        assert!((i32::from(turned[0]) - i32::from(FULL / 2)).abs() <= 1);
        let full = species.apply(&[FULL / 3, FULL - FULL / 3], 0.4);
        assert_eq!(total(&full), u32::from(FULL));
    }

    #[test]
    fn bad_brushes_are_refused() {
        let mut b = Brush::new(BrushAction::Erase, 0.0);
        assert!(b.validate().is_err());
        b.radius = f32::NAN;
        assert!(b.validate().is_err());
        b.radius = 5.0;
        b.strength = 1.5;
        assert!(b.validate().is_err());
        b.strength = 0.5;
        b.hardness = -0.1;
        assert!(b.validate().is_err());
        b.hardness = 1.0;
        assert!(b.validate().is_ok());
    }
}
