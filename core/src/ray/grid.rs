//! A uniform grid over world-space primitives, traversed with the 3D DDA
//! of Amanatides and Woo, "A Fast Voxel Traversal Algorithm for Ray
//! Tracing", Eurographics 1987, in caller-supplied storage.
//!
//! # Storage
//!
//! [`Grid::build`] takes the primitives' boxes and two slices:
//! - `cell_start`: `nx·ny·nz + 1` entries; cell c's primitives are
//!   `items[cell_start[c]..cell_start[c + 1]]`;
//! - `items`: one entry per (primitive, overlapped cell) pair. A too-short
//!   slice gives [`GridError::ItemStorage`] with the exact size needed.
//!
//! # Traversal
//!
//! Cells are visited in ray order. Each primitive is tested at most once
//! per ray (**mailboxing**, with a caller-supplied [`Mailbox`]); its hit,
//! wherever it lies, competes for the best so far. The traversal stops
//! after a cell as soon as the best hit lies *inside* the cells visited so
//! far (`t < t_exit` of the current cell): every primitive not yet tested
//! occupies only later cells, so its hits are farther. A hit beyond the
//! current cell therefore does not end the walk early, which is the
//! classic "a hit counts only if it is inside the current cell" rule made
//! compatible with mailboxing. Equal `t` goes to the lower primitive index,
//! as in [`nearest_hit`](super::nearest_hit), so the result equals brute
//! force. The one exception: a hit that a primitive reports *outside its
//! own box* (only through rounding, e.g. a fixed-point ray whose huge
//! direction quantizes t coarsely) may be missed, since the grid visits a
//! primitive only in the cells its box overlaps (found by the `grid` fuzz
//! target, which checks everything else).
//!
//! Fixed point: the margins above need the ray to spend at least 64 steps
//! of t (2⁻¹⁶ each) in a cell, i.e. `cell / |d_k| ≥ 64·2⁻¹⁶` on every
//! axis. A longer direction (the fuzz target found |d| ≈ 32768 with cells
//! of 5 units) makes the margin round to zero and the walk can stop or
//! step early and miss a hit; keep fixed-point directions near unit length
//! (this is not fixed: the documented precondition is checked by the fuzz
//! target instead). Likewise, at the extremes of the float range (found
//! with |d| ≈ 10²⁵⁷ in a scene 10³⁰⁰ wide), distinct hits in different
//! cells can round to the same t; the walk may then stop at the first
//! one found rather than the lower index.
//!
//! Rounding is absorbed by two margins that only cost a little extra
//! work: primitives are assigned to every cell their box overlaps after
//! widening the box by 1/64 of a cell, and the walk stops only when the
//! best hit is earlier than the cell's exit by 1/64 of the shortest cell
//! crossing time (in which the ray moves less than 1/64 of a cell on every
//! axis). A DDA whose boundary times are off by less than that can only
//! visit a primitive's cell late, never miss it.

use super::bounds::Aabb;
use super::nearest::{Intersect, SurfaceHit};
use super::{Ray, checked::point_at};
use crate::math::Vec3;
use crate::scalar::Scalar;
use core::fmt;

/// Why a [`Grid`] could not be built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum GridError {
    /// No primitives, or a resolution of zero along some axis.
    Empty,
    /// `cell_start` is shorter than `nx·ny·nz + 1`.
    CellStorage {
        /// Entries needed.
        needed: usize,
    },
    /// `items` is too short.
    ItemStorage {
        /// Entries needed.
        needed: usize,
    },
    /// More than `u32::MAX` cells, items or primitives.
    TooLarge,
}

impl fmt::Display for GridError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Empty => f.write_str("grid has no primitives or a zero resolution"),
            Self::CellStorage { needed } => write!(f, "grid needs {needed} cell_start entries"),
            Self::ItemStorage { needed } => write!(f, "grid needs {needed} item entries"),
            Self::TooLarge => f.write_str("grid has more than u32::MAX entries"),
        }
    }
}

impl core::error::Error for GridError {}

/// Per-primitive "already tested for this ray" stamps, in caller storage.
#[derive(Debug)]
pub struct Mailbox<'a> {
    stamps: &'a mut [u32],
    current: u32,
}

impl<'a> Mailbox<'a> {
    /// Wraps (and clears) one stamp per primitive. Primitives beyond the
    /// slice's length are simply not mailboxed (tested once per cell).
    pub fn new(stamps: &'a mut [u32]) -> Self {
        stamps.fill(0);
        Self { stamps, current: 0 }
    }

    fn next_ray(&mut self) {
        self.current = self.current.wrapping_add(1);
        if self.current == 0 {
            // Wrapped after 2³² rays: clear so old stamps cannot collide.
            self.stamps.fill(0);
            self.current = 1;
        }
    }

