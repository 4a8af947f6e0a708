use super::*;
use crate::raster::{Flat, NoDepth, ScalableColor, fill_polygon};
#[cfg(feature = "gouraud")]
use crate::raster::{Gouraud, ScreenVertex};
#[cfg(feature = "gouraud")]
use crate::test_util::sp;
use crate::test_util::sv;
use embedded_graphics::Pixel;
use embedded_graphics::draw_target::DrawTarget;
use embedded_graphics::geometry::{OriginDimensions, Point, Size};
use embedded_graphics::mock_display::MockDisplay;
use embedded_graphics::pixelcolor::{BinaryColor, Gray8};
#[cfg(feature = "gouraud")]
use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
use embedded_graphics::primitives::Rectangle;
use proptest::prelude::*;
use std::vec;

#[test]
fn framebuffer_validates_shape_once() {
    let mut buf = [0u8; 20];
    assert_eq!(
        Framebuffer::new(&mut buf, 5, 4, 4).unwrap_err(),
        BufferError::StrideTooSmall
    );
    // stride·(h−1) + w = 6·3 + 5 = 23 > 20.
    assert_eq!(
        Framebuffer::new(&mut buf, 5, 4, 6).unwrap_err(),
        BufferError::TooShort {
            needed: 23,
            len: 20
        }
    );
    // The last row needs no padding: 5·3 + 5 = 20 fits exactly.
    assert!(Framebuffer::new(&mut buf, 5, 4, 5).is_ok());
    assert_eq!(
        Framebuffer::new(&mut buf, 5, 4, usize::MAX).unwrap_err(),
        BufferError::Overflow
    );
    assert_eq!(
        Band::new(&mut buf, 5, 2, 5, i32::MAX).unwrap_err(),
        BufferError::Overflow
    );
    // Zero-sized frames are valid and hold nothing.
    let mut fb = Framebuffer::new(&mut buf, 0, 0, 0).unwrap();
    fb.fill_solid(0, 0, 10, 7);
    assert!(buf.iter().all(|&p| p == 0));
}

#[test]
fn stride_padding_is_never_written() {
    let mut buf = [0u8; 4 * 3];
    let mut fb = Framebuffer::new(&mut buf, 3, 3, 4).unwrap();
    fb.clear(1);
    fb.fill_solid(1, -5, 100, 2);
    fb.fill_with(2, 1, 10, || 3);
    assert_eq!(buf, [1, 1, 1, 0, 2, 2, 2, 0, 1, 3, 3, 0]);
}

proptest! {
    #[test]
    fn framebuffer_methods_never_panic(
        w in 0u16..9, h in 0u16..9, pad in 0usize..3, extra in 0usize..4,
        ops in proptest::collection::vec((any::<i32>(), any::<i32>(), any::<u32>()), 0..20),
    ) {
        let stride = w as usize + pad;
        let len = if h == 0 { extra } else { stride * (h as usize - 1) + w as usize + extra };
        let mut buf = vec![0u8; len];
        let mut fb = Framebuffer::new(&mut buf, w, h, stride).unwrap();
        for &(x, y, n) in &ops {
            fb.fill_solid(y, x, n, 1);
            let mut k = 0u32;
            // Colors stay aligned: pixel x gets the (x − x_start)-th value.
            fb.fill_with(y, x, n.min(1000), || { k += 1; 2 });
            let _ = fb.pixel(x, y);
        }
        // Padding and the tail past the last row stay untouched.
        for (i, &p) in buf.iter().enumerate() {
            let (row, col) = (i / stride.max(1), i % stride.max(1));
            if col >= w as usize || row >= h as usize {
                prop_assert_eq!(p, 0);
            }
        }
    }
}

#[test]
fn fill_with_keeps_colors_aligned_when_clipped() {
    let mut buf = [0u8; 4];
    let mut fb = Framebuffer::new(&mut buf, 4, 1, 4).unwrap();
    let mut k = 0;
    fb.fill_with(0, -2, 5, || {
        k += 1;
        k
    });
    // Pixels x = −2, −1 took values 1, 2; x = 0..3 got 3, 4, 5.
    assert_eq!(buf, [3, 4, 5, 0]);
}

/// Forwards `fill_contiguous` and `fill_solid` to a `MockDisplay` (which
/// panics on overdraw and out-of-bounds), records the rectangle of each
/// call, and panics if anything falls back to per-pixel `draw_iter`.
struct NoPerPixel(MockDisplay<BinaryColor>, std::vec::Vec<Rectangle>);

impl OriginDimensions for NoPerPixel {
    fn size(&self) -> Size {
        Size::new(12, 8)
    }
}

