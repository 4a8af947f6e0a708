//! The one texel store and nearest-texel sampler: what the raster's
//! texture shaders, the column caster and both paths of the scene read.
//!
//! Texel (i, j) covers `[i, i+1) × [j, j+1)` in texture coordinates, so a
//! sample at (u, v) reads texel `(⌊u⌋, ⌊v⌋)` after wrapping. The wrap mode
//! is a type parameter ([`Repeat`], [`RepeatPow2`], [`Clamp`]): no
//! per-pixel branch on it, and the power-of-two fast path is one AND per
//! axis. This module depends on nothing else in the crate.

use core::fmt;
use core::fmt::Debug;

/// Why a slice cannot be used as a texture of the given shape.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum TextureError {
    /// The width or the height is zero: there is no texel to sample.
    Empty,
    /// `stride < width`: rows would overlap.
    StrideTooSmall,
    /// The slice is shorter than `stride·(height−1) + width`.
    TooShort {
        /// Texels needed.
        needed: usize,
        /// Texels supplied.
        len: usize,
    },
    /// `stride·(height−1) + width` does not fit in `usize`.
    Overflow,
}

impl fmt::Display for TextureError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Empty => f.write_str("texture width or height is zero"),
            Self::StrideTooSmall => f.write_str("texture stride is smaller than its width"),
            Self::TooShort { needed, len } => {
                write!(
                    f,
                    "texture slice holds {len} texels, its shape needs {needed}"
                )
            }
            Self::Overflow => f.write_str("texture shape overflows"),
        }
    }
}

impl core::error::Error for TextureError {}

/// A read-only texture over a caller-supplied slice of texels `C`,
/// row-major with a stride.
///
/// # Guarantees
///
/// Validated once by [`Texture::new`]; [`Texture::sample`] never panics
/// and never reads outside the slice, for any texture coordinates and any
/// [`Wrap`].
///
/// # Examples
/// ```
/// use sightline::texture::{Clamp, Repeat, RepeatPow2, Texture};
/// // 2×2 texels in rows of 3 (the third column is padding).
/// const T: Texture<'static, u8> = match Texture::new(&[1, 2, 0, 3, 4], 2, 2, 3) {
///     Ok(t) => t,
///     Err(_) => panic!("bad texture"),
/// };
/// assert_eq!(T.sample::<Repeat>(-1, 0), 2);
/// assert_eq!(T.sample::<RepeatPow2>(2, 3), 3);
/// assert_eq!(T.sample::<Clamp>(9, 9), 4);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Texture<'a, C> {
    texels: &'a [C],
    /// The first texel: what `sample` would return if an index were ever
    /// out of range (it cannot be; this avoids a panicking index).
    fallback: C,
    width: u16,
    height: u16,
    stride: usize,
}

impl<'a, C: Copy> Texture<'a, C> {
    /// Wraps `texels` as `width`×`height` texels, rows `stride` apart.
    /// A `const fn`, so that built-in textures are checked at compile time.
    ///
    /// # Errors
    /// [`TextureError::Empty`] for a zero width or height,
    /// [`TextureError::StrideTooSmall`], [`TextureError::TooShort`],
    /// [`TextureError::Overflow`].
    pub const fn new(
        texels: &'a [C],
        width: u16,
        height: u16,
        stride: usize,
    ) -> Result<Self, TextureError> {
        if width == 0 || height == 0 {
            return Err(TextureError::Empty);
        }
        if stride < width as usize {
            return Err(TextureError::StrideTooSmall);
        }
        let needed = match stride.checked_mul(height as usize - 1) {
            Some(n) => match n.checked_add(width as usize) {
                Some(n) => n,
                None => return Err(TextureError::Overflow),
            },
            None => return Err(TextureError::Overflow),
        };
        // `needed ≥ width ≥ 1`, so a slice that passes is not empty.
        let fallback = match texels {
            [first, ..] if texels.len() >= needed => *first,
            _ => {
                return Err(TextureError::TooShort {
                    needed,
                    len: texels.len(),
                });
            }
        };
        Ok(Self {
            texels,
            fallback,
            width,
            height,
            stride,
        })
    }

