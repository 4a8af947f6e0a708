//! The column caster: a DOOM/Wolfenstein-style 2.5D ray caster over a 2D
//! grid map, the chapter's example of the relaxations that make ray
//! casting real-time (one ray per screen column instead of per pixel,
//! walls of one height, an eye at half the wall height, integer cell
//! traversal).
//!
//! # Model
//!
//! - The map ([`GridMap`]) is a row-major grid of cells seen from above:
//!   map x runs along a row (cell column index), map y down the rows. A
//!   cell is free when its byte is `b'.'`, anything else is a wall one
//!   unit high. Cell (x, y) covers `[x, x+1) × [y, y+1)`.
//! - The [`ColumnCamera`] is the map-plane restriction of the chapter's
//!   (O, u, v, V) camera ([`RayCamera`](super::RayCamera)): the viewer V at
//!   `position`, the unit view direction `w`, the screen O = V + f·w one
//!   focus distance f (pixels) ahead, and the per-pixel screen vector
//!   u = right (unit, ⟂ w). The ray of column i runs from V through the
//!   center of that column, `d_i = w + (i + ½ − width/2)/f · u`, exactly as
//!   [`RayCamera::column_ray`](super::RayCamera::column_ray) does in 3D.
//! - Because `w·d_i = 1`, the ray parameter t at a hit **is** the
//!   perpendicular distance from the screen plane (the depth along w), not
//!   the Euclidean distance: using it for the wall height gives straight
//!   walls, with no fisheye.
//! - The eye is at height ½ and walls are 1 high, so a wall at
//!   perpendicular distance t spans screen rows whose centers lie in
//!   `[c_y − f/(2t), c_y + f/(2t))`, `c_y = height/2`. Rows above are
//!   ceiling, rows below floor (flat colors).
//!
//! # Traversal
//!
//! The cells a ray passes are visited with the 2D DDA of Amanatides and
//! Woo ("A Fast Voxel Traversal Algorithm for Ray Tracing", 1987): integer
//! cell indices, and per axis the parameter of the next grid line
//! (`t_max`) and the parameter step between lines (`t_delta = 1/|d|`), in
//! the caster's [`Scalar`]. When both axes cross at the same t (a ray
//! through a grid corner) the y line is taken first: deterministic, and
//! the same on every scalar. A traversal visits at most
//! `map.width + map.height + 2` cells.
//!
//! # Two phases: cast, then draw
//!
//! [`cast_columns`] fills one [`Column`] record per screen column in a
//! caller-supplied slice (no alloc); [`draw_columns`] then writes any
//! [`Target`] row by row: a whole [`Framebuffer`](crate::target::Framebuffer)
//! or a [`Band`](crate::target::Band) of a strip renderer. Every pixel is a
//! pure function of its row and its column record (texture rows come from
//! integer 24.8 arithmetic on the row number, never from stepping), so a
//! frame drawn band by band equals the frame drawn at once, bit for bit.
//!
//! # Textures and shading
//!
//! Walls sample a caller texture ([`Texture`]) by nearest texel: the
//! horizontal texture coordinate is the fractional part of the hit along
//! the wall (flipped on the faces whose normal points to −x/+y, so the
//! texture reads left to right on every face), the vertical one steps
//! down the wall's screen height. Walls hit on an x side (a vertical
//! grid line) use [`ColumnStyle::x_side`], those hit on a y side use
//! [`ColumnStyle::y_side`], so the two orientations are shaded apart as in
//! Wolfenstein 3D (pass a darkened copy for one of them).
//!
//! # Bad input
//!
//! Nothing panics and nothing is written outside the target. A map whose
//! cell count is not `width·height`, an empty map, a non-finite or
//! out-of-map camera, a camera inside a wall and a too-short column slice
//! are reported by [`cast_columns`] as a [`ColumnError`]; the columns it
//! could fill are then set to [`Column::EMPTY`] (ceiling and floor only),
//! so drawing them anyway gives a defined frame. A ray that leaves the map
//! without meeting a wall (a map that is not enclosed) gives an empty
//! column, as does one whose distance overflows the scalar.

