//! RGB565 pixels as raw words or byte pairs in a chosen byte order, for
//! display controllers (ST7789, ILI9341, GC9A01 …) that take RGB565 over
//! SPI high byte first.

use super::{Rect, Target};
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::IntoStorage;

/// The order of the two bytes of an RGB565 pixel **in memory**, which is
/// the order a byte-wise SPI or DMA transfer sends them in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ByteOrder {
    /// High byte first (`RRRRRGGG`, then `GGGBBBBB`): what SPI panels such
    /// as the ST7789 and ILI9341 expect in their default 16-bit mode.
    BigEndian,
    /// Low byte first: the native `u16` layout of Cortex-M and RISC-V, for
    /// a panel or a DMA set up for 16-bit transfers.
    LittleEndian,
}

/// A raw storage element that holds one RGB565 pixel: `u16` words or
/// `[u8; 2]` byte pairs.
pub trait Rgb565Storage: Copy {
    /// `color` in `order`, as this element is laid out in memory.
    fn encode(color: Rgb565, order: ByteOrder) -> Self;
}

impl Rgb565Storage for u16 {
    #[inline]
    fn encode(color: Rgb565, order: ByteOrder) -> Self {
        let raw = color.into_storage();
        // `to_be`/`to_le` give the word whose in-memory bytes are in that
        // order on this target, whatever its endianness.
        match order {
            ByteOrder::BigEndian => raw.to_be(),
            ByteOrder::LittleEndian => raw.to_le(),
        }
    }
}

impl Rgb565Storage for [u8; 2] {
    #[inline]
    fn encode(color: Rgb565, order: ByteOrder) -> Self {
        let raw = color.into_storage();
        match order {
            ByteOrder::BigEndian => raw.to_be_bytes(),
            ByteOrder::LittleEndian => raw.to_le_bytes(),
        }
    }
}

/// Writes [`Rgb565`] spans into a target of raw words or byte pairs
/// ([`Framebuffer`](super::Framebuffer) or [`Band`](super::Band) of `u16`
/// or `[u8; 2]`), encoding each pixel in the chosen [`ByteOrder`], so the
/// buffer can go to an SPI display as it is.
///
/// Each pixel is encoded as it is written (a byte swap for the non-native
/// order): the target offers no direct span access, so depth-tested spans
/// take the run-splitting path. A byte buffer `&mut [u8]` becomes the
/// `&mut [[u8; 2]]` this needs with `as_chunks_mut` (Rust 1.88) or by
/// declaring the buffer as `[[u8; 2]; N]`.
///
/// ```
/// use embedded_graphics::pixelcolor::Rgb565;
/// use sightline::target::{Band, ByteOrder, Rgb565Encoder, Target};
///
/// // One 240-pixel, 16-row strip of a 240×240 ST7789 frame, sent high
/// // byte first.
/// let mut words = [0u16; 240 * 16];
/// let band = Band::new(&mut words, 240, 16, 240, 0).unwrap();
/// let mut spi = Rgb565Encoder::new(band, ByteOrder::BigEndian);
/// spi.fill_solid(0, 0, 1, Rgb565::new(31, 0, 0)); // pure red: 0xF800
/// assert_eq!(words[0].to_ne_bytes(), [0xF8, 0x00]);
/// ```
#[derive(Debug)]
pub struct Rgb565Encoder<T> {
    inner: T,
    order: ByteOrder,
}

impl<T> Rgb565Encoder<T>
where
    T: Target,
    T::Color: Rgb565Storage,
{
    /// Wraps `inner`, writing pixels in `order`.
    pub fn new(inner: T, order: ByteOrder) -> Self {
        Self { inner, order }
    }

    /// The byte order pixels are written in.
    #[must_use]
    pub fn order(&self) -> ByteOrder {
        self.order
    }

    /// The wrapped target (to move a band, or to read the buffer).
    pub fn inner_mut(&mut self) -> &mut T {
        &mut self.inner
    }

    /// The wrapped target.
    #[must_use]
    pub fn into_inner(self) -> T {
        self.inner
    }
}