    /// `true` the first time `i` is seen for the current ray.
    fn first_visit(&mut self, i: usize) -> bool {
        match self.stamps.get_mut(i) {
            Some(s) if *s == self.current => false,
            Some(s) => {
                *s = self.current;
                true
            }
            None => true,
        }
    }
}

/// A uniform grid of `res[0]×res[1]×res[2]` cells over the primitives'
/// bounding boxes.
///
/// # Guarantees
/// After [`Self::build`] succeeds no query panics or indexes out of bounds.
#[derive(Clone, Debug)]
pub struct Grid<'a, S> {
    bounds: Aabb<S>,
    res: [usize; 3],
    cell: Vec3<S>,
    cell_start: &'a [u32],
    items: &'a [u32],
    prims: usize,
}

impl<'a, S: Scalar> Grid<'a, S> {
    /// Bins the primitives (given by their world boxes) into a grid with
    /// `res` cells per axis.
    ///
    /// # Errors
    /// [`GridError`].
    pub fn build(
        boxes: &[Aabb<S>],
        res: [u16; 3],
        cell_start: &'a mut [u32],
        items: &'a mut [u32],
    ) -> Result<Self, GridError> {
        Self::build_with(
            boxes.len(),
            |i| boxes.get(i).copied(),
            res,
            cell_start,
            items,
        )
    }

    /// As [`Self::build`], with primitive `i`'s box given by `box_of(i)`
    /// for `i < count` (so the caller needs no slice of boxes; `box_of`
    /// is called a few times per primitive). A `None` box gives
    /// [`GridError::Empty`].
    ///
    /// # Errors
    /// [`GridError`].
    pub fn build_with(
        count: usize,
        box_of: impl Fn(usize) -> Option<Aabb<S>>,
        res: [u16; 3],
        cell_start: &'a mut [u32],
        items: &'a mut [u32],
    ) -> Result<Self, GridError> {
        if count == 0 || res.contains(&0) {
            return Err(GridError::Empty);
        }
        let res = res.map(usize::from);
        let cells = res[0]
            .checked_mul(res[1])
            .and_then(|c| c.checked_mul(res[2]))
            .filter(|&c| c < u32::MAX as usize)
            .ok_or(GridError::TooLarge)?;
        if count > u32::MAX as usize {
            return Err(GridError::TooLarge);
        }
        if cell_start.len() < cells + 1 {
            return Err(GridError::CellStorage { needed: cells + 1 });
        }
        let mut bounds = box_of(0).ok_or(GridError::Empty)?;
        for i in 1..count {
            bounds = bounds.union(&box_of(i).ok_or(GridError::Empty)?);
        }
        let n = |k: usize| S::from_i32(res[k] as i32);
        let ext = bounds.max() - bounds.min();
        // A zero extent (flat scene) still gets cells of positive size.
        let size = |e: S, k: usize| {
            let c = e / n(k);
            if c > S::ZERO { c } else { S::ONE }
        };
        let cell = Vec3::new(size(ext.x, 0), size(ext.y, 1), size(ext.z, 2));
        let mut grid = Self {
            bounds,
            res,
            cell,
            cell_start: &[],
            items: &[],
            prims: count,
        };
        // Every box is known to exist (the union above).
        let box_at = |i: usize| box_of(i).unwrap_or(bounds);
        // The total first (checked), so no per-cell counter can overflow.
        let mut needed = 0usize;
        for i in 0..count {
            let (lo, hi) = grid.cell_range(&box_at(i));
            let n = (hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1);
            needed = needed
                .checked_add(n)
                .filter(|&t| t <= u32::MAX as usize)
                .ok_or(GridError::TooLarge)?;
        }
        if items.len() < needed {
            return Err(GridError::ItemStorage { needed });
        }
        // Count per cell into cell_start[c + 1], then prefix sums.
        let cell_start = &mut cell_start[..=cells];
        cell_start.fill(0);
        for i in 0..count {
            let (lo, hi) = grid.cell_range(&box_at(i));
            for z in lo[2]..=hi[2] {
                for y in lo[1]..=hi[1] {
                    for x in lo[0]..=hi[0] {
                        cell_start[grid.index([x, y, z]) + 1] += 1;
                    }
                }
            }
        }
        for c in 0..cells {
            cell_start[c + 1] += cell_start[c];
        }
        // Fill, using cell_start[c] as the cursor, then shift back.
        for i in 0..count {
            let (lo, hi) = grid.cell_range(&box_at(i));
            for z in lo[2]..=hi[2] {
                for y in lo[1]..=hi[1] {
                    for x in lo[0]..=hi[0] {
                        let c = grid.index([x, y, z]);
                        items[cell_start[c] as usize] = i as u32;
                        cell_start[c] += 1;
                    }
                }
            }
        }
        for c in (1..=cells).rev() {
            cell_start[c] = cell_start[c - 1];
        }
        cell_start[0] = 0;
        grid.cell_start = cell_start;
        grid.items = &items[..needed];
        Ok(grid)
    }