    /// Width in texels.
    #[must_use]
    pub const fn width(&self) -> u16 {
        self.width
    }

    /// Height in texels.
    #[must_use]
    pub const fn height(&self) -> u16 {
        self.height
    }

    /// Elements from one row to the next.
    #[must_use]
    pub const fn stride(&self) -> usize {
        self.stride
    }

    /// The texel slice as given to [`Texture::new`].
    #[must_use]
    pub const fn texels(&self) -> &'a [C] {
        self.texels
    }

    /// Whether `W` accepts both sides ([`RepeatPow2`] needs powers of
    /// two); the texture shaders and the scene check this once.
    #[must_use]
    pub fn accepts<W: Wrap>(&self) -> bool {
        W::accepts(self.width) && W::accepts(self.height)
    }

    /// The texel at integer texel coordinates (u, v), wrapped with `W`:
    /// texel `(W::wrap(u, width), W::wrap(v, height))`. Any `W` stays in
    /// bounds; it tiles as documented only for sides `W` accepts.
    #[inline]
    #[must_use]
    pub fn sample<W: Wrap>(&self, u: i32, v: i32) -> C {
        let x = W::wrap(u, self.width) as usize;
        let y = W::wrap(v, self.height) as usize;
        // x < width, y < height, so the index is below
        // stride·(height−1) + width ≤ len (validated in `new`); `get`
        // keeps that local.
        match self.texels.get(y * self.stride + x) {
            Some(&c) => c,
            None => self.fallback,
        }
    }
}

/// A power-of-two texture sampled with masks ([`Texture::masked`]): the
/// texture shaders' inner loop for [`RepeatPow2`], with no multiply and
/// no bounds check per texel.
#[cfg(feature = "texture")]
#[derive(Clone, Copy, Debug)]
pub(crate) struct MaskedTexels<'a, C> {
    /// At least `2^bits` texels.
    texels: &'a [C],
    /// log2 of `stride·height`, at most 16.
    bits: u32,
    /// log2 of the stride.
    row_shift: u32,
    /// `width − 1`.
    u_mask: u32,
    /// `(height − 1)·stride`.
    v_mask: u32,
}

#[cfg(feature = "texture")]
impl<'a, C: Copy> Texture<'a, C> {
    /// The texture as [`MaskedTexels`] when `W` masks ([`Wrap::MASKS`]),
    /// both sides and the stride are powers of two, `stride·height` is at
    /// most 2^16 texels and the slice holds that many; else `None`.
    /// Sampling it gives exactly what [`Texture::sample`]`::<W>` gives.
    #[must_use]
    pub(crate) fn masked<W: Wrap>(&self) -> Option<MaskedTexels<'a, C>> {
        let (w, h, s) = (self.width as usize, self.height as usize, self.stride);
        if !(W::MASKS && w.is_power_of_two() && h.is_power_of_two() && s.is_power_of_two()) {
            return None;
        }
        let n = s.checked_mul(h).filter(|&n| n <= 1 << 16)?;
        Some(MaskedTexels {
            texels: self.texels.get(..n)?,
            bits: n.trailing_zeros(),
            row_shift: s.trailing_zeros(),
            u_mask: w as u32 - 1,
            v_mask: ((h - 1) * s) as u32,
        })
    }
}

