//! The one numeric abstraction every kernel in sightline is written against.
//!
//! [`Scalar`] is implemented for
//! - [`f64`]: the reference representation used by tests and reports;
//! - [`f32`]: hardware float on FPU cores, soft float elsewhere; transcendental
//!   functions go through [`libm`] (see the private `float_math` module, the one
//!   place where the no_std build calls into it);
//! - [`Fx<Frac>`](Fx): saturating fixed point over [`fixed::FixedI32<Frac>`]
//!   storage, with [`I16F16`] as the default format.
//!
//! # Overflow policy
//!
//! - The operators `+ - * /` on [`Fx`] **saturate**: a result beyond the
//!   representable range becomes `MAX` or `MIN`, never a wrapped value.
//!   Division by zero saturates to `MAX`/`MIN` by the sign of the dividend
//!   (`0 / 0` is `0`).
//! - The `checked_*` methods are the **reporting path**: they return `None`
//!   where the operators would have saturated (fixed point) or produced a
//!   non-finite value (float). The solver uses them and turns `None` into
//!   [`SolveError::Overflow`](crate::solve::SolveError::Overflow).
//! - Conversions from float ([`Scalar::from_f64`], [`Scalar::from_f32`])
//!   round to nearest and saturate; NaN converts to zero. Use
//!   [`Scalar::try_from_f64`] to reject out-of-range or NaN input instead.
//! - Floats follow IEEE 754: overflow gives ±∞, which kernels detect with
//!   [`Scalar::is_finite`].

/// Whether the build is for ARMv6-M (Cortex-M0/M0+/M1: 32-bit Arm without
/// atomic read-modify-write, a divide instruction or a 64-bit multiply),
/// where a few routines take a different route, each with its measured
/// reason beside it. Here because every layer uses `scalar`.
pub(crate) const ARMV6M: bool = cfg!(all(target_arch = "arm", not(target_has_atomic = "ptr")));

mod fixed_point;
pub(crate) use fixed_point::normalize_shift;
#[cfg(all(
    feature = "perspective",
    any(test, all(target_arch = "arm", not(target_has_atomic = "ptr")))
))]
pub(crate) use fixed_point::shr_u64;
pub(crate) use fixed_point::{widening_mul, widening_mul_u32};
mod div;
pub(crate) use div::{div_rem_i64, div_rem_u64};
mod float;
mod float_math;
pub(crate) mod predicates;
mod recip;
#[cfg(any(test, feature = "perspective"))]
pub(crate) use recip::{recip46_below, recip62_above};
pub(crate) use recip::{recip62, recip62_floor};

pub use fixed_point::{Fx, I2F30, I16F16, I20F12, I24F8};

use core::cmp::Ordering;
use core::fmt::Debug;
use core::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};

