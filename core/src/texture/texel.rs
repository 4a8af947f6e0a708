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

/// How integer texel coordinates outside the texture map inside.
pub trait Wrap: Copy + Debug + Default {
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
