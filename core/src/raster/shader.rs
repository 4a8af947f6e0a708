//! Span shaders: what color each pixel of a span gets.
//!
//! A shader sees only the polygon's interpolated *varyings*: `VARYINGS` values in
//! 16.16 fixed point, set up per span and stepped by one integer add per
//! pixel. Per-pixel work is [`SpanShader::color`] plus those adds.

use crate::target::Target;
use embedded_graphics::pixelcolor::{Gray8, GrayColor, Rgb565, RgbColor};

/// Fractional bits of the varyings handed to shaders (16.16).
pub const VARYING_FRAC_BITS: u32 = 16;

/// Colors pixels from `VARYINGS` interpolated varyings.
pub trait SpanShader<const VARYINGS: usize> {
    /// The color produced.
    type Color: Copy;

    /// The range every varying is kept in: the span set-up clamps values
    /// into it (so [`Self::color`] needs no clamp). `hi − lo` must be below
    /// 2^31.
    const RANGE: (i32, i32) = (-(1 << 29), (1 << 29) - 1);

    /// Whether [`Self::shade_run`] is the default (one [`Self::color`]
    /// per pixel from linearly stepped varyings). Then the scan converter
    /// may instead call [`Self::color`] directly for the pixels that pass
    /// the depth test, fusing test and write in one loop. A shader that
    /// overrides `shade_run` with different results must set this to
    /// `false`.
    const PER_PIXEL: bool = true;

    /// `Some(color)` if every pixel gets the same color; the scan
    /// converter then uses [`Target::fill_solid`](crate::target::Target::fill_solid)
    /// and skips the varyings.
    fn solid(&self) -> Option<Self::Color> {
        None
    }

    /// The color for one pixel with varyings `v` (16.16, within
    /// [`Self::RANGE`]).
    fn color(&self, v: &[i32; VARYINGS]) -> Self::Color;

    /// Writes one run of `len` pixels starting at column `x` of row `y`,
    /// whose first pixel has varyings `start` and each next pixel `step`
    /// more. The default calls [`Self::color`] per pixel; shaders that
    /// need state along the run (subdivided perspective texturing)
    /// override it.
    #[inline]
    fn shade_run<T: Target<Color = Self::Color>>(
        &self,
        target: &mut T,
        y: i32,
        x: i32,
        len: u32,
        start: [i32; VARYINGS],
        step: [i32; VARYINGS],
    ) {
        let mut v = start;
        target.fill_with(y, x, len, || {
            let c = self.color(&v);
            for (vk, sk) in v.iter_mut().zip(&step) {
                *vk = vk.wrapping_add(*sk);
            }
            c
        });
    }
}

/// One color for the whole polygon. Ignores any varyings, so it works
/// with every vertex format, and the scan converter skips their set-up.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Flat<C>(pub C);

impl<C: Copy, const VARYINGS: usize> SpanShader<VARYINGS> for Flat<C> {
    type Color = C;

    fn solid(&self) -> Option<C> {
        Some(self.0)
    }

    #[inline]
    fn color(&self, _v: &[i32; VARYINGS]) -> C {
        self.0
    }
}

/// Gouraud shading: the first varying is the intensity 0..=255 (16.16),
/// looked up in a 256-entry color ramp; further varyings are ignored.
/// Per pixel: one add, one shift, one load. With `VARYINGS = 0` every pixel gets
/// `ramp[0]`.
///
/// Build a ramp with [`ScalableColor::ramp`] or fill one by hand (a palette).
#[cfg(feature = "gouraud")]
#[derive(Clone, Copy, Debug)]
pub struct Gouraud<'a, C> {
    ramp: &'a [C; 256],
}

#[cfg(feature = "gouraud")]
impl<'a, C: Copy> Gouraud<'a, C> {
    /// Gouraud shading through `ramp`: intensity i gives `ramp[i]`.
    #[must_use]
    pub fn new(ramp: &'a [C; 256]) -> Self {
        Self { ramp }
    }
}

#[cfg(feature = "gouraud")]
impl<C: Copy, const VARYINGS: usize> SpanShader<VARYINGS> for Gouraud<'_, C> {
    type Color = C;
    const RANGE: (i32, i32) = (0, (256 << VARYING_FRAC_BITS) - 1);

    #[inline]
    fn color(&self, v: &[i32; VARYINGS]) -> C {
        // RANGE keeps v[0] >> 16 in 0..=255 (the span set-up clamps both
        // ends); the `u8` cast only drops bits that are already zero, and a
        // u8 index cannot miss a 256-entry array. Debug builds (and so the
        // tests) check the range, so that a set-up fault that let a value
        // wrap is seen instead of being hidden by the cast. `first()` is
        // resolved at compile time (VARYINGS is a constant).
        let i = v.first().map_or(0, |&i| i >> VARYING_FRAC_BITS);
        debug_assert!(
            (0..256).contains(&i),
            "Gouraud intensity {i} left the ramp: span set-up did not clamp"
        );
        self.ramp[i as u8 as usize]
    }
}

/// Colors that can be scaled by an intensity, to build Gouraud ramps.
pub trait ScalableColor: Copy {
    /// `self` scaled by `i / 255` per channel, rounded down.
    #[must_use]
    fn scale(self, i: u8) -> Self;

    /// The 256-entry ramp from black (0) to `self` (255).
    #[must_use]
    fn ramp(self) -> [Self; 256] {
        let mut r = [self; 256];
        let mut i = 0;
        while i < 256 {
            r[i] = self.scale(i as u8);
            i += 1;
        }
        r
    }
}

/// `⌊c·i/255⌋` without a division (ARMv6-M has none): for
/// `x = c·i ≤ 255² = 65025`, `⌊x/255⌋ = (x + 1 + ⌊x/256⌋) >> 8`, checked for
/// every `(c, i)` by the test `scale_channel_is_exact`.
#[inline]
pub(crate) fn scale_channel(c: u8, i: u8) -> u8 {
    let x = c as u32 * i as u32;
    ((x + 1 + (x >> 8)) >> 8) as u8
}

#[cfg(test)]
#[test]
fn scale_channel_is_exact() {
    for c in 0..=255u8 {
        for i in 0..=255u8 {
            assert_eq!(
                scale_channel(c, i) as u32,
                c as u32 * i as u32 / 255,
                "{c}·{i}/255"
            );
        }
    }
}

impl ScalableColor for Rgb565 {
    fn scale(self, i: u8) -> Self {
        Rgb565::new(
            scale_channel(self.r(), i),
            scale_channel(self.g(), i),
            scale_channel(self.b(), i),
        )
    }
}

impl ScalableColor for Gray8 {
    fn scale(self, i: u8) -> Self {
        Gray8::new(scale_channel(self.luma(), i))
    }
}
