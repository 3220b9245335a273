//! Paint layers on disk: one 16-bit grayscale PNG mask per species, in one directory.
//!
//! See [`load_masks`] for the format.

use std::collections::BTreeMap;
use std::io;
use std::path::Path;

use sylva_base::file::{FileError, foreign_entry, previous_folder, replace_folder};
use sylva_forest::Rect;

use crate::error::{MaskProblem, PaintError};
use crate::layer::{MAX_PAINT_VALUES, PaintLayer};

/// The PNG text key holding the rectangle a mask covers.
pub const MASK_TEXT_KEY: &str = "sylva:paint";

/// The file name of a species' mask.
///
/// ```
/// assert_eq!(sylva_paint::mask_file_name("kenwood-leafy"), "kenwood-leafy.png");
/// assert_eq!(sylva_paint::mask_file_name("white oak/old"), "white_oak_old.png");
/// ```
pub fn mask_file_name(species: &str) -> String {
    let stem: String = species
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || "-_.".contains(c) {
                c
            } else {
                '_'
            }
        })
        .collect();
    format!("{stem}.png")
}

fn file_names(species: &[&str]) -> Result<Vec<String>, PaintError> {
    let names: Vec<String> = species.iter().map(|s| mask_file_name(s)).collect();
    for (i, a) in names.iter().enumerate() {
        if let Some(j) = names[..i].iter().position(|b| b == a) {
            return Err(PaintError::SharedMaskFile {
                first: species[j].into(),
                second: species[i].into(),
                file: a.clone(),
            });
        }
    }
    Ok(names)
}

fn mask_error(path: &Path, problem: MaskProblem) -> PaintError {
    PaintError::Mask {
        path: path.to_path_buf(),
        problem,
    }
}

/// A PNG decoding error: the file's own failure to read, or a malformed image.
fn decode_error(path: &Path, e: png::DecodingError) -> PaintError {
    match e {
        png::DecodingError::IoError(e) => FileError::new(path, e).into(),
        e => mask_error(path, MaskProblem::Decode(e.to_string())),
    }
}

/// Writes one mask per species of `layer` into the folder `dir`, in the format
/// [`load_masks`] reads; `species` names the layer's channels in order. Species with nothing
/// painted get a file too, so a saved layer reads back exactly.
///
/// The set is replaced whole or not at all: the masks are written into a new folder beside
/// `dir`, which takes `dir`'s place only once every mask is on disk. A full disk or an
/// interrupted save leaves the previous set as it was. `dir` must therefore hold masks only
/// (an error names the first other entry).
pub fn save_masks(layer: &PaintLayer, species: &[&str], dir: &Path) -> Result<(), PaintError> {
    if species.len() != layer.species() {
        return Err(PaintError::Names {
            names: species.len(),
            species: layer.species(),
        });
    }
    let names = file_names(species)?;
    if let Some(entry) = foreign_entry(dir, |name| name.ends_with(".png")) {
        return Err(PaintError::NotMaskFolder {
            folder: dir.to_path_buf(),
            entry,
        });
    }
    replace_folder(dir, |folder| {
        for (s, name) in names.iter().enumerate() {
            write_mask(layer, s, &folder.join(name))?;
        }
        Ok(())
    })?;
    Ok(())
}

/// Writes channel `s` of `layer` as a 16-bit grayscale PNG. The image is encoded in memory
/// and written in one call, so a full disk is reported (a buffered writer's last flush, on
/// drop, would lose the error).
fn write_mask(layer: &PaintLayer, s: usize, path: &Path) -> io::Result<()> {
    let mut png = Vec::new();
    let mut encoder = png::Encoder::new(&mut png, layer.width() as u32, layer.depth() as u32);
    encoder.set_color(png::ColorType::Grayscale);
    encoder.set_depth(png::BitDepth::Sixteen);
    let b = layer.bounds();
    encoder
        .add_text_chunk(
            MASK_TEXT_KEY.to_string(),
            format!("{} {} {} {}", b.min.x, b.min.y, b.max.x, b.max.y),
        )
        .map_err(encoding_error)?;
    let mut writer = encoder.write_header().map_err(encoding_error)?;
    let data: Vec<u8> = layer
        .channel(s)
        .into_iter()
        .flat_map(u16::to_be_bytes)
        .collect();
    writer.write_image_data(&data).map_err(encoding_error)?;
    writer.finish().map_err(encoding_error)?;
    std::fs::write(path, &png)
}

/// The system's error inside a PNG encoding error (a full disk), or the encoder's own.
fn encoding_error(e: png::EncodingError) -> io::Error {
    match e {
        png::EncodingError::IoError(e) => e,
        e => io::Error::other(e),
    }
}

/// One mask read: its size and values.
struct Mask {
    width: usize,
    depth: usize,
    values: Vec<u16>,
}

