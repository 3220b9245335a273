//! What a vlab model reads beside its grammar: the function, curve, contour and surface
//! files its view file names.

use crate::curve::Curve;
use crate::spline::SplineFunction;
use crate::surface::Surface;

/// The data files of a model folder, as [`LSystem::from_model_dir`](crate::LSystem::from_model_dir)
/// reads them: expressions read functions (`func`) and curves (`curveX`, `curveGAL`, ...);
/// the turtle draws surfaces (`~l`) and sweeps contours along generalized cylinders
/// (`@#(id)`).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ModelFiles {
    /// Functions, for `func(id, x)` (id 1 is the first).
    pub functions: Vec<SplineFunction>,
    /// Curves, for `curveX(id, t)`, `curveY`, `curveZ` and `curveGAL(id)` (id 1 is the
    /// first).
    pub curves: Vec<Curve>,
    /// Cross-sections of generalized cylinders, by the id `@#(id)` selects.
    pub contours: Vec<(u32, Curve)>,
    /// Surfaces, drawn by `~` and their letter.
    pub surfaces: Vec<Surface>,
    /// How many points round a generalized cylinder's contour (the view file's `contour
    /// sides:`; cpfg's default is 8).
    pub contour_sides: Option<u32>,
}

impl ModelFiles {
    /// No files (a grammar read without its folder).
    pub(crate) const NONE: ModelFiles = ModelFiles {
        functions: Vec::new(),
        curves: Vec::new(),
        contours: Vec::new(),
        surfaces: Vec::new(),
        contour_sides: None,
    };

    /// The contour `@#(id)` selects.
    pub fn contour(&self, id: u32) -> Option<&Curve> {
        self.contours.iter().find(|c| c.0 == id).map(|c| &c.1)
    }
}