#[cfg(feature = "texture")]
impl<C: Copy> MaskedTexels<'_, C> {
    /// Fills `run` with the texels at (u, v) = `a`, `a + d`, `a + 2d`, …
    /// in 16.16 texels (stepped modulo 2^32): pixel `j` is
    /// `Texture::sample::<RepeatPow2>((a.0 + j·d.0) >> 16, (a.1 + j·d.1) >> 16)`.
    ///
    /// v is kept as `v·stride`: the row's bits of `(v·stride) >> 16`
    /// are those of `⌊v⌋ mod height` times the stride, because
    /// `log2(stride·height) ≤ 16` keeps them inside 32 bits, so one mask
    /// gives the row offset.
    #[inline(always)]
    pub(crate) fn fill_run(&self, run: &mut [C], a: (i32, i32), d: (i32, i32)) {
        // `t.len()` is a power of two, so `i & (t.len() − 1)` (a no-op:
        // i ≤ (height−1)·stride + width − 1) needs no bounds check.
        let n = 1usize << (self.bits & 31);
        let Some(t) = self.texels.get(..n) else {
            return;
        };
        let last = n - 1;
        let (mut u, mut v) = (a.0 as u32, (a.1 as u32) << self.row_shift);
        let (du, dv) = (d.0 as u32, (d.1 as u32) << self.row_shift);
        let (vm, um) = (self.v_mask, self.u_mask);
        let texel = |u: u32, v: u32| {
            let i = ((v >> 16) & vm) | ((u >> 16) & um);
            t.get(i as usize & last).copied()
        };
        // Two pixels an iteration: the masks, the texels and the step
        // reloaded from the stack (ARMv6-M has seven low registers for
        // ten values here) serve both. `bash tests/mcu/run`, ipp persp16
        // and persp16 + depth: ARMv6-M 42.56 -> 41.74 and 49.18 -> 48.37,
        // Cortex-M4 26.00 -> 23.06 and 33.50 -> 30.56.
        let mut pairs = run.chunks_exact_mut(2);
        for pair in &mut pairs {
            if let [p0, p1] = pair {
                if let Some(c) = texel(u, v) {
                    *p0 = c;
                }
                u = u.wrapping_add(du);
                v = v.wrapping_add(dv);
                if let Some(c) = texel(u, v) {
                    *p1 = c;
                }
                u = u.wrapping_add(du);
                v = v.wrapping_add(dv);
            }
        }
        for p in pairs.into_remainder() {
            if let Some(c) = texel(u, v) {
                *p = c;
            }
        }
    }

    /// `run[j] = Texture::sample::<RepeatPow2>(u[j], v[j])` for integer
    /// texel coordinates (the texels exact perspective mode steps to),
    /// over the shortest of the three slices.
    ///
    /// `stride·height` is `2^bits`, so the low `bits` bits of `v·stride`
    /// are `(v mod height)·stride` for any `v` (two's complement), and
    /// `u & (width − 1)` lies below the stride: one OR joins them, and the
    /// mask by `2^bits − 1` that bounds the index changes nothing.
    #[cfg(feature = "perspective")]
    #[inline(always)]
    pub(crate) fn sample_run(&self, run: &mut [C], u: &[i16], v: &[i16]) {
        // Two pixels an iteration on ARMv6-M, whose seven low registers
        // cannot hold the loop: the masks and the texture, reloaded from
        // the stack, serve both (ipp persp 54.71 one at a time, 52.38 in
        // pairs: the tests/mcu firmware's `fill persp full|half` under
        // QEMU, counted by `../shared/tools/qemu-prof`). One at a time
        // elsewhere.
        self.sample_run_by::<{ PAIRS }>(run, u, v);
    }

    /// [`Self::sample_run`], two pixels an iteration with `PAIRS` (both
    /// routes tested on the host).
    #[cfg(feature = "perspective")]
    #[inline(always)]
    pub(crate) fn sample_run_by<const PAIRS: bool>(&self, run: &mut [C], u: &[i16], v: &[i16]) {
        let n = 1usize << (self.bits & 31);
        let Some(t) = self.texels.get(..n) else {
            return;
        };
        let last = n - 1;
        let (rs, um) = (self.row_shift & 31, self.u_mask);
        // Each coordinate's low 16 bits are enough (both sides divide
        // 2^16); zero-extended, ARMv6-M loads them with an offset.
        sample_coords::<_, PAIRS>(run, u, v, |x, y| {
            let i = (((y as u16 as u32) << rs) | (x as u16 as u32 & um)) as usize;
            t.get(i & last).copied()
        });
    }
}

