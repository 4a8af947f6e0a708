//! Span shaders: what color each pixel of a span gets.
//!
//! A shader sees only the polygon's interpolated *varyings*: `VARYINGS` values in
//! 16.16 fixed point (shifted left by [`SpanShader::SHIFT`]), set up per span
//! and stepped by one integer add per pixel. Per-pixel work is
//! [`SpanShader::color`] plus those adds.

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

    /// Bits every varying and its step are shifted left (wrapping) after
    /// the span set-up has kept the varying within [`Self::RANGE`], before
    /// [`Self::color`] and [`Self::shade_run`] see them. Stepping commutes
    /// with the shift modulo 2^32, so a shader sees exactly
    /// `(v << SHIFT) as u32` for the 16.16 value `v`. Default 0. A shader
    /// whose range is `0..2^(32 − SHIFT)` can then read its table index
    /// from the top bits with one shift and no mask, as [`Gouraud`] does.
    const SHIFT: u32 = 0;

    /// `Some(color)` if every pixel gets the same color; the scan
    /// converter then uses [`Target::fill_solid`](crate::target::Target::fill_solid)
    /// and skips the varyings.
    fn solid(&self) -> Option<Self::Color> {
        None
    }

    /// The color for one pixel with varyings `v` (16.16, within
    /// [`Self::RANGE`], shifted left by [`Self::SHIFT`]).
    fn color(&self, v: &[i32; VARYINGS]) -> Self::Color;

    /// Writes one run of `len` pixels starting at column `x` of row `y`,
    /// whose first pixel has varyings `start` and each next pixel `step`
    /// more (both shifted left by [`Self::SHIFT`]). The default calls
    /// [`Self::color`] per pixel; shaders that need state along the run
    /// (subdivided perspective texturing) override it.
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
        shade_per_pixel(self, target, (y, x, len), start, step);
    }
}

/// [`SpanShader::shade_run`]'s default: [`SpanShader::color`] at every
/// pixel, the varyings stepped (wrapping) from `start` by `step`. Also the
/// fallback of the shaders that override it, for targets that lend no
/// slice.
#[inline(always)]
pub(crate) fn shade_per_pixel<Sh, T, const VARYINGS: usize>(
    shader: &Sh,
    target: &mut T,
    (y, x, len): (i32, i32, u32),
    start: [i32; VARYINGS],
    step: [i32; VARYINGS],
) where
    Sh: SpanShader<VARYINGS> + ?Sized,
    T: Target<Color = Sh::Color>,
{
    let mut v = start;
    target.fill_with(y, x, len, || {
        let c = shader.color(&v);
        for (vk, sk) in v.iter_mut().zip(&step) {
            *vk = vk.wrapping_add(*sk);
        }
        c
    });
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
/// Per pixel: one add, one shift, one load (the intensity arrives shifted
/// left by 8, [`SpanShader::SHIFT`], so its integer part is the top byte).
/// With `VARYINGS = 0` every pixel gets `ramp[0]`.
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
    // RANGE is 0..2^24, so shifted left by 8 the intensity's integer part
    // is the top byte: the index is one shift, and a u32 shifted right by
    // 24 cannot miss a 256-entry array. As `(v >> 16) as u8` it was a
    // shift and a mask, and on ARMv6-M the mask (510, the byte offset's)
    // was rebuilt in the fused loop. `bash tests/mcu/run` and
    // `bash tests/x86/run`, before -> after: Gouraud + depth 20.26 -> 18.26
    // instructions per pixel on ARMv6-M (15.00 either way on the
    // Cortex-M4); the banded bunny scene frame ARMv6-M I16F16 9 095 533 ->
    // 9 087 299, but Cortex-M4 f32 6 215 679 -> 6 223 483; W2, whose spans
    // average 2.5 pixels, pays the two shifts a span: ARMv6-M 6 000 820 ->
    // 6 001 836, Cortex-M4 f32 3 756 957 -> 3 755 565, x86-64 4 013 043 ->
    // 4 016 785. x86-64 W1 (flat, which runs none of this) went from
    // 3 216 835 to 3 231 992: the shared row walk's code around it
    // compiled differently. 20 bytes more in the Gouraud firmware.
    const SHIFT: u32 = 32 - 8 - VARYING_FRAC_BITS;

    #[inline]
    fn color(&self, v: &[i32; VARYINGS]) -> C {
        // The span set-up checks the range before the shift in debug
        // builds (and so in the tests), where a set-up fault that let a
        // value wrap would show.
        let i = v.first().map_or(0, |&i| (i as u32) >> 24);
        self.ramp[i as usize]
    }

    /// [`Self::color`] at every pixel; on ARMv6-M, on a slice target,
    /// sixteen pixels a loop iteration.
    // Through `ramp_run` on ARMv6-M only. Elsewhere the default: on the
    // Cortex-M4 this route, though the scan converter does not take it
    // for depth-tested spans there, changed the code around the fused
    // loop and cost W2 (f32) 3 771 954 -> 3 804 196 instructions a frame
    // and the bunny scene frame 6 118 897 -> 6 153 072 (the tests/mcu
    // firmware's `wl` and `sf` runs under `../shared/tools/qemu-prof`).
    #[inline]
    fn shade_run<T: Target<Color = C>>(
        &self,
        target: &mut T,
        y: i32,
        x: i32,
        len: u32,
        start: [i32; VARYINGS],
        step: [i32; VARYINGS],
    ) {
        if crate::scalar::ARMV6M
            && let Some(pixels) = target.span_mut(y, x, len)
        {
            let (v, dv) = start
                .first()
                .zip(step.first())
                .map_or((0, 0), |(&v, &dv)| (v, dv));
            ramp_run(self.ramp, pixels, v as u32, dv as u32);
            return;
        }
        shade_per_pixel(self, target, (y, x, len), start, step);
    }
}