use crate::math::Vec2;
use crate::scalar::Scalar;
use crate::target::Target;
use crate::texture::{Clamp, Texture};
use core::fmt;

/// A grid map for the column caster: `cells` row-major, `b'.'` free and
/// any other byte a wall; the viewer starts at `start` (cell units)
/// facing `heading` radians (0 = +x along a row, π/2 = +y down the rows).
#[derive(Clone, Copy, Debug)]
pub struct GridMap<'a> {
    /// Cells across.
    pub width: u16,
    /// Cells down.
    pub height: u16,
    /// `width·height` cells.
    pub cells: &'a [u8],
    /// Viewer position in cell units.
    pub start: [f32; 2],
    /// Viewer heading in radians.
    pub heading: f32,
}

impl GridMap<'_> {
    /// Checks that the map has cells and `cells.len() == width·height`.
    ///
    /// # Errors
    /// [`ColumnError::EmptyMap`], [`ColumnError::MapSize`].
    pub fn validate(&self) -> Result<(), ColumnError> {
        if self.width == 0 || self.height == 0 {
            return Err(ColumnError::EmptyMap);
        }
        let n = self.width as usize * self.height as usize;
        if self.cells.len() != n {
            return Err(ColumnError::MapSize {
                cells: self.cells.len(),
                expected: n,
            });
        }
        Ok(())
    }

    /// Whether cell (x, y) is a wall; `None` outside the map (or when
    /// the cell slice is too short).
    #[must_use]
    pub fn is_wall(&self, x: i32, y: i32) -> Option<bool> {
        if x < 0 || y < 0 || x >= self.width as i32 || y >= self.height as i32 {
            return None;
        }
        self.cells
            .get(y as usize * self.width as usize + x as usize)
            .map(|&c| c != b'.')
    }
}

/// Why the column caster could not cast (see the [module docs](self#bad-input)).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum ColumnError {
    /// The map has no cells (zero width or height).
    EmptyMap,
    /// `cells.len()` is not `width·height`.
    MapSize {
        /// Cells supplied.
        cells: usize,
        /// `width·height`.
        expected: usize,
    },
    /// A camera input is NaN or ±∞, the focus is not positive, or the
    /// screen has no columns.
    BadCamera,
    /// The viewer is outside the map.
    OutsideMap,
    /// The viewer stands in a wall cell.
    InsideWall,
    /// The column slice is shorter than the screen width.
    ColumnsTooShort {
        /// Records supplied.
        len: usize,
        /// Screen width.
        width: u16,
    },
}

impl fmt::Display for ColumnError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::EmptyMap => f.write_str("map has no cells"),
            Self::MapSize { cells, expected } => {
                write!(f, "map has {cells} cells, width·height is {expected}")
            }
            Self::BadCamera => f.write_str("column camera is non-finite or has no focus"),
            Self::OutsideMap => f.write_str("viewer is outside the map"),
            Self::InsideWall => f.write_str("viewer is inside a wall"),
            Self::ColumnsTooShort { len, width } => {
                write!(f, "{len} column records for a {width}-column screen")
            }
        }
    }
}

impl core::error::Error for ColumnError {}

/// Which kind of grid line a wall was hit on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Side {
    /// A vertical line x = k (the wall faces ±x).
    X,
    /// A horizontal line y = k (the wall faces ±y).
    Y,
}

/// A wall hit of one column ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WallHit<S> {
    /// Perpendicular distance from the viewer (depth along the view
    /// direction), in cell units.
    pub distance: S,
    /// The grid line the wall was hit on.
    pub side: Side,
    /// The wall cell.
    pub cell: [u16; 2],
    /// Where along the wall face, in 1/65536 of a cell, oriented so that
    /// textures read left to right on every face.
    pub wall_u: u16,
}

/// What [`cast_columns`] found for one screen column, with its wall's
/// screen extent precomputed for [`draw_columns`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Column<S> {
    /// The wall, or `None` (ceiling and floor only).
    pub hit: Option<WallHit<S>>,
    /// Top of the wall on screen, rows in 24.8 fixed point.
    pub top: i32,
    /// Bottom of the wall on screen (exclusive), rows in 24.8.
    pub bottom: i32,
}

