//! Texture-mapping span shaders: nearest-texel sampling from a
//! caller-supplied slice, affine or perspective-correct.
//!
//! Texel (i, j) covers `[i, i+1) × [j, j+1)` in texture coordinates, so a
//! sample at (u, v) reads texel `(⌊u⌋, ⌊v⌋)` after wrapping. The wrap mode
//! is a type parameter ([`Repeat`], [`RepeatPow2`], [`Clamp`]): no per-pixel
//! branch on it, and the power-of-two fast path is one AND per axis.
//!
//! - [`AffineTexture`] interpolates (u, v) linearly in screen space: exact
//!   for parallel projection and for polygons parallel to the screen,
//!   distorted (swimming) for steep polygons under perspective.
//! - [`PerspectiveTexture`] interpolates (u/z, v/z, 1/z), which *are*
//!   linear in screen space, and divides. With `N = 1` it divides at every
//!   pixel (exact); with `N = 8`, `16` or `32` it divides at the ends of
//!   runs of `N` pixels and steps linearly between them (the classic
//!   subdivided affine compromise: two divisions per run).

#[cfg(feature = "perspective")]
use super::PERSPECTIVE_Q_BITS;
use super::shader::{Shade, SpanShader, VARYING_FRAC_BITS};
#[cfg(feature = "perspective")]
use crate::target::Target;
use crate::target::{BufferError, layout::Layout};
use core::fmt::Debug;

/// A read-only texture over a caller-supplied slice, row-major with a
/// stride.
///
/// # Guarantees
///
/// Validated once by [`Texture::new`]; sampling never panics and never
/// reads outside the slice, for any texture coordinates.
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
    /// Wraps `texels` as `width`×`height` texels, `stride` apart.
    ///
    /// # Errors
    /// As [`Framebuffer::new`](crate::target::Framebuffer::new), and
    /// [`BufferError::BadTextureSize`] for a zero width or height.
    pub fn new(
        texels: &'a [C],
        width: u16,
        height: u16,
        stride: usize,
    ) -> Result<Self, BufferError> {
        if width == 0 || height == 0 {
            return Err(BufferError::BadTextureSize);
        }
        Layout::new(texels.len(), width, height, stride, 0)?;
        // Non-empty: width, height ≥ 1 and the length was validated.
        let &fallback = texels.first().ok_or(BufferError::BadTextureSize)?;
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
    pub fn width(&self) -> u16 {
        self.width
    }

    /// Height in texels.
    #[must_use]
    pub fn height(&self) -> u16 {
        self.height
    }

    /// The texel at integer coordinates, wrapped with `W`.
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

/// How integer texel coordinates outside the texture map inside.
pub trait Wrap: Copy + Debug + Default {
    /// Whether a texture side of `n` texels is supported.
    fn accepts(n: u16) -> bool;
    /// Maps `i` into `0..n` (`n ≥ 1`, and accepted).
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

/// Affine texture mapping: varyings (u, v) in texels, 16.16.
///
/// Per pixel: two adds, two shifts, the wrap, one multiply-add for the
/// index and one load.
#[derive(Clone, Copy, Debug)]
pub struct AffineTexture<'a, C, W> {
    tex: Texture<'a, C>,
    wrap: W,
}

impl<'a, C: Copy, W: Wrap> AffineTexture<'a, C, W> {
    /// An affine texture shader; `None` if `W` does not accept the
    /// texture's size ([`RepeatPow2`] needs powers of two).
    #[must_use]
    pub fn new(tex: Texture<'a, C>) -> Option<Self> {
        (W::accepts(tex.width) && W::accepts(tex.height)).then(|| Self {
            tex,
            wrap: W::default(),
        })
    }
}

impl<C: Copy, W: Wrap> SpanShader<2> for AffineTexture<'_, C, W> {
    type Color = C;

    #[inline]
    fn color(&self, v: &[i32; 2]) -> C {
        let _ = self.wrap;
        self.tex
            .sample::<W>(v[0] >> VARYING_FRAC_BITS, v[1] >> VARYING_FRAC_BITS)
    }
}

