//! A cpfg model's own shapes, ready to draw: its surfaces (`~l`) as quads in the turtle's
//! frame, and its contours (`@#(id)`) as the cross-sections of generalized cylinders.

use std::sync::Arc;

use glam::{Vec2, Vec3};
use sylva_lsys::ModelFiles;

/// Most points around one contour.
const MAX_CONTOUR_POINTS: usize = 1024;
/// Points around a contour when the model's view file does not say (cpfg's default).
const DEFAULT_CONTOUR_SIDES: u32 = 8;

/// A cross-section of generalized cylinders in the file's units: a cylinder of radius r
/// draws each point (x, y) at r x along the turtle's up and r y along its right (cpfg's
/// placement).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Contour {
    pub(crate) points: Vec<Vec2>,
    /// Whether the last point joins the first (else the section is an open blade).
    pub(crate) closed: bool,
}

/// The surfaces and contours of a model ([`ModelFiles`]), prepared once for every drawing.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ModelShapes {
    /// Each surface's module name (`~` and its letter) and quads: corners as (along the
    /// heading, along the left, along the up) from where the turtle stands.
    pub(crate) surfaces: Vec<(String, Arc<[[Vec3; 4]]>)>,
    /// Contours by the id `@#(id)` selects.
    pub(crate) contours: Vec<(u32, Contour)>,
}

impl ModelShapes {
    /// The shapes of `files`: every surface cut into its quads, every contour sampled at
    /// the model's count of points along its length.
    pub fn new(files: &ModelFiles) -> ModelShapes {
        let surfaces = files
            .surfaces
            .iter()
            .map(|s| {
                let quads: Vec<[Vec3; 4]> = s
                    .quads()
                    .into_iter()
                    .map(|q| q.map(Vec3::from_array))
                    .collect();
                (format!("~{}", s.letter), quads.into())
            })
            .collect();
        // As cpfg does: a contour's points evenly spaced along its length, as many as the
        // view file's contour sides (a closed one's last point is its first, and it is
        // turned so that its first point lies on the x axis).
        let sides = files.contour_sides.unwrap_or(DEFAULT_CONTOUR_SIDES) as usize;
        let sides = sides.clamp(3, MAX_CONTOUR_POINTS);
        let contours = files
            .contours
            .iter()
            .map(|(id, curve)| {
                let count = if curve.closed { sides } else { sides + 1 };
                let mut points: Vec<Vec2> = (0..count)
                    .map(|k| {
                        let p = curve.at_length(k as f64 / sides as f64);
                        Vec2::new(p[0] as f32, p[1] as f32)
                    })
                    .collect();
                if curve.closed
                    && let Some(first) = points[0].try_normalize()
                {
                    let turn = Vec2::new(first.x, -first.y);
                    points.iter_mut().for_each(|p| *p = turn.rotate(*p));
                }
                (
                    *id,
                    Contour {
                        points,
                        closed: curve.closed,
                    },
                )
            })
            .collect();
        ModelShapes { surfaces, contours }
    }

    pub(crate) fn contour(&self, id: u32) -> Option<&Contour> {
        self.contours.iter().find(|c| c.0 == id).map(|c| &c.1)
    }
}