impl<S: Scalar> Column<S> {
    /// A column with no wall: its upper half is ceiling, its lower half
    /// floor.
    pub const EMPTY: Self = Self {
        hit: None,
        top: 0,
        bottom: 0,
    };
}

/// The map-plane camera of the column caster (see the
/// [module docs](self#model)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ColumnCamera<S> {
    /// Viewer V in cell units.
    pub position: Vec2<S>,
    /// Unit view direction w.
    pub forward: Vec2<S>,
    /// Unit screen vector u (to the right on screen), ⟂ w.
    pub right: Vec2<S>,
    /// Focus distance f in pixels (horizontal and vertical).
    pub focus: S,
    /// Screen width in pixels (one ray per column).
    pub width: u16,
    /// Screen height in pixels.
    pub height: u16,
}

impl<S: Scalar> ColumnCamera<S> {
    /// A camera at `position` facing `heading` radians (0 = +x, π/2 = +y),
    /// with focus distance `focus` pixels: the horizontal field of view is
    /// `2·atan(width / (2·focus))`.
    ///
    /// # Errors
    /// [`ColumnError::BadCamera`] for a non-finite input, a focus that is
    /// not positive, or a zero width or height.
    pub fn new(
        position: Vec2<S>,
        heading: S,
        focus: S,
        width: u16,
        height: u16,
    ) -> Result<Self, ColumnError> {
        if !(position.x.is_finite()
            && position.y.is_finite()
            && heading.is_finite()
            && focus.is_finite()
            && focus > S::ZERO
            && width > 0
            && height > 0)
        {
            return Err(ColumnError::BadCamera);
        }
        let (s, c) = heading.sin_cos();
        Ok(Self {
            position,
            forward: Vec2::new(c, s),
            // Seen from above with y down the rows, the viewer's right is
            // w turned a quarter towards +y: (1,0) → (0,1).
            right: Vec2::new(-s, c),
            focus,
            width,
            height,
        })
    }

    /// The camera at a map's start position and heading.
    ///
    /// # Errors
    /// As [`Self::new`].
    pub fn at_start(
        map: &GridMap<'_>,
        focus: S,
        width: u16,
        height: u16,
    ) -> Result<Self, ColumnError> {
        Self::new(
            Vec2::new(S::from_f32(map.start[0]), S::from_f32(map.start[1])),
            S::from_f32(map.heading),
            focus,
            width,
            height,
        )
    }

    /// The direction of column i's ray, `w + (i + ½ − width/2)/f · u`. Its
    /// component along w is 1, so its ray parameter is the perpendicular
    /// distance. Columns outside the screen are allowed (the formula
    /// extends).
    #[must_use]
    pub fn column_dir(&self, i: u16) -> Vec2<S> {
        let s = (S::from_i32(i as i32) + S::HALF - S::from_i32(self.width as i32) * S::HALF)
            / self.focus;
        Vec2::new(
            self.forward.x + self.right.x * s,
            self.forward.y + self.right.y * s,
        )
    }
}

/// The largest integer ≤ `s`, or `None` when it does not fit in `i32`.
fn floor_i32<S: Scalar>(s: S) -> Option<i32> {
    let r = s.to_subpixel(0)?;
    Some(if S::from_i32(r) > s { r - 1 } else { r })
}