    /// The grid's box (the union of the primitives' boxes).
    #[must_use]
    pub fn bounds(&self) -> &Aabb<S> {
        &self.bounds
    }

    /// Cells per axis.
    #[must_use]
    pub fn resolution(&self) -> [usize; 3] {
        self.res
    }

    fn index(&self, c: [usize; 3]) -> usize {
        (c[2] * self.res[1] + c[1]) * self.res[0] + c[0]
    }

    /// The cell coordinate of `v` along axis k, floored and clamped.
    fn coord(&self, v: S, k: usize) -> usize {
        let lo = self.bounds.min().to_array()[k];
        let size = self.cell.to_array()[k];
        let f: f64 = (v.to_f64() - lo.to_f64()) / size.to_f64();
        // Truncation is floor for f ≥ 0; `as` saturates huge values.
        if f.is_nan() || f < 0.0 {
            0
        } else {
            (f as usize).min(self.res[k] - 1)
        }
    }

    /// Inclusive cell ranges of a box, widened by 1/64 of a cell (plus a
    /// few ulps) on each side.
    fn cell_range(&self, b: &Aabb<S>) -> ([usize; 3], [usize; 3]) {
        let (mn, mx) = (b.min().to_array(), b.max().to_array());
        let mut lo = [0; 3];
        let mut hi = [0; 3];
        for k in 0..3 {
            let pad = self.cell.to_array()[k] / S::from_i32(64) + S::EPSILON * S::from_i32(4);
            lo[k] = self.coord(mn[k] - pad, k);
            hi[k] = self.coord(mx[k] + pad, k);
        }
        (lo, hi)
    }

    /// The nearest hit with `t > t_min` among `prims` (the same primitives,
    /// in the same order, as the boxes given to [`Self::build`]): (primitive
    /// index, hit). Equals brute force over `prims`, ties to the lower
    /// index. Returns `None` if `prims.len()` differs from the build.
    pub fn nearest<P: Intersect<S>>(
        &self,
        ray: &Ray<S>,
        t_min: S,
        prims: &[P],
        mailbox: &mut Mailbox<'_>,
    ) -> Option<(usize, SurfaceHit<S>)> {
        if prims.len() != self.prims {
            return None;
        }
        mailbox.next_ray();
        let (t_enter, t_leave) = self.bounds.intersect_range(ray, t_min, S::MAX)?;
        let q = ray.origin().to_array();
        let d = ray.dir().to_array();
        let p = point_at(ray.origin(), ray.dir(), t_enter.max_of(t_min))?.to_array();
        let mut c = [0usize; 3];
        let mut step = [0isize; 3];
        let mut t_next = [S::MAX; 3];
        let mut t_delta = [S::MAX; 3];
        let lo = self.bounds.min().to_array();
        let size = self.cell.to_array();
        for k in 0..3 {
            c[k] = self.coord(p[k], k);
            if d[k] == S::ZERO {
                continue;
            }
            step[k] = if d[k] > S::ZERO { 1 } else { -1 };
            let edge = c[k] + usize::from(d[k] > S::ZERO);
            let boundary = lo[k] + size[k] * S::from_i32(edge as i32);
            // Saturating for fixed point: a far crossing becomes MAX.
            t_next[k] = (boundary - q[k]) / d[k];
            t_delta[k] = (size[k] / d[k]).abs();
        }
        let margin = t_delta.iter().fold(S::MAX, |m, &t| m.min_of(t)) / S::from_i32(64);
        let mut best: Option<(usize, SurfaceHit<S>)> = None;
        // Each step leaves one cell; a ray crosses at most nx + ny + nz.
        let max_steps = self.res.iter().sum::<usize>() + 3;
        for _ in 0..max_steps {
            let ci = self.index(c);
            let (s, e) = (
                self.cell_start[ci] as usize,
                self.cell_start[ci + 1] as usize,
            );
            for &i in &self.items[s..e] {
                let i = i as usize;
                if !mailbox.first_visit(i) {
                    continue;
                }
                if let Some(h) = prims[i].intersect_ray(ray, t_min) {
                    let better = match &best {
                        None => true,
                        Some((bi, b)) => h.t < b.t || (h.t == b.t && i < *bi),
                    };
                    if better {
                        best = Some((i, h));
                    }
                }
            }
            // The axis whose boundary comes first.
            let mut k = 0;
            for j in 1..3 {
                if t_next[j] < t_next[k] {
                    k = j;
                }
            }
            let t_exit = t_next[k].min_of(t_leave);
            if let Some((_, b)) = &best {
                if b.t < t_exit - margin {
                    break;
                }
            }
            if step[k] == 0 || t_next[k] > t_leave {
                break;
            }
            let nc = c[k] as isize + step[k];
            if nc < 0 || nc as usize >= self.res[k] {
                break;
            }
            c[k] = nc as usize;
            t_next[k] += t_delta[k];
        }
        best
    }
}