/// Writes `ramp[v_i >> 24]` into each pixel `i` of `pixels`, where
/// `v_i = v + i·dv` (wrapping): [`Gouraud`]'s colors from its shifted
/// intensity. Sixteen pixels a loop iteration, each five instructions on
/// ARMv6-M (shift, shift, load, store, step), and five for the loop: ipp
/// Gouraud + depth (tests/mcu firmware's `fill` runs under
/// `../shared/tools/qemu-prof`, the shader alone) 12.28 with eight
/// pixels an iteration, 11.96 with sixteen.
///
/// The intensity arrives shifted left by [`Gouraud`]'s `SHIFT` (8), so
/// `v` and `dv` are multiples of 256 and clearing the low byte of the `v`
/// carried to the next iteration changes nothing. It hides the
/// recurrence from LLVM's loop strength reduction, as in the depth key
/// loop: without it, each pixel's value was rewritten as `v + k·dv` from
/// the iteration's first, with the multiples kept on the stack.
#[cfg(feature = "gouraud")]
#[inline(never)]
fn ramp_run<C: Copy>(ramp: &[C; 256], pixels: &mut [C], mut v: u32, dv: u32) {
    debug_assert!(
        v.is_multiple_of(256) && dv.is_multiple_of(256),
        "Gouraud's intensities are shifted by 8"
    );
    macro_rules! pixel {
        ($($p:ident)*) => {$(
            *$p = ramp[(v >> 24) as usize];
            v = v.wrapping_add(dv);
        )*};
    }
    let mut sixteens = pixels.chunks_exact_mut(16);
    for sixteen in &mut sixteens {
        // Written out: at opt-level "s" LLVM does not unroll.
        if let [a, b, c, d, e, f, g, h, i, j, k, l, m, n, o, p] = sixteen {
            pixel!(a b c d e f g h i j k l m n o p);
        }
        v = (v >> 8) << 8;
    }
    for p in sixteens.into_remainder() {
        pixel!(p);
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

#[cfg(all(test, feature = "gouraud"))]
mod ramp_tests {
    use super::ramp_run;
    use proptest::prelude::*;
    use std::vec;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(512))]

        /// `ramp_run` writes `ramp[⌊w_i⌋]` for the 16.16 intensities
        /// `w_i = w + i·s`, all within 0..256 (the span set-up's range),
        /// handed to it shifted left by 8 as [`Gouraud`](super::Gouraud)
        /// sees them; the oracle indexes in i64. Every entry of the ramp
        /// differs, so a wrong index shows. Lengths reach past two of the
        /// loop's 16-pixel blocks and the remainder after them.
        #[test]
        fn ramp_run_indexes_each_pixel(
            w in 0i64..1 << 24,
            end in 0i64..1 << 24,
            n in 0usize..80,
        ) {
            // From `w` towards `end`, rounded towards `w`: every pixel's
            // intensity stays in range.
            let s = (end - w) / (n as i64 - 1).max(1);
            let ramp: [u16; 256] = core::array::from_fn(|i| (i as u16).wrapping_mul(257) ^ 0x5a5a);
            let mut px = vec![0u16; n];
            ramp_run(&ramp, &mut px, (w << 8) as u32, (s << 8) as u32);
            for (i, &p) in px.iter().enumerate() {
                let want = ramp[((w + i as i64 * s) >> 16) as usize];
                prop_assert_eq!(p, want, "pixel {} of {}", i, n);
            }
        }
    }
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