/// Casts one ray from `pos` along `d` through `map` (validated, `pos` in
/// a free cell) and returns the first wall, or `None` if the ray leaves
/// the map or its distance overflows.
fn cast_ray<S: Scalar>(map: &GridMap<'_>, pos: Vec2<S>, d: Vec2<S>) -> Option<WallHit<S>> {
    if !(d.x.is_finite() && d.y.is_finite()) {
        return None; // a float direction overflowed
    }
    let mut cx = floor_i32(pos.x)?;
    let mut cy = floor_i32(pos.y)?;
    // Per axis: step direction, t between grid lines, t of the next line.
    let axis = |p: S, c: i32, d: S| -> (i32, S, S) {
        if d == S::ZERO {
            return (0, S::MAX, S::MAX);
        }
        let delta = S::ONE.checked_div(d.abs()).unwrap_or(S::MAX);
        let (step, gap) = if d > S::ZERO {
            (1, S::from_i32(c + 1) - p)
        } else {
            (-1, p - S::from_i32(c))
        };
        (step, delta, gap.checked_mul(delta).unwrap_or(S::MAX))
    };
    let (sx, dx, mut tx) = axis(pos.x, cx, d.x);
    let (sy, dy, mut ty) = axis(pos.y, cy, d.y);
    let max_steps = map.width as u32 + map.height as u32 + 2;
    for _ in 0..max_steps {
        // Ties (a grid corner) take the y line first.
        let (t, side) = if tx < ty {
            cx += sx;
            let t = tx;
            tx = tx.checked_add(dx).unwrap_or(S::MAX);
            (t, Side::X)
        } else {
            cy += sy;
            let t = ty;
            ty = ty.checked_add(dy).unwrap_or(S::MAX);
            (t, Side::Y)
        };
        if t == S::MAX || !t.is_finite() {
            return None; // distance overflow: treated as no wall
        }
        if map.is_wall(cx, cy)? {
            // Hit coordinate along the face: y on an x side, x on a y side.
            let (along, flip) = match side {
                Side::X => (pos.y + d.y * t, sx < 0),
                Side::Y => (pos.x + d.x * t, sy > 0),
            };
            let a = along.to_subpixel(16).unwrap_or(0);
            let frac = (a & 0xFFFF) as u16;
            let wall_u = if flip { u16::MAX - frac } else { frac };
            return Some(WallHit {
                distance: t,
                side,
                cell: [cx as u16, cy as u16],
                wall_u,
            });
        }
    }
    None
}

/// Casts one ray per screen column of `camera` through `map` and fills
/// `columns[i]` for `i in 0..camera.width` (extra records are left alone).
///
/// # Errors
/// [`ColumnError::EmptyMap`] / [`ColumnError::MapSize`] for a bad map,
/// [`ColumnError::OutsideMap`] / [`ColumnError::InsideWall`] for a bad
/// viewer position, [`ColumnError::ColumnsTooShort`] when
/// `columns.len() < camera.width`. On any error every record it covers is
/// set to [`Column::EMPTY`].
///
/// # Panics
/// Never.
pub fn cast_columns<S: Scalar>(
    map: &GridMap<'_>,
    camera: &ColumnCamera<S>,
    columns: &mut [Column<S>],
) -> Result<(), ColumnError> {
    let checked = (|| {
        map.validate()?;
        if columns.len() < camera.width as usize {
            return Err(ColumnError::ColumnsTooShort {
                len: columns.len(),
                width: camera.width,
            });
        }
        // A camera built by hand (pub fields) may still be bad.
        let finite = |v: Vec2<S>| v.x.is_finite() && v.y.is_finite();
        if !(finite(camera.position)
            && finite(camera.forward)
            && finite(camera.right)
            && camera.focus.is_finite()
            && camera.focus > S::ZERO)
        {
            return Err(ColumnError::BadCamera);
        }
        let (Some(cx), Some(cy)) = (floor_i32(camera.position.x), floor_i32(camera.position.y))
        else {
            return Err(ColumnError::OutsideMap);
        };
        match map.is_wall(cx, cy) {
            None => Err(ColumnError::OutsideMap),
            Some(true) => Err(ColumnError::InsideWall),
            Some(false) => Ok(()),
        }
    })();
    let n = columns.len().min(camera.width as usize);
    if let Err(e) = checked {
        for c in &mut columns[..n] {
            *c = Column::EMPTY;
        }
        return Err(e);
    }
    // Wall extent: rows with centers in [c_y − f/(2t), c_y + f/(2t)), in
    // 24.8. The half height is clamped so that the integer arithmetic in
    // `draw_columns` cannot overflow: a wall taller than 64 screens is
    // drawn as one 64 screens tall (identical on screen, the texture's v
    // scale then saturates).
    let cy8 = camera.height as i32 * 128;
    let max_half = S::from_i32(camera.height as i32 * 64);
    let half_focus = camera.focus * S::HALF;
    for (i, col) in columns[..n].iter_mut().enumerate() {
        let d = camera.column_dir(i as u16);
        *col = match cast_ray(map, camera.position, d) {
            Some(hit) => {
                let half = half_focus
                    .checked_div(hit.distance)
                    .unwrap_or(max_half)
                    .min_of(max_half);
                let half8 = half.to_subpixel(8).unwrap_or(0).max(0);
                Column {
                    hit: Some(hit),
                    top: cy8 - half8,
                    bottom: cy8 + half8,
                }
            }
            None => Column::EMPTY,
        };
    }
    Ok(())
}

