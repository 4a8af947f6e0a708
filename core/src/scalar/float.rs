//! [`Scalar`] for `f32` and `f64`: IEEE 754 arithmetic, `libm` for the rest.

use super::Scalar;
use super::float_math as m;
use super::predicates as p;

macro_rules! impl_float {
    ($t:ty, $name:literal, $sqrt:path, $sincos:path, $atan2:path, $asin:path, $orient:path) => {
        impl Scalar for $t {
            const ZERO: Self = 0.0;
            const ONE: Self = 1.0;
            const TWO: Self = 2.0;
            const HALF: Self = 0.5;
            const PI: Self = core::f64::consts::PI as $t;
            const EPSILON: Self = <$t>::EPSILON;
            const MAX: Self = <$t>::MAX;
            const MIN: Self = <$t>::MIN;
            const IS_FLOAT: bool = true;
            const NAME: &'static str = $name;

            #[inline]
            fn from_f64(x: f64) -> Self {
                if x.is_nan() {
                    0.0
                } else {
                    // `as` rounds to nearest and gives ±∞ beyond the range;
                    // saturate those to the finite extremes.
                    (x as $t).clamp(<$t>::MIN, <$t>::MAX)
                }
            }
            #[inline]
            fn from_f32(x: f32) -> Self {
                Self::from_f64(x as f64)
            }
            #[inline]
            fn from_i32(x: i32) -> Self {
                x as $t
            }
            #[inline]
            fn try_from_f64(x: f64) -> Option<Self> {
                let v = x as $t;
                if v.is_finite() { Some(v) } else { None }
            }
            #[inline]
            fn to_f64(self) -> f64 {
                self as f64
            }
            #[inline]
            fn to_f32(self) -> f32 {
                self as f32
            }
            #[inline]
            fn is_finite(self) -> bool {
                <$t>::is_finite(self)
            }
            #[inline]
            fn abs(self) -> Self {
                <$t>::abs(self)
            }
            #[inline]
            fn sqrt(self) -> Self {
                $sqrt(self)
            }
            #[inline]
            fn sin_cos(self) -> (Self, Self) {
                $sincos(self)
            }
            #[inline]
            fn atan2(self, x: Self) -> Self {
                $atan2(self, x)
            }
            #[inline]
            fn asin(self) -> Self {
                $asin(self.clamp_to(-1.0, 1.0))
            }
            #[inline]
            fn checked_add(self, rhs: Self) -> Option<Self> {
                finite(self + rhs)
            }
            #[inline]
            fn checked_sub(self, rhs: Self) -> Option<Self> {
                finite(self - rhs)
            }
            #[inline]
            fn checked_mul(self, rhs: Self) -> Option<Self> {
                finite(self * rhs)
            }
            #[inline]
            fn checked_div(self, rhs: Self) -> Option<Self> {
                if rhs == 0.0 { None } else { finite(self / rhs) }
            }
            #[inline]
            fn sub_mul_noting_overflow(self, a: Self, b: Self, _overflow: &mut bool) -> Self {
                self - a * b
            }
            #[inline]
            fn div_noting_overflow(self, d: Self, _overflow: &mut bool) -> Self {
                self / d
            }
            #[inline]
            fn to_subpixel(self, frac_bits: u32) -> Option<i32> {
                // Round half away from zero, as `libm::round`, without the
                // call (this runs per projected vertex): truncate, then
                // look at the exact remainder. Accepted exactly when the
                // rounded value lies in [−2^31, 2^31).
                let s = self * (1u32 << frac_bits.min(24)) as $t;
                // s > −2^31 − 1 (f64), or s ≥ −2^31 (f32, where the
                // constant rounds to −2^31 and nothing lies between), and
                // s < 2^31; false for NaN and ±∞. No f64 arithmetic for
                // f32, which matters on soft-float cores.
                let lo = -2_147_483_649.0 as $t;
                let min = -2_147_483_648.0 as $t;
                if !((s > lo || s == min) && s < 2_147_483_648.0) {
                    return None;
                }
                // |s| < 2^31 + 1: the cast truncates toward zero without
                // saturating, and `s − t` is exact (t is s itself when s
                // is too large to have a fraction).
                let t = s as i32;
                let f = s - t as $t;
                if f >= 0.5 {
                    t.checked_add(1)
                } else if f <= -0.5 {
                    t.checked_sub(1)
                } else {
                    Some(t)
                }
            }
            #[inline]
            fn orient2d(a: [Self; 2], b: [Self; 2], c: [Self; 2]) -> Option<core::cmp::Ordering> {
                $orient(a, b, c)
            }
        }
    };
}

#[inline]
fn finite<T: Scalar>(v: T) -> Option<T> {
    if v.is_finite() { Some(v) } else { None }
}

impl_float!(
    f32,
    "f32",
    m::sqrtf,
    m::sincosf,
    m::atan2f,
    m::asinf,
    p::orient2d_f32
);
impl_float!(
    f64,
    "f64",
    m::sqrt,
    m::sincos,
    m::atan2,
    m::asin,
    p::orient2d_f64
);
