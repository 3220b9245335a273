//! A world's ground: generated, or any elevation model, cropped to the window asked for or
//! to a default region about its middle, resampled onto the square grid forests stand on.
//! Models of any size make a world: one larger than the region taken says what it took.

use std::path::Path;

use sylva_forest::Rect;
use sylva_terrain::dem::{ElevationModel, ReadOptions, Window};
use sylva_terrain::glam::Vec2;
use sylva_terrain::{Heightmap, HydraulicErosion};

use crate::error::WorldError;
use crate::limits::{MAX_SIDE, MIN_SIDE};
use crate::model::model_format;
use crate::presets::{self, GENERATED_SIZE};

/// How much of an elevation model a world takes when no window is named.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Fit {
    /// Its middle, at most `side` metres along each axis: the whole model when it is no
    /// larger.
    Middle {
        /// Longest side of the region taken, metres.
        side: f32,
    },
    /// Its middle square, at most `side` metres a side and no larger than the model's
    /// shorter side: land on every sample of a square world (the viewer's).
    MiddleSquare {
        /// Longest side of the region taken, metres.
        side: f32,
    },
}

impl Fit {
    /// The whole model when it makes a world ([`MAX_SIDE`] a side), else its middle
    /// [`MAX_SIDE`] square: a tiled world's default.
    pub const WHOLE: Fit = Fit::Middle { side: MAX_SIDE };
}

/// The window a world took of a model larger than its region, and why: what to say to the
/// user, who may name another with a crop.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Chosen {
    /// The model's samples, across and down.
    pub model_size: [usize; 2],
    /// The model's extent, metres (x, z).
    pub model_extent: [f32; 2],
    /// The window taken.
    pub window: Window,
    /// The window's extent, metres (x, z).
    pub extent: [f32; 2],
}

impl Chosen {
    /// What was taken, for a person: the model's size, the window, and the crop that names it.
    ///
    /// ```
    /// use sylva_world::{Chosen, Window};
    /// let chosen = Chosen {
    ///     model_size: [129, 67],
    ///     model_extent: [3058.0, 2035.0],
    ///     window: Window { column: 43, row: 17, width: 42, height: 33 },
    ///     extent: [979.0, 987.0],
    /// };
    /// assert!(chosen.note().starts_with("the model covers 3058 x 2035 m (129 x 67 samples); took the middle 979 x 987 m"));
    /// ```
    pub fn note(&self) -> String {
        self.note_naming(crop_flag)
    }

    /// What was taken, then how to name that window again, in the caller's words: `naming`
    /// says it for the window (`--crop C,R,W,H names this window` on the command line, the
    /// terrain's `"crop"` in a served world).
    pub fn note_naming(&self, naming: impl Fn(Window) -> String) -> String {
        format!("{}; {}", self.summary(), naming(self.window))
    }

    /// What was taken, without how to name it: the model's size and the window.
    pub fn summary(&self) -> String {
        let [mx, mz] = self.model_extent;
        let [w, h] = self.model_size;
        let Window {
            column,
            row,
            width,
            height,
        } = self.window;
        let [x, z] = self.extent;
        format!(
            "the model covers {mx:.0} x {mz:.0} m ({w} x {h} samples); took the middle {x:.0} x {z:.0} m (columns {column}..{}, rows {row}..{})",
            column + width - 1,
            row + height - 1
        )
    }
}

/// A world's ground: a square heightmap, the extent the world covers on it, and what was
/// made of the model it came from.
#[derive(Debug, Clone, PartialEq)]
pub struct Ground {
    /// The square (2^n + 1) heightmap, covering the longer side of `extent`.
    pub map: Heightmap,
    /// The world's extent on the map, metres (x, z).
    pub extent: [f32; 2],
    /// The window taken of a model larger than its region; `None` for generated ground, a
    /// model taken whole or a window the user named.
    pub chosen: Option<Chosen>,
    /// Cells of the model that had no data and were filled from their neighbours.
    pub filled: usize,
}

impl Ground {
    /// The default terrain ([`presets::terrain`]) over a square of `side` metres.
    ///
    /// ```
    /// let ground = sylva_world::Ground::generated(1, 300.0)?;
    /// assert_eq!(ground.extent, [300.0, 300.0]);
    /// # Ok::<(), sylva_world::WorldError>(())
    /// ```
    pub fn generated(seed: u64, side: f32) -> Result<Ground, WorldError> {
        check_side(side)?;
        Ok(Self::square(presets::terrain(seed, side)?, side))
    }

