//! The one place where a caller's slice is checked against a 2D shape.
//!
//! [`Layout::new`] validates once (smoltcp's `new_checked` idea); afterwards
//! [`Layout::span`] only ever returns index ranges inside the validated
//! length, so the framebuffer, band and depth buffer built on it cannot
//! index out of bounds.

use core::fmt;
use core::ops::Range;

/// Why a caller-supplied buffer cannot be used with the given shape.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum BufferError {
    /// `stride < width`: rows would overlap.
    StrideTooSmall,
    /// The slice is shorter than `stride·(height−1) + width`.
    TooShort {
        /// Elements needed.
        needed: usize,
        /// Elements supplied.
        len: usize,
    },
    /// `stride·(height−1) + width` does not fit in `usize`, or the frame
    /// rows `y0..y0+height` do not fit in `i32`.
    Overflow,
}

impl fmt::Display for BufferError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::StrideTooSmall => f.write_str("stride is smaller than width"),
            Self::TooShort { needed, len } => {
                write!(f, "buffer holds {len} elements, shape needs {needed}")
            }
            Self::Overflow => f.write_str("buffer shape overflows"),
        }
    }
}

impl core::error::Error for BufferError {}

/// A validated shape: `height` rows of `width` elements, `stride` apart,
/// holding frame rows `y0..y0+height` and columns `0..width`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Layout {
    pub(crate) width: u16,
    pub(crate) height: u16,
    pub(crate) stride: usize,
    pub(crate) y0: i32,
}

impl Layout {
    /// Checks `stride ≥ width`, `len ≥ stride·(height−1) + width` without
    /// overflow, and that `y0 + height` fits in `i32`. A zero width or
    /// height is valid and gives a target that holds no pixel.
    pub(crate) fn new(
        len: usize,
        width: u16,
        height: u16,
        stride: usize,
        y0: i32,
    ) -> Result<Self, BufferError> {
        if stride < width as usize {
            return Err(BufferError::StrideTooSmall);
        }
        y0.checked_add(height as i32).ok_or(BufferError::Overflow)?;
        let needed = if width == 0 || height == 0 {
            0
        } else {
            stride
                .checked_mul(height as usize - 1)
                .and_then(|n| n.checked_add(width as usize))
                .ok_or(BufferError::Overflow)?
        };
        if len < needed {
            return Err(BufferError::TooShort { needed, len });
        }
        Ok(Self {
            width,
            height,
            stride,
            y0,
        })
    }

    /// The frame rectangle held.
    pub(crate) fn rect(&self) -> super::Rect {
        super::Rect::new(0, self.y0, self.width as i32, self.y0 + self.height as i32)
    }

    /// The part of span `x..x+len` on frame row `y` that lies inside:
    /// `(skip, range)` where `skip` is how many leading pixels of the span
    /// were clipped and `range` indexes the buffer. `None` if nothing is
    /// inside.
    ///
    /// The range is in bounds of any slice at least as long as the one
    /// validated in [`Layout::new`]: row < height and column < width, so
    /// the end is at most `stride·(height−1) + width`.
    #[inline]
    pub(crate) fn span(&self, y: i32, x: i32, len: u32) -> Option<(u32, Range<usize>)> {
        let row = (y as i64) - (self.y0 as i64);
        if row < 0 || row >= self.height as i64 {
            return None;
        }
        let x0 = x as i64;
        let x1 = x0 + len as i64;
        let a = x0.max(0);
        let b = x1.min(self.width as i64);
        if a >= b {
            return None;
        }
        let base = row as usize * self.stride;
        Some(((a - x0) as u32, base + a as usize..base + b as usize))
    }

    /// The buffer range of span `x..x+len` on frame row `y` when all of it
    /// is inside (`len ≥ 1`), else `None`: what [`Self::span`] returns
    /// with `skip = 0` and the full length, in a few instructions for the
    /// scan converter's per-span fast paths.
    #[inline]
    pub(crate) fn span_exact(&self, y: i32, x: i32, len: u32) -> Option<Range<usize>> {
        // Exact row test: y − y0 wraps to ≥ 2^31 > height whenever y < y0
        // or the true difference exceeds i32.
        let row = y.wrapping_sub(self.y0) as u32;
        // Columns in two compares: `x as u32 < end` holds exactly when
        // len ≥ 1 and the u32 sum does not wrap; then `end ≤ width` (below
        // 2^16) also puts `x as u32` below 2^16, so x ≥ 0: exactly
        // 0 ≤ x < x + len ≤ width. (Three compares in all, five before:
        // W1/W2 per frame on the Cortex-M4 3.64 M / 4.27 M -> 3.58 M /
        // 4.23 M, ARMv6-M 5.46 M / 6.45 M -> 5.47 M / 6.43 M, x86-64
        // 3.27 M / 4.04 M -> 3.28 M / 4.03 M.)
        let end = (x as u32).wrapping_add(len);
        if row >= self.height as u32 || x as u32 >= end || end > self.width as u32 {
            return None;
        }
        let base = row as usize * self.stride;
        Some(base + x as usize..base + end as usize)
    }

    /// Buffer index of pixel (x, y), if inside.
    pub(crate) fn index(&self, x: i32, y: i32) -> Option<usize> {
        self.span(y, x, 1).map(|(_, r)| r.start)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn span_exact_is_span_without_clipping() {
        for y0 in [-5, 0, 3, i32::MIN + 1, i32::MAX - 20] {
            let l = Layout::new(10 * 7, 9, 7, 10, y0).unwrap();
            for y in [
                y0.saturating_sub(1),
                y0,
                y0 + 3,
                y0 + 6,
                y0.saturating_add(7),
                i32::MIN,
                i32::MAX,
            ] {
                for x in [-9, -3, -1, 0, 1, 2, 5, 7, 8, 9, 12, i32::MIN, i32::MAX] {
                    // With the lengths near 2^32 and 2^31 that make
                    // `x + len` wrap in u32.
                    for len in [
                        0,
                        1,
                        2,
                        3,
                        4,
                        9,
                        10,
                        1 << 31,
                        u32::MAX - 4,
                        u32::MAX - 1,
                        u32::MAX,
                    ] {
                        let want = match l.span(y, x, len) {
                            Some((0, r)) if r.len() == len as usize => Some(r),
                            _ => None,
                        };
                        assert_eq!(
                            l.span_exact(y, x, len),
                            want,
                            "y0 {y0} y {y} x {x} len {len}"
                        );
                    }
                }
            }
        }
    }
}