impl<T> Target for Rgb565Encoder<T>
where
    T: Target,
    T::Color: Rgb565Storage,
{
    type Color = Rgb565;

    fn clip_rect(&self) -> Rect {
        self.inner.clip_rect()
    }

    #[inline]
    fn fill_solid(&mut self, y: i32, x: i32, len: u32, color: Rgb565) {
        let order = self.order;
        self.inner
            .fill_solid(y, x, len, T::Color::encode(color, order));
    }

    #[inline]
    fn fill_with<F: FnMut() -> Rgb565>(&mut self, y: i32, x: i32, len: u32, mut colors: F) {
        let order = self.order;
        self.inner
            .fill_with(y, x, len, || T::Color::encode(colors(), order));
    }

    fn clear(&mut self, color: Rgb565) {
        let order = self.order;
        self.inner.clear(T::Color::encode(color, order));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::target::{Band, Framebuffer};
    use std::vec;

    #[test]
    fn pixels_are_laid_out_in_the_chosen_byte_order() {
        // Exact bit patterns, independent of the encoder: RGB565 is
        // r << 11 | g << 5 | b.
        let c = Rgb565::new(0b10110, 0b011001, 0b00111);
        let raw: u16 = 0b10110 << 11 | 0b011001 << 5 | 0b00111;
        let (hi, lo) = ((raw >> 8) as u8, raw as u8);
        let mut words = [0u16; 4];
        let mut bytes = [[0u8; 2]; 4];
        {
            let fb = Framebuffer::new(&mut words, 4, 1, 4).unwrap();
            let mut t = Rgb565Encoder::new(fb, ByteOrder::BigEndian);
            t.fill_solid(0, 0, 2, c);
            let mut n = 0;
            t.fill_with(0, 2, 2, || {
                n += 1;
                c
            });
            assert_eq!(n, 2);
        }
        assert!(
            words.iter().all(|w| w.to_ne_bytes() == [hi, lo]),
            "{words:x?}"
        );
        {
            let fb = Framebuffer::new(&mut bytes, 4, 1, 4).unwrap();
            let mut t = Rgb565Encoder::new(fb, ByteOrder::LittleEndian);
            t.fill_solid(0, 0, 4, c);
        }
        assert!(bytes.iter().all(|b| *b == [lo, hi]), "{bytes:x?}");
        {
            let fb = Framebuffer::new(&mut bytes, 4, 1, 4).unwrap();
            let mut t = Rgb565Encoder::new(fb, ByteOrder::BigEndian);
            t.fill_with(0, 1, 1, || c);
            assert_eq!(t.order(), ByteOrder::BigEndian);
        }
        assert_eq!(bytes[1], [hi, lo]);
        assert_eq!(bytes[0], [lo, hi]);
    }

    #[test]
    fn clear_encodes_once_for_the_whole_target() {
        let c = Rgb565::new(0b10110, 0b011001, 0b00111);
        let raw: u16 = 0b10110 << 11 | 0b011001 << 5 | 0b00111;
        let mut words = [0u16; 7];
        {
            let fb = Framebuffer::new(&mut words, 3, 2, 3).unwrap();
            Rgb565Encoder::new(fb, ByteOrder::BigEndian).clear(c);
        }
        let be = u16::from_ne_bytes(raw.to_be_bytes());
        assert_eq!(words, [be, be, be, be, be, be, 0]);
    }

    #[test]
    fn a_band_clips_and_keeps_frame_coordinates() {
        let mut words = vec![0u16; 3 * 2];
        let band = Band::new(&mut words, 3, 2, 3, 10).unwrap();
        let mut t = Rgb565Encoder::new(band, ByteOrder::BigEndian);
        assert_eq!(t.clip_rect(), Rect::new(0, 10, 3, 12));
        // Outside the band, partly left of it, beyond the right edge:
        // clipped, never a panic.
        t.fill_solid(9, 0, 3, Rgb565::new(31, 0, 0));
        t.fill_solid(11, -2, 10, Rgb565::new(0, 0, 31));
        t.fill_with(12, 0, 3, || Rgb565::new(31, 0, 0));
        let blue = 0x001fu16.to_be();
        assert_eq!(words, [0, 0, 0, blue, blue, blue]);
    }
}