/// What [`draw_columns`] paints with.
#[derive(Clone, Copy, Debug)]
pub struct ColumnStyle<'a, C> {
    /// Texture of walls hit on an x side.
    pub x_side: Texture<'a, C>,
    /// Texture of walls hit on a y side (e.g. a darker copy).
    pub y_side: Texture<'a, C>,
    /// Color above the walls.
    pub ceiling: C,
    /// Color below the walls.
    pub floor: C,
}

/// The color of row `y` (pixel center y + ½) in a column.
#[inline]
fn column_color<S, C: Copy>(col: &Column<S>, y: i32, mid8: i32, style: &ColumnStyle<'_, C>) -> C {
    let p8 = y.saturating_mul(256).saturating_add(128);
    match &col.hit {
        Some(hit) if p8 >= col.top && p8 < col.bottom => {
            let tex = match hit.side {
                Side::X => &style.x_side,
                Side::Y => &style.y_side,
            };
            let u = ((hit.wall_u as u32 * tex.width() as u32) >> 16) as i32;
            // v = (p − top)/(bottom − top) · tex_height, exact in i64:
            // p − top < span ≤ 2^23 (the clamp in `cast_columns`) and
            // tex_height < 2^16, so the product stays below 2^39.
            let span = (col.bottom - col.top).max(1) as i64;
            let v = ((p8 - col.top) as i64 * tex.height() as i64 / span) as i32;
            tex.sample::<Clamp>(u, v)
        }
        _ => {
            if p8 < mid8 {
                style.ceiling
            } else {
                style.floor
            }
        }
    }
}

/// Draws `columns` (one per screen column, from [`cast_columns`]) into
/// `target`: every pixel of `target`'s clip rectangle in columns
/// `0..columns.len()` is written exactly once; nothing else is. `height`
/// is the frame height the columns were cast for (the ceiling/floor
/// boundary is its middle row).
///
/// # Panics
/// Never.
pub fn draw_columns<S, T: Target>(
    columns: &[Column<S>],
    height: u16,
    style: &ColumnStyle<'_, T::Color>,
    target: &mut T,
) {
    let clip = target.clip_rect();
    let x0 = clip.x0.max(0);
    let x1 = clip.x1.min(columns.len().min(i32::MAX as usize) as i32);
    if x0 >= x1 {
        return;
    }
    let mid8 = height as i32 * 128;
    for y in clip.y0..clip.y1 {
        let mut cols = columns.get(x0 as usize..x1 as usize).unwrap_or(&[]).iter();
        let fallback = style.floor;
        target.fill_with(y, x0, (x1 - x0) as u32, || match cols.next() {
            Some(c) => column_color(c, y, mid8, style),
            None => fallback,
        });
    }
}

/// [`cast_columns`] then [`draw_columns`] for the frame `camera` sees,
/// into one target (a framebuffer, or a band of one).
///
/// # Errors
/// As [`cast_columns`]; the target is then drawn from the empty columns
/// (ceiling and floor only).
pub fn render_columns<S: Scalar, T: Target>(
    map: &GridMap<'_>,
    camera: &ColumnCamera<S>,
    style: &ColumnStyle<'_, T::Color>,
    columns: &mut [Column<S>],
    target: &mut T,
) -> Result<(), ColumnError> {
    let r = cast_columns(map, camera, columns);
    let n = columns.len().min(camera.width as usize);
    draw_columns(&columns[..n], camera.height, style, target);
    r
}