/// Affine texture mapping modulated by Gouraud intensity: varyings
/// (intensity 0..=255, u, v), all 16.16, as
/// [`IntensityUv`](crate::pipeline::IntensityUv) vertices produce. Each
/// pixel is its texel scaled by the interpolated intensity
/// ([`Shade::scale`]), so full intensity (255) gives exactly
/// [`AffineTexture`]'s colour.
///
/// Per pixel: the affine texture's work plus one scale per channel.
#[derive(Clone, Copy, Debug)]
pub struct LitAffineTexture<'a, C, W> {
    tex: Texture<'a, C>,
    wrap: W,
}

impl<'a, C: Shade, W: Wrap> LitAffineTexture<'a, C, W> {
    /// A lit affine texture shader; `None` if `W` does not accept the
    /// texture's size.
    #[must_use]
    pub fn new(tex: Texture<'a, C>) -> Option<Self> {
        (W::accepts(tex.width) && W::accepts(tex.height)).then(|| Self {
            tex,
            wrap: W::default(),
        })
    }
}

impl<C: Shade, W: Wrap> SpanShader<3> for LitAffineTexture<'_, C, W> {
    type Color = C;

    #[inline]
    fn color(&self, v: &[i32; 3]) -> C {
        let _ = self.wrap;
        // The intensity varying shares the default range with u and v, so
        // clamp it into 0..=255 here.
        let i = (v[0] >> VARYING_FRAC_BITS).clamp(0, 255) as u8;
        self.tex
            .sample::<W>(v[1] >> VARYING_FRAC_BITS, v[2] >> VARYING_FRAC_BITS)
            .scale(i)
    }
}

/// Perspective-correct texture mapping from the varyings
/// (u·q, v·q, q) with `q = near/z`: (u, v) = (u·q / q, v·q / q).
///
/// `N` is the run length between exact divisions: 1 for exact per-pixel
/// division, 8, 16 or 32 for subdivided affine runs (any `N ≥ 1` works).
/// Feed it [`UvPerspective`](crate::pipeline::UvPerspective) vertices.
#[cfg(feature = "perspective")]
#[derive(Clone, Copy, Debug)]
pub struct PerspectiveTexture<'a, C, W, const N: u32> {
    tex: Texture<'a, C>,
    wrap: W,
}

#[cfg(feature = "perspective")]
impl<'a, C: Copy, W: Wrap, const N: u32> PerspectiveTexture<'a, C, W, N> {
    /// A perspective texture shader; `None` if `W` does not accept the
    /// texture's size.
    #[must_use]
    pub fn new(tex: Texture<'a, C>) -> Option<Self> {
        (W::accepts(tex.width) && W::accepts(tex.height)).then(|| Self {
            tex,
            wrap: W::default(),
        })
    }
}

#[cfg(feature = "perspective")]
impl<C: Copy, W: Wrap, const N: u32> PerspectiveTexture<'_, C, W, N> {
    /// Pixels of one run from (u, v) = `a` stepping by `d` (16.16).
    #[inline]
    fn fill_run(&self, run: &mut [C], a: (i64, i64), d: (i64, i64)) {
        let last = run.len().saturating_sub(1) as i64;
        let fits = |v: i64, dv: i64| {
            let end = dv.saturating_mul(last).saturating_add(v);
            i32::try_from(v).is_ok() && i32::try_from(end).is_ok()
        };
        if fits(a.0, d.0) && fits(a.1, d.1) {
            // Every value lies between the two ends, so i32 holds them all
            // and `>> 16` equals `texel_coord`.
            let (mut u, mut v) = (a.0 as i32, a.1 as i32);
            let (du, dv) = (d.0 as i32, d.1 as i32);
            for p in run {
                *p = self
                    .tex
                    .sample::<W>(u >> VARYING_FRAC_BITS, v >> VARYING_FRAC_BITS);
                u = u.wrapping_add(du);
                v = v.wrapping_add(dv);
            }
        } else {
            let mut cur = a;
            for p in run {
                *p = self.tex.sample::<W>(texel_coord(cur.0), texel_coord(cur.1));
                cur.0 += d.0;
                cur.1 += d.1;
            }
        }
    }
}