impl DrawTarget for NoPerPixel {
    type Color = BinaryColor;
    type Error = core::convert::Infallible;
    fn draw_iter<I: IntoIterator<Item = Pixel<BinaryColor>>>(
        &mut self,
        _: I,
    ) -> Result<(), Self::Error> {
        panic!("per-pixel draw_iter used");
    }
    fn fill_contiguous<I: IntoIterator<Item = BinaryColor>>(
        &mut self,
        area: &Rectangle,
        colors: I,
    ) -> Result<(), Self::Error> {
        self.1.push(*area);
        self.0.fill_contiguous(area, colors)
    }
    fn fill_solid(&mut self, area: &Rectangle, color: BinaryColor) -> Result<(), Self::Error> {
        self.1.push(*area);
        self.0.fill_solid(area, color)
    }
}

#[test]
fn draw_target_sink_uses_span_fills_and_clips() {
    let mut d = NoPerPixel(MockDisplay::new(), vec![]);
    {
        let mut sink = DrawTargetSink::new(&mut d);
        assert_eq!(sink.clip_rect(), Rect::new(0, 0, 12, 8));
        // Partly outside the 12×8 bounding box on the right and bottom.
        // Hypotenuse x + y = 17: row j covers columns 2..16−j.
        let tri = [sv(2.0, 1.0), sv(16.0, 1.0), sv(2.0, 15.0)];
        fill_polygon(&mut sink, &mut NoDepth, &Flat(BinaryColor::On), &tri);
        // Gouraud goes through fill_contiguous.
        #[cfg(feature = "gouraud")]
        {
            let ramp = [BinaryColor::Off; 256];
            let v = |x: f64, y: f64| ScreenVertex::new(sp(x), sp(y), 0, [0]);
            let q = [v(0.0, 0.0), v(2.0, 0.0), v(2.0, 1.0), v(0.0, 1.0)];
            fill_polygon(&mut sink, &mut NoDepth, &Gouraud::new(&ramp), &q);
        }
        sink.finish().unwrap();
    }
    // One call per row: seven flat spans, one Gouraud span.
    let gouraud = cfg!(feature = "gouraud");
    assert_eq!(d.1.len(), 7 + gouraud as usize);
    assert!(d.1.iter().all(|r| r.size.height == 1), "{:?}", d.1);
    d.0.assert_pattern(&[
        if gouraud {
            "..          "
        } else {
            "            "
        }, //
        "  ##########", //
        "  ##########", //
        "  ##########", //
        "  ##########", //
        "  ######### ", //
        "  ########  ", //
        "  #######   ", //
    ]);
}

/// `Target::clear` sets exactly the clip rectangle, whichever route the
/// target takes: the default (row by row), a gapless framebuffer's one
/// pass (the slice beyond `width·height` is not the frame's), a padded
/// one (row by row, padding kept), a band, the byte-order encoder and the
/// `DrawTarget` sink's one rectangle fill.
#[test]
fn target_clear_fills_the_clip_rect_only() {
    fn via_trait<T: Target>(t: &mut T, c: T::Color) {
        t.clear(c);
    }
    let mut buf = [0u8; 14];
    via_trait(&mut Framebuffer::new(&mut buf, 3, 4, 3).unwrap(), 5);
    assert_eq!(buf, [5, 5, 5, 5, 5, 5, 5, 5, 5, 5, 5, 5, 0, 0]);
    let mut buf = [0u8; 11];
    via_trait(&mut Framebuffer::new(&mut buf, 3, 3, 4).unwrap(), 6);
    assert_eq!(buf, [6, 6, 6, 0, 6, 6, 6, 0, 6, 6, 6]);
    let mut buf = [0u8; 6];
    via_trait(&mut Band::new(&mut buf, 2, 2, 3, 40).unwrap(), 7);
    assert_eq!(buf, [7, 7, 0, 7, 7, 0]);
    // The default route, through a target that has no override of its own.
    // (MockTarget panics on a write outside it or a second write.)
    let mut m = crate::test_util::MockTarget::new(4, 3);
    via_trait(&mut m, '#');
    m.assert_pattern(&["####"; 3]);
    // One fill_solid of the whole 12×8 box, not one per row.
    let mut d = NoPerPixel(MockDisplay::new(), vec![]);
    let mut sink = DrawTargetSink::new(&mut d);
    via_trait(&mut sink, BinaryColor::On);
    sink.finish().unwrap();
    assert_eq!(d.1, [Rectangle::new(Point::zero(), Size::new(12, 8))]);
    d.0.assert_pattern(&["############"; 8]);
}