    /// Generated terrain with its settings open (see [`presets::generated`]), then
    /// `erosion` droplets of rain per sample (0 for none).
    pub fn generated_with(
        seed: u64,
        side: f32,
        [roughness, relief, smoothing]: [f32; 3],
        erosion: f32,
    ) -> Result<Ground, WorldError> {
        check_side(side)?;
        let mut map = presets::generated(seed, side, roughness, relief, smoothing)?;
        if erosion > 0.0 {
            let droplets = (erosion * (GENERATED_SIZE * GENERATED_SIZE) as f32) as u32;
            HydraulicErosion::new(droplets, seed ^ 0xe205_1011).apply(&mut map)?;
        }
        Ok(Self::square(map, side))
    }

    /// Ground made elsewhere: a square heightmap, the world covering all of it.
    pub fn square(map: Heightmap, side: f32) -> Ground {
        Ground {
            map,
            extent: [side, side],
            chosen: None,
            filled: 0,
        }
    }

    /// An elevation model's file (GeoTIFF, SRTM .hgt, ESRI ASCII grid, 16-bit PNG, RAW)
    /// as ground: `crop`'s window of it when given, else what `fit` takes. `spacing_hint`
    /// says how to give a spacing the file lacks (`--spacing M`).
    ///
    /// ```
    /// use sylva_terrain::dem::ReadOptions;
    /// use sylva_world::{Fit, Ground};
    /// let model = concat!(env!("CARGO_MANIFEST_DIR"), "/../terrain/tests/data/dems/west_bijou_escarpment.asc");
    /// let ground = Ground::read(model.as_ref(), &ReadOptions::default(), None, Fit::Middle { side: 1000.0 }, "--spacing M")?;
    /// let chosen = ground.chosen.expect("a 3 km model is larger than 1000 m");
    /// assert!(ground.extent[0] <= 1000.0 && chosen.model_extent[0] > 3000.0);
    /// # Ok::<(), sylva_world::WorldError>(())
    /// ```
    pub fn read(
        path: &Path,
        options: &ReadOptions,
        crop: Option<Window>,
        fit: Fit,
        spacing_hint: &str,
    ) -> Result<Ground, WorldError> {
        let name = path.display().to_string();
        let model =
            ElevationModel::read(path, options).map_err(|e| model_error(&name)(e.to_string()))?;
        Self::of_model(model, &name, options, crop, fit, spacing_hint)
    }

    /// [`Ground::read`] for a model's bytes (an upload, a project's file); `name` names it
    /// in errors. Its format comes from its first bytes ([`model_format`]).
    pub fn parse(
        bytes: &[u8],
        name: &str,
        options: &ReadOptions,
        crop: Option<Window>,
        fit: Fit,
        spacing_hint: &str,
    ) -> Result<Ground, WorldError> {
        let bad = model_error(name);
        let format = model_format(bytes).ok_or_else(|| bad("not an elevation model".into()))?;
        let model =
            ElevationModel::parse(bytes, format, options).map_err(|e| bad(e.to_string()))?;
        Self::of_model(model, name, options, crop, fit, spacing_hint)
    }

    /// A model read already, as ground (see [`Ground::read`]).
    pub fn of_model(
        model: ElevationModel,
        name: &str,
        options: &ReadOptions,
        crop: Option<Window>,
        fit: Fit,
        spacing_hint: &str,
    ) -> Result<Ground, WorldError> {
        let bad = model_error(name);
        if !model.spacing_from_file && options.spacing.is_none() {
            return Err(WorldError::NoSpacing {
                name: name.to_owned(),
                hint: spacing_hint.to_owned(),
            });
        }
        let filled = model.nodata;
        let (window, chosen) = match crop {
            Some(window) => (Some(window), None),
            None => match middle(&model, fit) {
                Some(chosen) => (Some(chosen.window), Some(chosen)),
                None => (None, None),
            },
        };
        let model = match window {
            // A window the user named that does not fit is their setting's mistake.
            Some(w) => model.crop(w).map_err(|e| {
                WorldError::Invalid(format!("{name}: the crop {}: {e}", window_text(w)))
            })?,
            None => model,
        };
        let [x, z] = model.extent();
        if !(x >= MIN_SIDE && z >= MIN_SIDE && x <= MAX_SIDE && z <= MAX_SIDE) {
            return Err(bad(format!(
                "{} x {} samples at {:.2} x {:.2} m cover {x:.0} x {z:.0} m; a world is {MIN_SIDE} to {MAX_SIDE} m a side (a spacing or a crop changes what the model covers)",
                model.width, model.height, model.spacing[0], model.spacing[1]
            )));
        }
        let (map, extent) = model.to_heightmap().map_err(|e| bad(e.to_string()))?;
        Ok(Ground {
            map,
            extent,
            chosen,
            filled,
        })
    }