/// Whether the texel-coordinate sampling loops ([`sample_coords`]) take two
/// pixels an iteration: on ARMv6-M, whose seven low registers cannot hold
/// them, so values reloaded from the stack serve two pixels.
#[cfg(feature = "perspective")]
pub(crate) const PAIRS: bool = crate::scalar::ARMV6M;

/// `run[j] = texel(u[j], v[j])` where `texel` answers, over the shortest of
/// the three slices; two pixels an iteration with `P` ([`PAIRS`]). The one
/// loop of exact perspective mode's sampling pass, masked or not.
#[cfg(feature = "perspective")]
#[inline(always)]
pub(crate) fn sample_coords<C, const P: bool>(
    run: &mut [C],
    u: &[i16],
    v: &[i16],
    texel: impl Fn(i16, i16) -> Option<C>,
) {
    let m = run.len().min(u.len()).min(v.len());
    let (Some(run), Some(u), Some(v)) = (run.get_mut(..m), u.get(..m), v.get(..m)) else {
        return;
    };
    if P {
        let mut pairs = run.chunks_exact_mut(2);
        for ((p, x), y) in (&mut pairs).zip(u.chunks_exact(2)).zip(v.chunks_exact(2)) {
            if let ([p0, p1], [x0, x1], [y0, y1]) = (p, x, y) {
                if let Some(c) = texel(*x0, *y0) {
                    *p0 = c;
                }
                if let Some(c) = texel(*x1, *y1) {
                    *p1 = c;
                }
            }
        }
        // An odd run's last pixel.
        if let (Some(p), Some(&x), Some(&y)) =
            (pairs.into_remainder().first_mut(), u.last(), v.last())
        {
            if let Some(c) = texel(x, y) {
                *p = c;
            }
        }
    } else {
        for ((p, &x), &y) in run.iter_mut().zip(u).zip(v) {
            if let Some(c) = texel(x, y) {
                *p = c;
            }
        }
    }
}

/// How integer texel coordinates outside the texture map inside.
pub trait Wrap: Copy + Debug + Default {
    /// Whether [`Self::wrap`] is `i & (n − 1)` for every accepted `n`.
    /// Shaders may then index a power-of-two texture with masks on
    /// shifted coordinates instead of calling `wrap` (the texture
    /// shaders do). Default `false`; only [`RepeatPow2`] sets it.
    const MASKS: bool = false;
    /// Whether a texture side of `n` texels is supported.
    fn accepts(n: u16) -> bool;
    /// Maps `i` into `0..n` (`n ≥ 1`; the result is below `n` for every
    /// `n ≥ 1`, and is the documented wrap when `n` is accepted).
    fn wrap(i: i32, n: u16) -> u16;
}

/// Tiles the texture: `i mod n`.
#[derive(Clone, Copy, Debug, Default)]
pub struct Repeat;

/// Tiles a texture whose sides are powers of two: `i & (n − 1)`, one AND.
#[derive(Clone, Copy, Debug, Default)]
pub struct RepeatPow2;

/// Repeats the edge texels: `clamp(i, 0, n − 1)`.
#[derive(Clone, Copy, Debug, Default)]
pub struct Clamp;

impl Wrap for Repeat {
    fn accepts(n: u16) -> bool {
        n > 0
    }
    #[inline]
    fn wrap(i: i32, n: u16) -> u16 {
        i.rem_euclid(n.max(1) as i32) as u16
    }
}

impl Wrap for RepeatPow2 {
    const MASKS: bool = true;
    fn accepts(n: u16) -> bool {
        n.is_power_of_two()
    }
    #[inline]
    fn wrap(i: i32, n: u16) -> u16 {
        // An AND never exceeds its mask, so the result is ≤ n − 1 for any
        // n ≥ 1 (in bounds); it equals i mod n only for powers of two,
        // which is what `accepts` checks.
        (i & (n.max(1) as i32 - 1)) as u16
    }
}