/// (u, v) in 16.16 from (u·q, v·q) in 16.16 and q in 8.24.
#[cfg(feature = "perspective")]
#[inline]
fn divide(v: &[i32; 3]) -> (i64, i64) {
    // q ≥ 1 guards the division; |u·q| < 2^31, so the shift stays below
    // 2^55.
    let q = (v[2] as i64).max(1);
    (
        ((v[0] as i64) << PERSPECTIVE_Q_BITS) / q,
        ((v[1] as i64) << PERSPECTIVE_Q_BITS) / q,
    )
}

#[cfg(feature = "perspective")]
#[inline]
fn texel_coord(u: i64) -> i32 {
    (u >> VARYING_FRAC_BITS).clamp(i32::MIN as i64, i32::MAX as i64) as i32
}

#[cfg(feature = "perspective")]
impl<C: Copy, W: Wrap, const N: u32> SpanShader<3> for PerspectiveTexture<'_, C, W, N> {
    type Color = C;
    // Runs of N > 1 step between exact divisions, which `color` alone
    // cannot reproduce.
    const PER_PIXEL: bool = N <= 1;

    #[inline]
    fn color(&self, v: &[i32; 3]) -> C {
        let _ = self.wrap;
        let (u, t) = divide(v);
        self.tex.sample::<W>(texel_coord(u), texel_coord(t))
    }

    fn shade_run<T: Target<Color = C>>(
        &self,
        target: &mut T,
        y: i32,
        x: i32,
        len: u32,
        start: [i32; 3],
        step: [i32; 3],
    ) {
        if N <= 1 {
            let mut v = start;
            target.fill_with(y, x, len, || {
                let c = self.color(&v);
                for (vk, sk) in v.iter_mut().zip(step) {
                    *vk = vk.wrapping_add(sk);
                }
                c
            });
            return;
        }
        // Exact (u, v) at the first pixel of each run of N and at the
        // run's last pixel; linear steps between. Both ends lie on the
        // span, so q there is within the polygon's range.
        let at = |i: u32| -> (i64, i64) {
            let i = i as i32;
            divide(&[
                start[0].wrapping_add(step[0].wrapping_mul(i)),
                start[1].wrapping_add(step[1].wrapping_mul(i)),
                start[2].wrapping_add(step[2].wrapping_mul(i)),
            ])
        };
        if let Some(pixels) = target.span_mut(y, x, len) {
            // Slice target: the same values as the general path below, one
            // run of N at a time in a tight loop.
            let mut i = 0u32;
            for run in pixels.chunks_mut(N as usize) {
                let seg = run.len() as u32;
                let a = at(i);
                let (du, dv) = if seg > 1 {
                    let b = at(i + seg - 1);
                    let n = seg as i64 - 1;
                    ((b.0 - a.0) / n, (b.1 - a.1) / n)
                } else {
                    (0, 0)
                };
                self.fill_run(run, a, (du, dv));
                i += seg;
            }
            return;
        }
        let mut i = 0u32;
        let mut cur = at(0);
        let (mut du, mut dv) = (0i64, 0i64);
        let mut left = 0u32;
        target.fill_with(y, x, len, || {
            if left == 0 {
                // `max(1)`: robust even if a target called this more than `len`
                // times, which the `Target` contract rules out.
                let seg = N.min(len.saturating_sub(i)).max(1);
                if seg > 1 {
                    let end = at(i + seg - 1);
                    du = (end.0 - cur.0) / (seg as i64 - 1);
                    dv = (end.1 - cur.1) / (seg as i64 - 1);
                }
                left = seg;
            }
            let c = self.tex.sample::<W>(texel_coord(cur.0), texel_coord(cur.1));
            left -= 1;
            i += 1;
            if left == 0 {
                if i < len {
                    cur = at(i);
                }
            } else {
                cur.0 += du;
                cur.1 += dv;
            }
            c
        });
    }
}