    /// The world's region on the map: from the origin to its extent.
    pub fn region(&self) -> Rect {
        Rect::new(Vec2::ZERO, Vec2::new(self.extent[0], self.extent[1]))
    }

    /// The world's area, hectares.
    pub fn hectares(&self) -> f64 {
        f64::from(self.extent[0]) * f64::from(self.extent[1]) / 10_000.0
    }

    /// The world's longer side, metres.
    pub fn side(&self) -> f32 {
        self.extent[0].max(self.extent[1])
    }

    /// What a person should hear about this ground made from `name`: the cells filled,
    /// the window chosen. Empty for ground that needs no word.
    pub fn notes(&self, name: &str) -> Vec<String> {
        self.notes_naming(name, crop_flag)
    }

    /// [`Ground::notes`], the window named in the caller's words (see
    /// [`Chosen::note_naming`]).
    pub fn notes_naming(&self, name: &str, naming: impl Fn(Window) -> String) -> Vec<String> {
        let mut notes = Vec::new();
        if self.filled > 0 {
            notes.push(format!(
                "{name}: {} cells had no data and were filled from their neighbours",
                self.filled
            ));
        }
        if let Some(chosen) = &self.chosen {
            notes.push(format!("{name}: {}", chosen.note_naming(naming)));
        }
        notes
    }
}

/// The window `fit` takes of `model`, or `None` when it takes the whole model.
fn middle(model: &ElevationModel, fit: Fit) -> Option<Chosen> {
    let [sx, sz] = model.spacing;
    let [ex, ez] = model.extent();
    let (side_x, side_z) = match fit {
        Fit::Middle { side } => (side.min(ex), side.min(ez)),
        Fit::MiddleSquare { side } => {
            let s = side.min(ex).min(ez);
            (s, s)
        }
    };
    // Samples spanning at most the side, and at least two.
    let samples = |side: f32, spacing: f32, n: usize| ((side / spacing) as usize + 1).clamp(2, n);
    let width = samples(side_x, sx, model.width);
    let height = samples(side_z, sz, model.height);
    if width == model.width && height == model.height {
        return None;
    }
    let window = Window {
        column: (model.width - width) / 2,
        row: (model.height - height) / 2,
        width,
        height,
    };
    Some(Chosen {
        model_size: [model.width, model.height],
        model_extent: [ex, ez],
        window,
        extent: [(width - 1) as f32 * sx, (height - 1) as f32 * sz],
    })
}

/// The error for the model `name`, saying `message`.
fn model_error(name: &str) -> impl Fn(String) -> WorldError + '_ {
    move |message| WorldError::Model {
        name: name.to_owned(),
        message,
    }
}

/// How the command line names a window: `--crop C,R,W,H names this window`.
pub fn crop_flag(window: Window) -> String {
    format!("--crop {} names this window", window_text(window))
}

/// A window as `--crop` takes it.
fn window_text(w: Window) -> String {
    format!("{},{},{},{}", w.column, w.row, w.width, w.height)
}

