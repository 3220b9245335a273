//! A turntable: one tree of a species alone on its ground, seen from views evenly round it,
//! each written as a PNG, and a contact sheet of them all.

use sylva::forest::{Extent, Rect};
use sylva::terrain::glam::{Vec2, Vec3};

use crate::error::ViewerError;
use crate::offscreen::Offscreen;
use crate::render::Mode;
use crate::scene::{Camera, FIELD_OF_VIEW_DEGREES, Scene};

/// `views` pictures of the world's one tree from evenly spaced directions.
pub(crate) struct Turntable {
    pub(crate) views: u32,
    pub(crate) size: (u32, u32),
}

impl Turntable {
    /// Renders the views to `PATH_0000.png` and on, and a contact sheet of them (four a row,
    /// at half size) to `path`; prints the tree's size and each view's triangles.
    pub(crate) fn run(
        &self,
        scene: &mut Scene,
        offscreen: &mut Offscreen,
        path: &str,
        mode: Mode,
    ) -> Result<(), ViewerError> {
        let (views, tree) = self.render(scene, offscreen, mode)?;
        let mut pictures = Vec::new();
        for (
            view,
            View {
                turn,
                pixels,
                triangles,
            },
        ) in views.into_iter().enumerate()
        {
            let file = crate::numbered(path, view as u32);
            crate::write_png(&file, self.size, &pixels)?;
            println!(
                "wrote {file}: view {view} from {:.0} degrees, {triangles} triangles",
                turn.to_degrees()
            );
            pictures.push(pixels);
        }
        let (sheet, sheet_size) = contact_sheet(&pictures, self.size, 4);
        crate::write_png(path, sheet_size, &sheet)?;
        println!(
            "wrote {path}: {} views of a tree {:.1} m tall, crown {:.1} m across, from {:.1} m",
            self.views, tree.height, tree.crown, tree.distance
        );
        Ok(())
    }

    /// The views and the tree's size.
    pub(crate) fn render(
        &self,
        scene: &mut Scene,
        offscreen: &mut Offscreen,
        mode: Mode,
    ) -> Result<(Vec<View>, SpecimenSize), ViewerError> {
        let (builder, _) = scene.world.forest();
        let side = scene.side();
        let whole = Rect::new(Vec2::ZERO, Vec2::splat(side));
        let centre = Vec2::splat(side * 0.5);
        let tree = builder
            .trees(&scene.world.heightmap, whole)
            .into_iter()
            .min_by(|a, b| {
                let d = |t: &sylva::instancing::CompactTree| {
                    Vec2::new(t.position[0], t.position[2]).distance(centre)
                };
                d(a).total_cmp(&d(b))
            })
            .ok_or_else(|| {
                ViewerError::Usage(
                    "the turntable's plot holds no tree (the terrain refused it)".into(),
                )
            })?;
        let extent = Extent::of(&builder.variants()[tree.variant as usize]);
        let (height, crown) = (extent.height * tree.scale, extent.crown * tree.scale);
        let base = Vec3::from(tree.position);
        // Far enough that the whole tree fits the frame's height with a margin, measured from
        // the crown's near side (a wide crown's front is closer than its trunk); the eye at
        // mid-height, looking at the tree's middle.
        let half_fov = (FIELD_OF_VIEW_DEGREES * 0.5).to_radians();
        let distance = crown + 0.45 * height / half_fov.tan();
        let mut views = Vec::new();
        for view in 0..self.views {
            let turn = std::f32::consts::TAU * view as f32 / self.views as f32;
            let eye = Vec2::new(base.x, base.z) + distance * Vec2::new(turn.cos(), turn.sin());
            let ground = scene.ground(eye.x, eye.y);
            let eye_height = 0.5 * height;
            let look = Vec2::new(base.x, base.z) - eye;
            let camera = Camera {
                x: eye.x,
                z: eye.y,
                yaw: look.y.atan2(look.x),
                pitch: ((base.y + 0.5 * height) - (ground + eye_height)).atan2(distance),
                height: eye_height,
            };
            let (pixels, stats) = offscreen.frame(scene, &camera, mode)?;
            views.push(View {
                turn,
                pixels,
                triangles: stats.triangles,
            });
        }
        let size = SpecimenSize {
            height,
            crown: 2.0 * crown,
            distance,
        };
        Ok((views, size))
    }
}

/// One view of a turntable.
pub(crate) struct View {
    /// The direction it is seen from, radians about +y.
    pub(crate) turn: f32,
    /// RGBA8, row by row from the top.
    pub(crate) pixels: Vec<u8>,
    /// Triangles drawn.
    pub(crate) triangles: u64,
}

/// A turntable tree's size and the distance it is seen from, metres.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SpecimenSize {
    pub(crate) height: f32,
    /// The crown's width.
    pub(crate) crown: f32,
    pub(crate) distance: f32,
}

/// RGBA pictures of `size` laid out `columns` a row at half size (each 2 x 2 block averaged).
pub(crate) fn contact_sheet(
    pictures: &[Vec<u8>],
    size: (u32, u32),
    columns: u32,
) -> (Vec<u8>, (u32, u32)) {
    let (w, h) = ((size.0 / 2).max(1), (size.1 / 2).max(1));
    let count = pictures.len() as u32;
    let columns = columns.min(count).max(1);
    let rows = count.div_ceil(columns).max(1);
    let (sw, sh) = (w * columns, h * rows);
    let mut sheet = vec![0u8; (sw * sh * 4) as usize];
    for (k, picture) in pictures.iter().enumerate() {
        let (ox, oy) = ((k as u32 % columns) * w, (k as u32 / columns) * h);
        for y in 0..h {
            for x in 0..w {
                for c in 0..4 {
                    let at = |dx: u32, dy: u32| {
                        let (px, py) = ((2 * x + dx).min(size.0 - 1), (2 * y + dy).min(size.1 - 1));
                        u32::from(picture[((py * size.0 + px) * 4 + c) as usize])
                    };
                    let mean = (at(0, 0) + at(1, 0) + at(0, 1) + at(1, 1) + 2) / 4;
                    sheet[(((oy + y) * sw + ox + x) * 4 + c) as usize] = mean as u8;
                }
            }
        }
    }
    (sheet, (sw, sh))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A contact sheet halves each picture and lays them out in rows.
    #[test]
    fn the_contact_sheet_halves_and_tiles() {
        let red = [200u8, 0, 0, 255].repeat(4 * 2);
        let blue = [0u8, 0, 100, 255].repeat(4 * 2);
        let (sheet, size) = contact_sheet(&[red, blue.clone(), blue], (4, 2), 2);
        assert_eq!(size, (4, 2));
        assert_eq!(&sheet[..4], &[200, 0, 0, 255]);
        assert_eq!(&sheet[8..12], &[0, 0, 100, 255]);
        // The third picture starts the second row; the empty slot beside it stays clear.
        assert_eq!(&sheet[16..20], &[0, 0, 100, 255]);
        assert_eq!(&sheet[24..28], &[0, 0, 0, 0]);
    }
}