/// A real-number representation: `f32`, `f64` or saturating fixed point.
///
/// All numeric kernels in sightline (vectors, matrices, the solver, cameras)
/// are generic over this trait and written once.
pub trait Scalar:
    Copy
    + Default
    + PartialEq
    + PartialOrd
    + Debug
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign
    + DivAssign
{
    /// 0.
    const ZERO: Self;
    /// 1.
    const ONE: Self;
    /// 2.
    const TWO: Self;
    /// 0.5.
    const HALF: Self;
    /// π, rounded to the representation.
    const PI: Self;
    /// The resolution of the type near 1: machine epsilon (2⁻²³ for `f32`,
    /// 2⁻⁵² for `f64`) or one step of the fixed-point grid (2⁻ᶠʳᵃᶜ).
    /// Tolerances in tests and thresholds in the solver are multiples of it.
    const EPSILON: Self;
    /// The largest finite value.
    const MAX: Self;
    /// The most negative finite value.
    const MIN: Self;
    /// Whether the representation is IEEE floating point.
    const IS_FLOAT: bool;
    /// A short name for reports and test messages, e.g. `"f32"` or `"I16F16"`.
    const NAME: &'static str;

    /// Converts from `f64`, rounding to nearest. Saturates out-of-range
    /// values; NaN becomes zero.
    fn from_f64(x: f64) -> Self;
    /// Converts from `f32`, with the same rules as [`Scalar::from_f64`].
    #[must_use]
    fn from_f32(x: f32) -> Self {
        Self::from_f64(x as f64)
    }
    /// Converts an integer, saturating where it does not fit.
    fn from_i32(x: i32) -> Self;
    /// Converts from `f64`; `None` for NaN or a value out of range
    /// (for floats: one that would become infinite).
    fn try_from_f64(x: f64) -> Option<Self>;
    /// Converts to `f64` (exact for every implemented type).
    fn to_f64(self) -> f64;
    /// Converts to `f32` (rounded to nearest).
    fn to_f32(self) -> f32;

    /// `false` for NaN and ±∞. Always `true` for fixed point.
    fn is_finite(self) -> bool;
    /// Absolute value (saturating for fixed point: `|MIN|` is `MAX`).
    fn abs(self) -> Self;
    /// Square root. For negative input: NaN for floats, zero for fixed point.
    fn sqrt(self) -> Self;
    /// Sine of an angle in radians.
    fn sin(self) -> Self {
        self.sin_cos().0
    }
    /// Cosine of an angle in radians.
    fn cos(self) -> Self {
        self.sin_cos().1
    }
    /// Sine and cosine together (one range reduction).
    fn sin_cos(self) -> (Self, Self);
    /// Four-quadrant arctangent of `self / x`, in (−π, π]; `atan2(0, 0) = 0`.
    fn atan2(self, x: Self) -> Self;
    /// Arcsine; the argument is clamped to [−1, 1] first, so the result is
    /// always defined for finite input.
    #[must_use]
    fn asin(self) -> Self {
        let s = self.clamp_to(-Self::ONE, Self::ONE);
        let c = (Self::ONE - s * s).sqrt();
        s.atan2(c)
    }

    /// `Some(self + rhs)` unless the sum overflows or is not finite.
    fn checked_add(self, rhs: Self) -> Option<Self>;
    /// `Some(self - rhs)` unless the difference overflows or is not finite.
    fn checked_sub(self, rhs: Self) -> Option<Self>;
    /// `Some(self * rhs)` unless the product overflows or is not finite.
    fn checked_mul(self, rhs: Self) -> Option<Self>;
    /// `Some(self / rhs)` unless `rhs` is zero or the quotient overflows or
    /// is not finite.
    fn checked_div(self, rhs: Self) -> Option<Self>;

    /// `self − a·b` for elimination kernels, reporting overflow through a
    /// flag instead of branching per operation.
    ///
    /// Fixed point computes the exact value in `i64` with a single rounding,
    /// saturates, and sets `*overflow` when it did not fit. Floats compute
    /// `self - a * b` (no fused multiply-add, for bit-reproducibility
    /// across targets) and leave the flag alone: a non-finite result is
    /// detected by the caller's final [`Scalar::is_finite`] check.
    fn sub_mul_noting_overflow(self, a: Self, b: Self, overflow: &mut bool) -> Self;
    /// `self / d` with the same reporting as [`Scalar::sub_mul_noting_overflow`].
    fn div_noting_overflow(self, d: Self, overflow: &mut bool) -> Self;

    /// `n.checked_div(d)` for every `n` of `nums`: the same values, computed
    /// together. Fixed point divides by one shared reciprocal of `d` (a
    /// table seed and two Newton steps, then an exact correction of each
    /// quotient by one multiply), where each `/` would be a 64-bit library
    /// division on a core without a divide instruction; floats divide each.
    #[must_use]
    fn checked_quotients<const N: usize>(nums: [Self; N], d: Self) -> [Option<Self>; N] {
        nums.map(|n| n.checked_div(d))
    }

    /// A perspective projection's `(x·r, y·r, 1/z)` with `r = focus/z`,
    /// the values [`Projection::project`](crate::camera::Projection::project)
    /// forms for a view point near the axis (`|x|, |y| ≤ 128`: the shared
    /// `r` as [`Self::checked_quotients`] gives it, each coordinate's
    /// product as [`Self::checked_mul`]), by a faster route where the type
    /// has one for these operands; `None` sends the caller to the general
    /// route. 16.16 fixed point has one: one reciprocal of `z` and no
    /// division.
    #[must_use]
    #[inline]
    fn perspective_fast(x: Self, y: Self, z: Self, focus: Self) -> Option<(Self, Self, Self)> {
        let _ = (x, y, z, focus);
        None
    }

    /// `Σ a[i]·b[i]` as the vectors' `dot` computes it (each product
    /// rounded, summed left to right from zero) by a faster route, where
    /// the type has one for these operands; `None` sends the caller to
    /// the plain sum. Fixed point on ARMv6-M has one for small 16.16
    /// vectors of three.
    #[must_use]
    #[inline]
    fn dot_fast<const N: usize>(a: [Self; N], b: [Self; N]) -> Option<Self> {
        let _ = (a, b);
        None
    }

    /// `[m[0]·v, m[1]·v, m[2]·v]`, each row as [`Self::dot_fast`] gives it,
    /// by a faster route where the type has one for these operands
    /// (`None` sends the caller to three dot products). Fixed point on
    /// ARMv6-M tests the range of all twelve operands once.
    #[must_use]
    #[inline]
    fn mat3_vec3_fast(m: &[[Self; 3]; 3], v: [Self; 3]) -> Option<[Self; 3]> {
        let _ = (m, v);
        None
    }

    /// `m` prepared for many products by [`Self::mat3_vec3_prepared`], in
    /// the type's own 27 words, where it has a faster route for them;
    /// `None` otherwise. 16.16 fixed point on ARMv6-M has one for entries
    /// within ±64: the range test of the matrix and the 16-bit halves of
    /// its entries, once.
    #[must_use]
    #[inline]
    fn mat3_prepare(m: &[[Self; 3]; 3]) -> Option<[[[i32; 3]; 3]; 3]> {
        let _ = m;
        None
    }

    /// [`Self::mat3_vec3_fast`]`(m, v)` for the `m` that
    /// [`Self::mat3_prepare`] prepared into `prepared`: the same values,
    /// or `None` where that gives `None`.
    #[must_use]
    #[inline]
    fn mat3_vec3_prepared(prepared: &[[[i32; 3]; 3]; 3], v: [Self; 3]) -> Option<[Self; 3]> {
        let _ = (prepared, v);
        None
    }

    /// `v` prepared for many dot products by [`Self::dot3_prepared`], in
    /// the type's own nine words, where it has a faster route for them;
    /// `None` otherwise (as [`Self::mat3_prepare`], for one row).
    #[must_use]
    #[inline]
    fn dot3_prepare(v: [Self; 3]) -> Option<[[i32; 3]; 3]> {
        let _ = v;
        None
    }

    /// `w · v` as [`Self::dot_fast`]`(w, v)` gives it, for the `v` that
    /// [`Self::dot3_prepare`] prepared into `prepared`: the same value, or
    /// `None` where that gives `None`.
    #[must_use]
    #[inline]
    fn dot3_prepared(prepared: &[[i32; 3]; 3], w: [Self; 3]) -> Option<Self> {
        let _ = (prepared, w);
        None
    }

    /// The smaller of two values (`other` if they are unordered).
    ///
    /// Named `min_of` rather than `min` on purpose: the fixed-point types
    /// implement `Ord`, and `f32`/`f64` have inherent `min`/`max` with
    /// their own NaN rule, so a trait method called `min` would be
    /// shadowed by, or ambiguous with, those at call sites.
    #[must_use]
    fn min_of(self, other: Self) -> Self {
        if self < other { self } else { other }
    }
    /// The larger of two values (`other` if they are unordered).
    #[must_use]
    fn max_of(self, other: Self) -> Self {
        if self > other { self } else { other }
    }
    /// Clamps into `[lo, hi]`; NaN becomes `lo`.
    #[must_use]
    fn clamp_to(self, lo: Self, hi: Self) -> Self {
        if self > hi {
            hi
        } else if self >= lo {
            self
        } else {
            lo
        }
    }
    /// `1 / self` (saturating for fixed point).
    #[must_use]
    fn recip(self) -> Self {
        Self::ONE / self
    }
    /// Converts to a signed fixed-point integer with `frac_bits` (≤ 24)
    /// fractional bits, rounding to nearest (ties away from zero). `None` for
    /// NaN, ±∞ or a value outside `i32`. Used to snap projected vertices to
    /// the sub-pixel grid.
    fn to_subpixel(self, frac_bits: u32) -> Option<i32>;

    /// The exact sign of `(b − a) × (c − a) = (b.x − a.x)(c.y − a.y) −
    /// (b.y − a.y)(c.x − a.x)`, points given as `[x, y]`: `Greater` when
    /// `a, b, c` turn counter-clockwise (c left of a→b, y up), `Equal` when
    /// collinear. `None` only for a non-finite input.
    ///
    /// Exact for every finite input, computed from the inputs themselves
    /// (no rounded intermediate decides): fixed point in `i128` on the raw
    /// bits; floats by a filter in `Self` with a proven error bound and an
    /// exact big-integer fallback on the dyadic inputs (Shewchuk's adaptive
    /// scheme, the private `predicates` module), which only inputs within
    /// rounding distance of collinear reach.
    fn orient2d(a: [Self; 2], b: [Self; 2], c: [Self; 2]) -> Option<Ordering>;
}

#[cfg(test)]
mod tests;