/// A side a world may have.
fn check_side(side: f32) -> Result<(), WorldError> {
    if (MIN_SIDE..=MAX_SIDE).contains(&side) {
        Ok(())
    } else {
        Err(WorldError::Invalid(format!(
            "a world of {side} m: expected a side from {MIN_SIDE} to {MAX_SIDE} metres"
        )))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dem(name: &str) -> std::path::PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../terrain/tests/data/dems")
            .join(name)
    }

    /// A model larger than the region gives its middle, and the note names the crop that
    /// gives the same window; that crop makes the same ground.
    #[test]
    fn the_middle_of_a_large_model_is_named_by_its_crop() {
        let path = dem("west_bijou_escarpment.asc");
        let options = ReadOptions::default();
        let fit = Fit::Middle { side: 1000.0 };
        let ground = Ground::read(&path, &options, None, fit, "--spacing M").unwrap();
        let chosen = ground.chosen.unwrap();
        assert!(ground.extent.iter().all(|e| *e <= 1000.0 && *e > 900.0));
        let w = chosen.window;
        assert_eq!(
            (w.column * 2 + w.width, w.row * 2 + w.height),
            (
                chosen.model_size[0] - (chosen.model_size[0] - w.width) % 2,
                chosen.model_size[1] - (chosen.model_size[1] - w.height) % 2
            )
        );
        assert!(
            chosen
                .note()
                .contains(&format!("--crop {}", window_text(w)))
        );
        let again = Ground::read(&path, &options, Some(w), fit, "").unwrap();
        assert_eq!((again.map, again.extent), (ground.map, ground.extent));
        assert_eq!(again.chosen, None);
    }

    /// A model no larger than the region is taken whole, with nothing to say.
    #[test]
    fn a_small_model_is_taken_whole() {
        let path = dem("west_bijou_escarpment.asc");
        let ground = Ground::read(&path, &ReadOptions::default(), None, Fit::WHOLE, "").unwrap();
        assert_eq!(ground.chosen, None);
        assert!(ground.extent[0] > 3000.0);
        assert!(ground.notes("m").is_empty());
    }

    /// A square fit takes land on every side of a square world.
    #[test]
    fn a_square_fit_is_square_within_a_sample() {
        let path = dem("west_bijou_escarpment.asc");
        let fit = Fit::MiddleSquare { side: 20_000.0 };
        let ground = Ground::read(&path, &ReadOptions::default(), None, fit, "").unwrap();
        let [x, z] = ground.extent;
        assert!((x - z).abs() < 40.0, "{x} x {z}");
    }

    /// An SRTM tile, 80 x 111 km, is no world whole; its middle is one.
    #[test]
    fn an_srtm_tile_gives_its_middle_and_refuses_whole() {
        let path = dem("N44W072.hgt");
        let ground = Ground::read(
            &path,
            &ReadOptions::default(),
            None,
            Fit::Middle { side: 1000.0 },
            "",
        )
        .unwrap();
        assert!(ground.side() <= 1000.0 && ground.side() > 900.0);
        let tiled = Ground::read(&path, &ReadOptions::default(), None, Fit::WHOLE, "").unwrap();
        assert!(tiled.side() <= MAX_SIDE && tiled.side() > 19_000.0);
        let crop = Window {
            column: 0,
            row: 0,
            width: 1201,
            height: 1201,
        };
        let e =
            Ground::read(&path, &ReadOptions::default(), Some(crop), Fit::WHOLE, "").unwrap_err();
        assert_eq!(e.code(), "bad_heightmap");
        assert!(
            e.to_string().contains("a world is 10 to 20000 m a side"),
            "{e}"
        );
    }

    /// A model without a spacing asks for one, in the caller's words.
    #[test]
    fn a_model_without_spacing_asks_for_it() {
        let model = ElevationModel {
            width: 3,
            height: 3,
            heights: vec![0.0; 9],
            spacing: [1.0, 1.0],
            nodata: 0,
            georeference: None,
            spacing_from_file: false,
        };
        let e = Ground::of_model(
            model,
            "h.png",
            &ReadOptions::default(),
            None,
            Fit::WHOLE,
            "\"spacing\"",
        )
        .unwrap_err();
        assert_eq!(e.code(), "bad_heightmap");
        assert!(
            e.to_string().contains("h.png") && e.to_string().contains("\"spacing\""),
            "{e}"
        );
    }

    proptest::proptest! {
        /// The middle window of any model lies inside it, spans at most the side asked for
        /// (or the two samples a window needs), is centred within a sample, and is `None`
        /// exactly when the whole model fits.
        #[test]
        fn the_middle_window_is_inside_centred_and_no_larger_than_asked(
            width in 2usize..400,
            height in 2usize..400,
            sx in 0.5f32..120.0,
            sz in 0.5f32..120.0,
            side in 10.0f32..30_000.0,
            square in proptest::bool::ANY,
        ) {
            let model = ElevationModel {
                width,
                height,
                heights: vec![0.0; width * height],
                spacing: [sx, sz],
                nodata: 0,
                georeference: None,
                spacing_from_file: true,
            };
            let fit = if square { Fit::MiddleSquare { side } } else { Fit::Middle { side } };
            match middle(&model, fit) {
                None => {
                    let [ex, ez] = model.extent();
                    proptest::prop_assert!(square || (ex <= side + sx && ez <= side + sz));
                }
                Some(chosen) => {
                    let w = chosen.window;
                    proptest::prop_assert!(w.width >= 2 && w.height >= 2);
                    proptest::prop_assert!(w.column + w.width <= width && w.row + w.height <= height);
                    proptest::prop_assert!(chosen.extent[0] <= side.max(sx) + 1e-3);
                    proptest::prop_assert!(chosen.extent[1] <= side.max(sz) + 1e-3);
                    proptest::prop_assert!((width - w.width) / 2 == w.column);
                    proptest::prop_assert!((height - w.height) / 2 == w.row);
                }
            }
        }
    }
}