#[cfg(feature = "gouraud")]
#[test]
fn rgb565_framebuffer_with_gouraud() {
    let mut buf = [Rgb565::BLACK; 16];
    let mut fb = Framebuffer::new(&mut buf, 4, 4, 4).unwrap();
    let ramp = Rgb565::RED.ramp();
    let v = |x: f64, y: f64, i: i32| ScreenVertex::new(sp(x), sp(y), 0, [i << 16]);
    let q = [
        v(0.0, 0.0, 0),
        v(4.0, 0.0, 255),
        v(4.0, 4.0, 255),
        v(0.0, 4.0, 0),
    ];
    fill_polygon(&mut fb, &mut NoDepth, &Gouraud::new(&ramp), &q);
    // Red increases left to right, green and blue stay zero.
    let reds: std::vec::Vec<u8> = (0..4).map(|x| fb.pixel(x, 2).unwrap().r()).collect();
    assert!(reds.windows(2).all(|w| w[0] < w[1]), "{reds:?}");
    assert!(buf.iter().all(|c| c.g() == 0 && c.b() == 0));
}

#[test]
fn gray8_framebuffer() {
    let mut g = [Gray8::new(0); 6];
    let mut fb = Framebuffer::new(&mut g, 3, 2, 3).unwrap();
    fill_polygon(
        &mut fb,
        &mut NoDepth,
        &Flat(Gray8::new(200)),
        &[sv(0.0, 0.0), sv(3.0, 0.0), sv(0.0, 2.0)],
    );
    assert_eq!(fb.pixel(0, 0), Some(Gray8::new(200)));
    assert_eq!(fb.pixel(2, 1), Some(Gray8::new(0)));
    assert_eq!(Gray8::new(255).ramp()[128], Gray8::new(128));
}

#[test]
fn fill_solid_writes_exactly_the_clipped_span_for_every_length() {
    // The unrolled fill (32 stores per step, then 16, then the remainder)
    // must write exactly [x, x + len) ∩ [0, w) of the row, for spans
    // shorter than, equal to and longer than multiples of 16 and 32 (up
    // to two whole 32-pixel steps and more), and leave the stride padding
    // and the other rows alone.
    let (w, h, stride) = (83u16, 3u16, 86usize);
    for x in -9..86 {
        for len in 0..100u32 {
            let mut buf = vec![0u16; stride * h as usize];
            let mut fb = Framebuffer::new(&mut buf, w, h, stride).unwrap();
            fb.fill_solid(1, x, len, 7);
            for (i, &p) in buf.iter().enumerate() {
                let (row, col) = (i / stride, (i % stride) as i32);
                let inside =
                    row == 1 && col < w as i32 && col >= x && (col as i64) < x as i64 + len as i64;
                assert_eq!(
                    p,
                    if inside { 7 } else { 0 },
                    "x {x} len {len} at {row},{col}"
                );
            }
        }
    }
}

/// The two-pixel word fill writes exactly the row, at every start
/// alignment and length around its 16- and 32-word steps, for 2-byte
/// pixel types of alignment 2 and 1 and one with a padding byte; the
/// neighbours on both sides keep their values. (CI also runs it under
/// Miri: `cargo +nightly-2026-05-20 miri test -p sightline --lib
/// pair_fill`.)
#[test]
fn pair_fill_writes_exactly_the_row() {
    fn check<C: Copy + PartialEq + core::fmt::Debug>(old: C, new: C) {
        let lens = if cfg!(miri) { 0..70 } else { 0..140 };
        for start in 0..4 {
            for len in lens.clone() {
                let mut buf = vec![old; start + len + 3];
                fill_row(&mut buf[start..start + len], new);
                for (i, &p) in buf.iter().enumerate() {
                    let inside = (start..start + len).contains(&i);
                    assert_eq!(
                        p,
                        if inside { new } else { old },
                        "start {start} len {len} at {i}"
                    );
                }
            }
        }
    }
    /// One byte of value and one of padding.
    #[derive(Clone, Copy, Debug, PartialEq)]
    #[repr(C, align(2))]
    struct Padded(u8);
    fn fill_row<C: Copy>(row: &mut [C], color: C) {
        let w = row.len() as u16;
        let mut fb = Framebuffer::new(row, w, 1, w as usize).unwrap();
        Target::clear(&mut fb, color);
    }
    check::<u16>(0x1234, 0xabcd);
    check::<[u8; 2]>([1, 2], [3, 4]);
    check::<Padded>(Padded(5), Padded(6));
    {
        use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
        check::<Rgb565>(Rgb565::BLACK, Rgb565::new(3, 50, 9));
    }
    // Other sizes take the plain fill.
    check::<u8>(1, 2);
    check::<u32>(1, 2);
}