fn read_mask(path: &Path, bounds: Rect, species: usize) -> Result<Mask, PaintError> {
    let file = std::fs::File::open(path).map_err(FileError::at(path))?;
    let decoder = png::Decoder::new(io::BufReader::new(file));
    let mut reader = decoder.read_info().map_err(|e| decode_error(path, e))?;
    let info = reader.info();
    if info.color_type != png::ColorType::Grayscale || info.bit_depth != png::BitDepth::Sixteen {
        return Err(mask_error(
            path,
            MaskProblem::NotGray16 {
                color: format!("{:?}", info.color_type),
                bits: info.bit_depth as u8,
            },
        ));
    }
    let (width, depth) = (info.width as usize, info.height as usize);
    if width as u128 * depth as u128 * species as u128 > MAX_PAINT_VALUES as u128 {
        return Err(mask_error(
            path,
            MaskProblem::TooLarge {
                width,
                depth,
                species,
            },
        ));
    }
    if let Some(text) = info
        .uncompressed_latin1_text
        .iter()
        .find(|t| t.keyword == MASK_TEXT_KEY)
    {
        let v: Vec<f32> = text
            .text
            .split_whitespace()
            .filter_map(|s| s.parse().ok())
            .collect();
        let want = [bounds.min.x, bounds.min.y, bounds.max.x, bounds.max.y];
        let tolerance = 1e-3 * (bounds.max - bounds.min).max_element().max(1.0);
        if v.len() != 4 || v.iter().zip(want).any(|(a, b)| (a - b).abs() > tolerance) {
            return Err(mask_error(
                path,
                MaskProblem::OtherTerrain {
                    mask: text.text.clone(),
                    terrain: want,
                },
            ));
        }
    }
    let size = reader.output_buffer_size().ok_or_else(|| {
        mask_error(
            path,
            MaskProblem::TooLarge {
                width,
                depth,
                species,
            },
        )
    })?;
    let mut buf = vec![0u8; size];
    reader
        .next_frame(&mut buf)
        .map_err(|e| decode_error(path, e))?;
    let values = buf[..width * depth * 2]
        .chunks_exact(2)
        .map(|b| u16::from_be_bytes([b[0], b[1]]))
        .collect();
    Ok(Mask {
        width,
        depth,
        values,
    })
}

/// Reads the masks in `dir` as a layer over `bounds` (the terrain's rectangle) for
/// `species` (the forest's species names, in order). Errors, naming the file, when a mask is
/// not 16-bit grayscale, the masks differ in size, a mask's stored rectangle is not the
/// terrain's, a file names no species, or no species has a mask.
///
/// # Format
///
/// A directory holding `<species name>.png` for each painted species (the name
/// with every character other than letters, digits, `-`, `_` and `.` turned into `_`; see
/// [`mask_file_name`]). Each mask is a 16-bit grayscale PNG of the layer's `width x depth`
/// cells; a pixel is that species' density in the cell, 0 (none) to 65535 (full); the
/// image's first row is the layer's lowest z, its first column the lowest x. The masks
/// stretch over the terrain's rectangle; a `tEXt` chunk [`MASK_TEXT_KEY`] holds that
/// rectangle (`min_x min_z max_x max_z`) and, when present, must match the terrain's. A
/// species without a file has no trees painted; every file must name a species.
///
/// ```
/// use sylva_forest::Rect;
/// use sylva_paint::{PaintLayer, load_masks, save_masks};
/// use sylva_terrain::glam::Vec2;
///
/// let terrain = Rect::new(Vec2::ZERO, Vec2::splat(64.0));
/// let mut layer = PaintLayer::new(terrain, 2.0, 2)?;
/// layer.set(5, &[1000, 30000])?;
/// let dir = std::env::temp_dir().join(format!("sylva-doc-masks-{}", std::process::id()));
/// save_masks(&layer, &["oak", "birch"], &dir)?;
/// assert!(dir.join("birch.png").exists());
/// assert_eq!(load_masks(&dir, &["oak", "birch"], terrain)?, layer);
/// # std::fs::remove_dir_all(&dir).ok();
/// # Ok::<(), sylva_paint::PaintError>(())
/// ```
pub fn load_masks(dir: &Path, species: &[&str], bounds: Rect) -> Result<PaintLayer, PaintError> {
    let names = file_names(species)?;
    let previous = previous_folder(dir);
    if !dir.exists() && previous.is_dir() {
        return Err(PaintError::Interrupted {
            folder: dir.to_path_buf(),
            previous,
        });
    }
    let entries = std::fs::read_dir(dir).map_err(FileError::at(dir))?;
    let mut found: BTreeMap<usize, std::path::PathBuf> = BTreeMap::new();
    for entry in entries {
        let path = entry.map_err(FileError::at(dir))?.path();
        if path.extension().and_then(|e| e.to_str()) != Some("png") {
            continue;
        }
        let file = path
            .file_name()
            .and_then(|f| f.to_str())
            .unwrap_or_default();
        match names.iter().position(|n| n == file) {
            Some(s) => {
                found.insert(s, path);
            }
            None => {
                return Err(mask_error(
                    &path,
                    MaskProblem::NoSpecies {
                        expected: names.join(", "),
                    },
                ));
            }
        }
    }
    let no_masks = || PaintError::NoMasks {
        folder: dir.to_path_buf(),
        expected: names.join(", "),
    };
    if found.is_empty() {
        return Err(no_masks());
    }
    let mut layer: Option<PaintLayer> = None;
    for (&s, path) in &found {
        let mask = read_mask(path, bounds, species.len())?;
        let layer = match &mut layer {
            Some(l) => l,
            None => layer.insert(PaintLayer::with_cells(
                bounds,
                mask.width,
                mask.depth,
                species.len(),
            )?),
        };
        if (mask.width, mask.depth) != (layer.width(), layer.depth()) {
            return Err(mask_error(
                path,
                MaskProblem::OtherSize {
                    width: mask.width,
                    depth: mask.depth,
                    others_width: layer.width(),
                    others_depth: layer.depth(),
                },
            ));
        }
        layer.set_channel(s, &mask.values)?;
    }
    layer.ok_or_else(no_masks)
}