impl Wrap for Clamp {
    fn accepts(n: u16) -> bool {
        n > 0
    }
    #[inline]
    fn wrap(i: i32, n: u16) -> u16 {
        i.clamp(0, n as i32 - 1) as u16
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    #[cfg(feature = "texture")]
    use proptest::prelude::*;

    #[cfg(feature = "texture")]
    proptest! {
        /// The masked sampler is `sample::<RepeatPow2>` at every pixel of a
        /// run, for any start and step (wrapping ones included) and any
        /// power-of-two shape it accepts, with row padding; and it
        /// refuses exactly the shapes its doc excludes.
        #[test]
        fn masked_run_is_sample(
            lw in 0u32..6, lh in 0u32..6, pad in 0u32..3, short in any::<bool>(),
            a in any::<(i32, i32)>(), d in any::<(i32, i32)>(), small in any::<bool>(),
            len in 0usize..40,
        ) {
            let (w, h, s) = (1usize << lw, 1usize << lh, 1usize << (lw + pad));
            // `short`: only stride·(height−1) + width texels, which
            // `Texture::new` accepts and the masked sampler must refuse
            // when that is fewer than stride·height.
            let n = if short { s * (h - 1) + w } else { s * h };
            let texels: std::vec::Vec<u16> = (0..n as u32).map(|i| (i * 40503 % 65521) as u16).collect();
            let tex = Texture::new(&texels, w as u16, h as u16, s).unwrap();
            let d = if small { (d.0 >> 12, d.1 >> 12) } else { d };
            match tex.masked::<RepeatPow2>() {
                None => prop_assert!(n < s * h),
                Some(m) => {
                    prop_assert_eq!(n, s * h);
                    let mut run = std::vec![0u16; len];
                    m.fill_run(&mut run, a, d);
                    for (j, &got) in run.iter().enumerate() {
                        let u = a.0.wrapping_add(d.0.wrapping_mul(j as i32));
                        let v = a.1.wrapping_add(d.1.wrapping_mul(j as i32));
                        prop_assert_eq!(got, tex.sample::<RepeatPow2>(u >> 16, v >> 16), "pixel {}", j);
                    }
                }
            }
            prop_assert!(tex.masked::<Repeat>().is_none());
        }
    }

    #[cfg(feature = "perspective")]
    proptest! {
        /// The masked sampler of integer texels (exact perspective mode's)
        /// is `sample::<RepeatPow2>` at every pixel, one or two pixels an
        /// iteration, for any i16 coordinates and any power-of-two shape
        /// up to 2^16 texels, with row padding.
        #[test]
        fn masked_texels_are_sample(
            lw in 0u32..9, lh in 0u32..9, pad in 0u32..2,
            uv in proptest::collection::vec(any::<(i16, i16)>(), 0..40),
        ) {
            let (w, h, s) = (1usize << lw, 1usize << lh, 1usize << (lw + pad));
            let n = s * h;
            let texels: std::vec::Vec<u16> =
                (0..n as u32).map(|i| (i.wrapping_mul(40503) % 65521) as u16).collect();
            let tex = Texture::new(&texels, w as u16, h as u16, s).unwrap();
            let (u, v): (std::vec::Vec<i16>, std::vec::Vec<i16>) = uv.iter().copied().unzip();
            match tex.masked::<RepeatPow2>() {
                None => prop_assert!(n > 1 << 16),
                Some(m) => {
                    for pairs in [false, true] {
                        let mut run = std::vec![0u16; uv.len()];
                        if pairs {
                            m.sample_run_by::<true>(&mut run, &u, &v);
                        } else {
                            m.sample_run_by::<false>(&mut run, &u, &v);
                        }
                        for (j, &got) in run.iter().enumerate() {
                            let want = tex.sample::<RepeatPow2>(u[j].into(), v[j].into());
                            prop_assert_eq!(got, want, "pixel {} pairs {}", j, pairs);
                        }
                    }
                }
            }
        }
    }

    #[cfg(feature = "perspective")]
    #[test]
    fn masked_needs_powers_of_two_and_at_most_2_16_texels() {
        let t = std::vec![0u8; 1 << 17];
        let ok = |w, h, s| {
            Texture::new(&t, w, h, s)
                .unwrap()
                .masked::<RepeatPow2>()
                .is_some()
        };
        assert!(ok(256, 256, 256));
        assert!(ok(64, 512, 128));
        assert!(!ok(256, 512, 256), "2^17 texels");
        assert!(!ok(4, 4, 6), "stride not a power of two");
        assert!(!ok(3, 4, 4), "width not a power of two");
        assert!(!ok(4, 3, 4), "height not a power of two");
    }

    #[test]
    fn texture_validates_its_shape() {
        let t = [1u8, 2, 3, 4, 5, 6];
        assert_eq!(
            Texture::new(&t[..0], 0, 1, 0).unwrap_err(),
            TextureError::Empty
        );
        assert_eq!(Texture::new(&t, 3, 0, 3).unwrap_err(), TextureError::Empty);
        assert_eq!(
            Texture::new(&t, 3, 2, 2).unwrap_err(),
            TextureError::StrideTooSmall
        );
        assert_eq!(
            Texture::new(&t, 3, 3, 3).unwrap_err(),
            TextureError::TooShort { needed: 9, len: 6 }
        );
        // Rows of 2 texels, 4 apart: the last row needs only its 2 texels.
        assert!(Texture::new(&t, 2, 2, 4).is_ok());
        assert_eq!(
            Texture::new(&t, 2, 3, usize::MAX).unwrap_err(),
            TextureError::Overflow
        );
    }

    #[test]
    fn every_wrap_samples_in_bounds_and_as_documented() {
        let t = [1u8, 2, 3, 4, 5, 6];
        let tex = Texture::new(&t, 3, 2, 3).unwrap();
        assert_eq!(tex.sample::<Repeat>(-1, 0), 3);
        assert_eq!(tex.sample::<Repeat>(4, 3), 5);
        assert_eq!(tex.sample::<Clamp>(-7, 9), 4);
        assert_eq!(tex.sample::<Clamp>(99, -9), 3);
        // RepeatPow2 refuses a 3-wide texture but still samples in bounds.
        assert!(!tex.accepts::<RepeatPow2>());
        assert!(tex.accepts::<Repeat>() && tex.accepts::<Clamp>());
        for i in [i32::MIN, -9, -1, 0, 5, 9, i32::MAX] {
            assert!(t.contains(&tex.sample::<RepeatPow2>(i, i.wrapping_mul(7))));
        }
        // Strided: texel (x, y) is element y·stride + x, padding never read.
        let s = [10u8, 11, 99, 12, 13, 99, 14, 15];
        let tex = Texture::new(&s, 2, 3, 3).unwrap();
        assert!(tex.accepts::<Repeat>() && !tex.accepts::<RepeatPow2>());
        for y in -3i32..6 {
            for x in -3i32..5 {
                let want = 10 + 2 * y.rem_euclid(3) as u8 + x.rem_euclid(2) as u8;
                assert_eq!(tex.sample::<Repeat>(x, y), want, "({x}, {y})");
            }
        }
        let t4 = [0u8; 8];
        assert!(Texture::new(&t4, 4, 2, 4).unwrap().accepts::<RepeatPow2>());
        assert_eq!(RepeatPow2::wrap(-1, 4), 3);
        assert_eq!(RepeatPow2::wrap(9, 4), 1);
        assert_eq!(
            Repeat::wrap(i32::MIN, 3),
            (i32::MIN as i64).rem_euclid(3) as u16
        );
    }
}
