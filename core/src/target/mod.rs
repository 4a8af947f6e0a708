//! Where spans go: sinks that write pixels.
//!
//! The scan converter in [`raster`](crate::raster) never touches memory
//! itself; it hands each horizontal span to a [`Target`] (tiny-skia's
//! *blitter* split: "Blitter is responsible for actually writing pixels into
//! memory"). These targets are provided:
//!
//! | target | for |
//! |---|---|
//! | [`Framebuffer`] | a whole frame in a caller-supplied `&mut [C]` with a stride |
//! | [`Band`] | rows `y0..y0+rows` of a larger frame in a small buffer, for strip-by-strip rendering on small RAM |
//! | [`DrawTargetSink`] | any embedded-graphics `DrawTarget`, written with `fill_contiguous` / `fill_solid` |
//! | [`Rgb565Encoder`] | RGB565 into a framebuffer or band of raw `u16` words or `[u8; 2]` pairs, big- or little-endian, ready for an SPI display |
//!
//! All coordinates are in frame pixels (x right, y down, see the crate
//! docs); a target reports the rectangle it can hold with
//! [`Target::clip_rect`] and the scan converter scissors to it.

mod draw_target;
mod framebuffer;
#[cfg(feature = "depth")]
pub(crate) use framebuffer::fill_run;
#[cfg(feature = "depth")]
pub(crate) use framebuffer::fill_unrolled;
pub(crate) mod layout;
mod pairs;
mod rgb565;

pub use draw_target::DrawTargetSink;
pub use framebuffer::{Band, Framebuffer};
pub use layout::BufferError;
pub use rgb565::{ByteOrder, Rgb565Encoder, Rgb565Storage};

/// A half-open pixel rectangle: columns `x0..x1`, rows `y0..y1`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct Rect {
    /// First column.
    pub x0: i32,
    /// First row.
    pub y0: i32,
    /// One past the last column.
    pub x1: i32,
    /// One past the last row.
    pub y1: i32,
}

impl Rect {
    /// The rectangle `x0..x1` × `y0..y1`.
    #[must_use]
    pub const fn new(x0: i32, y0: i32, x1: i32, y1: i32) -> Self {
        Self { x0, y0, x1, y1 }
    }

    /// Whether the rectangle holds no pixel.
    #[must_use]
    pub const fn is_empty(&self) -> bool {
        self.x0 >= self.x1 || self.y0 >= self.y1
    }

    /// The overlap of two rectangles (possibly empty).
    #[must_use]
    pub fn intersect(&self, other: &Self) -> Self {
        Self {
            x0: self.x0.max(other.x0),
            y0: self.y0.max(other.y0),
            x1: self.x1.min(other.x1),
            y1: self.y1.min(other.y1),
        }
    }

    /// Whether pixel (x, y) lies inside.
    #[must_use]
    pub const fn contains(&self, x: i32, y: i32) -> bool {
        x >= self.x0 && x < self.x1 && y >= self.y0 && y < self.y1
    }
}

/// A sink for horizontal spans of pixels.
///
/// The scan converter calls these with spans inside [`Target::clip_rect`],
/// but implementations must still tolerate any arguments without panicking
/// or writing outside their storage (clamp or ignore), so that a `Target`
/// is safe on its own.
pub trait Target {
    /// The pixel color stored.
    type Color: Copy;

    /// The pixels this target can hold, in frame coordinates. The scan
    /// converter writes nowhere else.
    fn clip_rect(&self) -> Rect;

    /// Sets pixels `x..x+len` of row `y` to one color.
    fn fill_solid(&mut self, y: i32, x: i32, len: u32, color: Self::Color);

    /// Sets pixels `x..x+len` of row `y` to successive results of
    /// `colors`, left to right. `colors` is called exactly once per pixel
    /// that is written, in order; pixels clipped away at the left are
    /// still generated (and discarded) so that the colors stay aligned.
    fn fill_with<F: FnMut() -> Self::Color>(&mut self, y: i32, x: i32, len: u32, colors: F);

    /// Direct access to pixels `x..x+len` of row `y`, when the target
    /// stores them contiguously in memory and the whole span is inside:
    /// `None` otherwise (the default). The scan converter then depth-tests
    /// and writes each pixel in one loop instead of splitting the span
    /// into runs.
    #[inline]
    fn span_mut(&mut self, _y: i32, _x: i32, _len: u32) -> Option<&mut [Self::Color]> {
        None
    }

    /// Sets every pixel of [`Target::clip_rect`] to `color`: what
    /// [`Frame::draw`](crate::scene::Frame::draw) does first with the
    /// scene's background. The default fills it row by row with
    /// [`Target::fill_solid`]; a target whose rows lie end to end in one
    /// slice ([`Framebuffer`] with `stride == width`) fills it in one pass.
    fn clear(&mut self, color: Self::Color) {
        let r = self.clip_rect();
        if r.is_empty() {
            return;
        }
        for y in r.y0..r.y1 {
            self.fill_solid(y, r.x0, (r.x1 - r.x0) as u32, color);
        }
    }
}

impl<T: Target + ?Sized> Target for &mut T {
    type Color = T::Color;
    fn clip_rect(&self) -> Rect {
        (**self).clip_rect()
    }
    fn fill_solid(&mut self, y: i32, x: i32, len: u32, color: Self::Color) {
        (**self).fill_solid(y, x, len, color);
    }
    fn fill_with<F: FnMut() -> Self::Color>(&mut self, y: i32, x: i32, len: u32, colors: F) {
        (**self).fill_with(y, x, len, colors);
    }
    #[inline]
    fn span_mut(&mut self, y: i32, x: i32, len: u32) -> Option<&mut [Self::Color]> {
        (**self).span_mut(y, x, len)
    }
    fn clear(&mut self, color: Self::Color) {
        (**self).clear(color);
    }
}

#[cfg(test)]
mod tests;
