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
    /// A texture needs at least one texel (or, for a power-of-two wrap,
    /// power-of-two sides).
    BadTextureSize,
}

impl fmt::Display for BufferError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::StrideTooSmall => f.write_str("stride is smaller than width"),
            Self::TooShort { needed, len } => {
                write!(f, "buffer holds {len} elements, shape needs {needed}")
            }
            Self::Overflow => f.write_str("buffer shape overflows"),
            Self::BadTextureSize => f.write_str("texture size is zero or not a power of two"),
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

    /// Buffer index of pixel (x, y), if inside.
    pub(crate) fn index(&self, x: i32, y: i32) -> Option<usize> {
        self.span(y, x, 1).map(|(_, r)| r.start)
    }
}
