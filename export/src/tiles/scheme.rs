//! How a world is cut into tiles: fine tiles grouped under coarse ones, their ids, and the
//! limit on how many, refused with what they would cost.

use std::fmt;
use std::str::FromStr;

use glam::Vec2;

use sylva_base::range::check;
use sylva_forest::Rect;

use crate::error::ExportError;

/// Most tiles a world may have (fine tiles).
pub const MAX_TILES: u64 = 1 << 16;

/// About how many bytes a tile takes in `tileset.json` (its bounding box, error, content and
/// the JSON around them; measured on written tilesets: 577 bytes a tile).
pub const TILESET_BYTES_PER_TILE: u64 = 580;

/// How a world is cut into tiles: fine tiles of side `tile`, grouped `group` x `group` under
/// each coarse tile, and what a fine tile holds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TileScheme {
    /// The world's rectangle.
    pub world: Rect,
    /// Side of a fine tile, metres.
    pub tile: f32,
    /// Fine tiles along each side of a coarse tile.
    pub group: u32,
    /// Whether a fine tile carries its trees' levels of detail and cells, as a forest file
    /// does (`MSFT_lod`, impostors, 64 m cells: what `sylva-three` draws within a frame
    /// budget), holding its own geometry and textures; otherwise (the default) its trees are
    /// full detail over the geometry every fine tile shares (`shared.bin`), the smallest
    /// world.
    pub fine_levels: bool,
}

/// Which of the two levels a tile is on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Level {
    /// The canopy trees as impostor cards.
    Coarse,
    /// Every tree's branch instances.
    Fine,
}

/// A tile: its level and its column (x) and row (z) on that level's grid.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct TileId {
    /// The level.
    pub level: Level,
    /// Column, from the world's low x.
    pub x: u32,
    /// Row, from the world's low z.
    pub y: u32,
}

impl fmt::Display for TileId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let l = match self.level {
            Level::Coarse => 'c',
            Level::Fine => 'f',
        };
        write!(f, "{l}_{}_{}", self.x, self.y)
    }
}

impl FromStr for TileId {
    type Err = ExportError;

    /// Parses `c_X_Y` or `f_X_Y` (the tile's file name without `.glb`).
    fn from_str(s: &str) -> Result<TileId, ExportError> {
        let bad = || ExportError::BadTileId { id: s.into() };
        let mut parts = s.split('_');
        let level = match parts.next() {
            Some("c") => Level::Coarse,
            Some("f") => Level::Fine,
            _ => return Err(bad()),
        };
        let x = parts.next().and_then(|p| p.parse().ok()).ok_or_else(bad)?;
        let y = parts.next().and_then(|p| p.parse().ok()).ok_or_else(bad)?;
        if parts.next().is_some() {
            return Err(bad());
        }
        Ok(TileId { level, x, y })
    }
}

impl TileScheme {
    /// A scheme over `world` with fine tiles of side `tile` and `group` x `group` fine tiles
    /// per coarse tile. Refuses tiles under 10 m, larger than the world, or more than
    /// [`MAX_TILES`] of them.
    ///
    /// ```
    /// use sylva_export::TileScheme;
    /// use sylva_forest::Rect;
    /// use sylva_terrain::glam::Vec2;
    /// let s = TileScheme::new(Rect::new(Vec2::ZERO, Vec2::splat(2000.0)), 250.0, 4)?;
    /// assert_eq!(s.fine_count(), (8, 8));
    /// assert_eq!(s.coarse_count(), (2, 2));
    /// assert!(TileScheme::new(Rect::new(Vec2::ZERO, Vec2::splat(2000.0)), 0.5, 4).is_err());
    /// # Ok::<(), sylva_export::ExportError>(())
    /// ```
    pub fn new(world: Rect, tile: f32, group: u32) -> Result<TileScheme, ExportError> {
        let size = world.max - world.min;
        if world.is_empty() {
            return Err(ExportError::EmptyWorld {
                min: world.min,
                max: world.max,
            });
        }
        check(
            "tile size",
            tile.into(),
            tile >= 10.0 && tile <= size.max_element(),
            "10 m up to the world's side",
        )?;
        check(
            "fine tiles per coarse tile side",
            group.into(),
            (1..=64).contains(&group),
            "1 to 64",
        )?;
        let n = (size / tile).ceil();
        let fine = f64::from(n.x) * f64::from(n.y);
        if fine > MAX_TILES as f64 {
            let coarse = (f64::from(n.x) / f64::from(group)).ceil()
                * (f64::from(n.y) / f64::from(group)).ceil();
            // The side at which the tiles along each axis multiply to at most the limit.
            let side = f64::from(size.x) * f64::from(size.y) / MAX_TILES as f64;
            let mut min_tile = side.sqrt().ceil() as u32;
            while (f64::from(size.x) / f64::from(min_tile)).ceil()
                * (f64::from(size.y) / f64::from(min_tile)).ceil()
                > MAX_TILES as f64
            {
                min_tile += 1;
            }
            return Err(ExportError::TooManyTiles {
                columns: n.x,
                rows: n.y,
                limit: MAX_TILES,
                tileset_bytes: ((fine + coarse) * TILESET_BYTES_PER_TILE as f64) as u64,
                min_tile,
            });
        }
        Ok(TileScheme {
            world,
            tile,
            group,
            fine_levels: false,
        })
    }

    /// Sets [`TileScheme::fine_levels`].
    ///
    /// ```
    /// use sylva_export::TileScheme;
    /// use sylva_forest::Rect;
    /// use sylva_terrain::glam::Vec2;
    /// let s = TileScheme::new(Rect::new(Vec2::ZERO, Vec2::splat(500.0)), 250.0, 2)?;
    /// assert!(s.with_fine_levels(true).fine_levels && !s.fine_levels);
    /// # Ok::<(), sylva_export::ExportError>(())
    /// ```
    #[must_use]
    pub fn with_fine_levels(mut self, fine_levels: bool) -> Self {
        self.fine_levels = fine_levels;
        self
    }

    /// Fine tiles along x and z.
    pub fn fine_count(&self) -> (u32, u32) {
        let n = ((self.world.max - self.world.min) / self.tile).ceil();
        (n.x as u32, n.y as u32)
    }

    /// Coarse tiles along x and z.
    pub fn coarse_count(&self) -> (u32, u32) {
        let (x, y) = self.fine_count();
        (x.div_ceil(self.group), y.div_ceil(self.group))
    }

    /// The rectangle of a tile, clipped to the world; an error for ids outside it.
    pub fn rect(&self, id: TileId) -> Result<Rect, ExportError> {
        let ((nx, ny), side) = match id.level {
            Level::Fine => (self.fine_count(), self.tile),
            Level::Coarse => (self.coarse_count(), self.tile * self.group as f32),
        };
        if id.x >= nx || id.y >= ny {
            return Err(ExportError::TileOutside {
                id: id.to_string(),
                columns: nx,
                rows: ny,
            });
        }
        let min = self.world.min + Vec2::new(id.x as f32, id.y as f32) * side;
        Ok(Rect::new(
            min,
            (min + Vec2::splat(side)).min(self.world.max),
        ))
    }

    /// Every tile id: the coarse ones, then the fine ones, row by row.
    pub fn ids(&self) -> Vec<TileId> {
        let mut out = Vec::new();
        for (level, (nx, ny)) in [
            (Level::Coarse, self.coarse_count()),
            (Level::Fine, self.fine_count()),
        ] {
            for y in 0..ny {
                for x in 0..nx {
                    out.push(TileId { level, x, y });
                }
            }
        }
        out
    }
}
