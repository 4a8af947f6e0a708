//! An adapter from spans to any embedded-graphics [`DrawTarget`].

use super::{Rect, Target};
use embedded_graphics::draw_target::DrawTarget;
use embedded_graphics::geometry::{Point, Size};
use embedded_graphics::primitives::Rectangle;

/// Writes spans to an embedded-graphics [`DrawTarget`] as one-row
/// rectangles with [`DrawTarget::fill_solid`] and
/// [`DrawTarget::fill_contiguous`], never pixel by pixel with `draw_iter`,
/// so display drivers that stream a window over SPI get one window per
/// span.
///
/// Spans are clipped to the target's bounding box. The first error the
/// target returns is kept (see [`DrawTargetSink::finish`]) and later spans
/// are dropped.
///
/// ```
/// use embedded_graphics::mock_display::MockDisplay;
/// use embedded_graphics::pixelcolor::Rgb565;
/// use embedded_graphics::prelude::*;
/// use sightline::target::{DrawTargetSink, Target};
///
/// // Any display driver that implements `DrawTarget<Color = Rgb565>`.
/// let mut display = MockDisplay::<Rgb565>::new();
/// let mut sink = DrawTargetSink::new(&mut display);
/// sink.fill_solid(2, 1, 3, Rgb565::RED); // row 2, columns 1..4
/// sink.finish().unwrap();
/// assert_eq!(display.get_pixel(Point::new(3, 2)), Some(Rgb565::RED));
/// assert_eq!(display.get_pixel(Point::new(4, 2)), None);
/// ```
#[derive(Debug)]
pub struct DrawTargetSink<'d, D: DrawTarget> {
    target: &'d mut D,
    clip: Rect,
    error: Option<D::Error>,
}

impl<'d, D: DrawTarget> DrawTargetSink<'d, D> {
    /// Wraps `target`; the clip rectangle is its bounding box.
    pub fn new(target: &'d mut D) -> Self {
        let bb = target.bounding_box();
        let x0 = bb.top_left.x;
        let y0 = bb.top_left.y;
        let w = i32::try_from(bb.size.width).unwrap_or(i32::MAX);
        let h = i32::try_from(bb.size.height).unwrap_or(i32::MAX);
        let clip = Rect::new(x0, y0, x0.saturating_add(w), y0.saturating_add(h));
        Self {
            target,
            clip,
            error: None,
        }
    }

    /// Finishes drawing.
    ///
    /// # Errors
    /// The first error the wrapped target reported, if any.
    pub fn finish(self) -> Result<(), D::Error> {
        match self.error {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }

    /// Clips a span to the bounding box: `(skip, x, len)`.
    fn clip_span(&self, y: i32, x: i32, len: u32) -> Option<(u32, i32, u32)> {
        if self.error.is_some() || y < self.clip.y0 || y >= self.clip.y1 {
            return None;
        }
        let a = (x as i64).max(self.clip.x0 as i64);
        let b = (x as i64 + len as i64).min(self.clip.x1 as i64);
        (a < b).then(|| ((a - x as i64) as u32, a as i32, (b - a) as u32))
    }
}

impl<D: DrawTarget> Target for DrawTargetSink<'_, D> {
    type Color = D::Color;

    fn clip_rect(&self) -> Rect {
        self.clip
    }

    fn fill_solid(&mut self, y: i32, x: i32, len: u32, color: D::Color) {
        if let Some((_, x, len)) = self.clip_span(y, x, len) {
            let area = Rectangle::new(Point::new(x, y), Size::new(len, 1));
            if let Err(e) = self.target.fill_solid(&area, color) {
                self.error = Some(e);
            }
        }
    }

    fn fill_with<F: FnMut() -> D::Color>(&mut self, y: i32, x: i32, len: u32, mut colors: F) {
        if let Some((skip, x, len)) = self.clip_span(y, x, len) {
            for _ in 0..skip {
                colors();
            }
            let area = Rectangle::new(Point::new(x, y), Size::new(len, 1));
            let it = (0..len).map(|_| colors());
            if let Err(e) = self.target.fill_contiguous(&area, it) {
                self.error = Some(e);
            }
        }
    }

    /// One `fill_solid` of the whole bounding box (a display driver's
    /// one window write) instead of one per row.
    fn clear(&mut self, color: D::Color) {
        let r = self.clip;
        if self.error.is_some() || r.is_empty() {
            return;
        }
        let size = Size::new((r.x1 - r.x0) as u32, (r.y1 - r.y0) as u32);
        let area = Rectangle::new(Point::new(r.x0, r.y0), size);
        if let Err(e) = self.target.fill_solid(&area, color) {
            self.error = Some(e);
        }
    }
}
