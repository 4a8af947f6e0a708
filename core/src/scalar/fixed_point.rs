//! Saturating fixed point: [`Fx<Frac>`], a 32-bit signed number with `Frac`
//! fractional bits, stored as [`fixed::FixedI32<Frac>`].
//!
//! All arithmetic is done here on the raw bits with `i64` intermediates, so
//! the rounding and overflow behavior is ours, documented, and identical on
//! every target (a Cortex-M0 computes the same bits as an x86 host):
//! - `+ -` saturate;
//! - `*` rounds to nearest (ties toward +∞) and saturates;
//! - `/` rounds to nearest (ties away from zero) and saturates; division by
//!   zero gives `MAX`, `MIN` or `0` by the sign of the dividend;
//! - `sqrt` is an exact integer square root, rounded to nearest;
//! - `sin`/`cos`/`atan2` are integer polynomials evaluated in Q2.30 (see
//!   below); no float and no table is involved.
//!
//! `Frac` must be in `1..=30`; other values fail to compile when a method is
//! used.
//!
//! # Trigonometry
//!
//! `sin_cos` reduces the angle to turns in Q0.32 (the wrap modulo one turn is
//! then exact integer wrap-around), splits off the octant, and evaluates the
//! Taylor polynomials of sin (to x⁹) and cos (to x¹⁰) on [0, π/4] in Q2.30,
//! where their truncation error is below 2·10⁻⁹. `atan2` reduces to
//! |w| ≤ tan(π/8) with atan(z) = π/4 + atan((z−1)/(z+1)) and evaluates the
//! Taylor series to w¹⁵ (truncation below 2·10⁻⁸). Both are therefore exact
//! to within one step of any format up to `Fx<U24>`; the measured errors for
//! I16F16 are in the crate's tests and in the accuracy report.

use super::{Scalar, recip62, recip62_floor};
use core::cmp::Ordering;
use core::fmt;
use core::marker::PhantomData;
use core::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};
use fixed::FixedI32;
use fixed::types::extra::{LeEqU32, U8, U12, U16, U30};

/// Saturating 32-bit fixed point with `Frac` fractional bits (1 ≤ `Frac` ≤ 30).
///
/// The value is `bits / 2^Frac`. Nothing ever wraps, and the rules are the
/// same bits on every target: `+ -` saturate; `*` rounds to nearest (ties
/// toward +∞) and saturates; `/` rounds to nearest (ties away from zero)
/// and saturates, division by zero giving `MAX`, `MIN` or `0` by the sign
/// of the dividend; `sqrt` is an exact integer square root rounded to
/// nearest; `sin`/`cos`/`atan2` are integer polynomials in Q2.30. The
/// overflow policy as a whole: [`crate::scalar`].
#[repr(transparent)]
pub struct Fx<Frac> {
    bits: i32,
    _frac: PhantomData<fn() -> Frac>,
}

/// Q16.16: range ±32768, step 2⁻¹⁶ ≈ 1.5·10⁻⁵. The default fixed format.
pub type I16F16 = Fx<U16>;
/// Q20.12: range ±524288, step 2⁻¹² ≈ 2.4·10⁻⁴.
pub type I20F12 = Fx<U12>;
/// Q24.8: range ±8388608, step 2⁻⁸.
pub type I24F8 = Fx<U8>;
/// Q2.30: range ±2, step 2⁻³⁰ ≈ 9.3·10⁻¹⁰. Suited to rotation coefficients.
pub type I2F30 = Fx<U30>;

impl<Frac> Clone for Fx<Frac> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<Frac> Copy for Fx<Frac> {}
impl<Frac> Default for Fx<Frac> {
    fn default() -> Self {
        Self::from_bits(0)
    }
}
impl<Frac> PartialEq for Fx<Frac> {
    fn eq(&self, other: &Self) -> bool {
        self.bits == other.bits
    }
}
impl<Frac> Eq for Fx<Frac> {}
impl<Frac> PartialOrd for Fx<Frac> {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl<Frac> Ord for Fx<Frac> {
    fn cmp(&self, other: &Self) -> Ordering {
        self.bits.cmp(&other.bits)
    }
}
impl<Frac> core::hash::Hash for Fx<Frac> {
    fn hash<H: core::hash::Hasher>(&self, state: &mut H) {
        self.bits.hash(state);
    }
}

impl<Frac> Fx<Frac> {
    /// The value with the given raw bits (`bits / 2^Frac`).
    #[must_use]
    pub const fn from_bits(bits: i32) -> Self {
        Self {
            bits,
            _frac: PhantomData,
        }
    }
    /// The raw bits.
    #[must_use]
    pub const fn to_bits(self) -> i32 {
        self.bits
    }
}

impl<Frac: LeEqU32> Fx<Frac> {
    const FRAC: u32 = {
        assert!(
            Frac::U32 >= 1 && Frac::U32 <= 30,
            "Fx<Frac> needs 1 <= Frac <= 30"
        );
        Frac::U32
    };

    /// Wraps a value of the `fixed` crate (same bits).
    #[must_use]
    pub fn from_fixed(v: FixedI32<Frac>) -> Self {
        Self::from_bits(v.to_bits())
    }
    /// The same bits as a value of the `fixed` crate.
    #[must_use]
    pub fn to_fixed(self) -> FixedI32<Frac> {
        FixedI32::from_bits(self.bits)
    }

    #[inline]
    fn sat(v: i64) -> Self {
        Self::from_bits(sat_i32(v))
    }
    #[inline]
    fn fits(v: i64) -> Option<Self> {
        if v >= i32::MIN as i64 && v <= i32::MAX as i64 {
            Some(Self::from_bits(v as i32))
        } else {
            None
        }
    }
    /// Rounded product of the raw bits, before the range check.
    #[inline]
    fn mul_wide(a: i32, b: i32) -> i64 {
        let f = Self::FRAC;
        (widening_mul(a, b) + (1i64 << (f - 1))) >> f
    }
    /// Rounded quotient of the raw bits, before the range check; `b != 0`.
    #[inline]
    fn div_wide(a: i32, b: i32) -> i64 {
        let n = (a as i64) << Self::FRAC;
        let d = b as i64;
        let (q, r) = super::div_rem_i64(n, d);
        // Round half away from zero.
        if 2 * r.unsigned_abs() >= d.unsigned_abs() {
            if (n < 0) == (d < 0) { q + 1 } else { q - 1 }
        } else {
            q
        }
    }
    #[inline]
    fn from_q30(v: i64) -> Self {
        let f = Self::FRAC;
        if f == 30 {
            Self::sat(v)
        } else {
            Self::sat((v + (1i64 << (29 - f))) >> (30 - f))
        }
    }
}

/// `round(x·2^frac)` (half away from zero), saturated to `i32`, NaN → 0,
/// from the bits of `x` in integer arithmetic; `frac ≤ 32`.
///
/// `x = ±m·2^(e − 150)` with the 24-bit significand m (the implicit bit
/// set for normal numbers) and the biased exponent e, so
/// `x·2^frac = ±m·2^k`, `k = e − 150 + frac`: an integer shift of m
/// (saturating) for `k ≥ 0`, else `(m + 2^(−k−1)) >> −k` on the magnitude.
pub(crate) fn f32_to_fixed_bits(x: f32, frac: u32) -> i32 {
    let bits = x.to_bits();
    let negative = bits >> 31 != 0;
    let e = ((bits >> 23) & 0xff) as i32;
    let frac_bits = bits & 0x7f_ffff;
    if e == 0xff {
        return match (frac_bits, negative) {
            (0, false) => i32::MAX,
            (0, true) => i32::MIN,
            _ => 0, // NaN
        };
    }
    let (m, e) = if e == 0 {
        (frac_bits, 1) // subnormal: no implicit bit, exponent of 2^-126
    } else {
        (frac_bits | 0x80_0000, e)
    };
    let k = e - 150 + frac as i32;
    // The magnitude, at most 2^31 (which saturates for a positive value).
    let mag: u64 = if k >= 0 {
        if k >= 40 {
            u64::MAX // m ≥ 1 here unless x = ±0, handled below
        } else {
            (m as u64) << k
        }
    } else {
        let s = (-k) as u32;
        if s > 40 {
            0 // below 2^-16 · 2^frac… far below one half
        } else {
            ((m as u64) + (1 << (s - 1))) >> s
        }
    };
    if m == 0 {
        return 0;
    }
    if negative {
        if mag >= 1 << 31 {
            i32::MIN
        } else {
            -(mag as i32)
        }
    } else if mag > i32::MAX as u64 {
        i32::MAX
    } else {
        mag as i32
    }
}

/// The exact product `a·b` as `i64`.
///
/// ARMv6-M (Cortex-M0/M0+, RP2040) has no 32×32→64 multiply, and LLVM
/// lowers `a as i64 * b as i64` there to a call of `__aeabi_lmul`, a full
/// 64×64 multiply: that call was 21 % of a W1 frame. There (recognized as
/// 32-bit ARM without atomic compare-and-swap, which ARMv6-M lacks) the
/// product is assembled from four 16×16 multiplies instead; elsewhere the
/// hardware's widening multiply is used. Both give the same bits (the
/// test `split_widening_mul_is_exact`).
#[inline(always)]
pub(crate) fn widening_mul(a: i32, b: i32) -> i64 {
    #[cfg(all(target_arch = "arm", not(target_has_atomic = "ptr")))]
    {
        split_widening_mul(a, b)
    }
    #[cfg(not(all(target_arch = "arm", not(target_has_atomic = "ptr"))))]
    {
        a as i64 * b as i64
    }
}

/// The exact product `a·b` of unsigned 32-bit values, as
/// [`widening_mul`] does it for signed ones (four 16×16 multiplies on
/// ARMv6-M, the hardware's widening multiply elsewhere).
#[inline(always)]
pub(crate) fn widening_mul_u32(a: u32, b: u32) -> u64 {
    #[cfg(all(target_arch = "arm", not(target_has_atomic = "ptr")))]
    {
        split_widening_mul_u32(a, b)
    }
    #[cfg(not(all(target_arch = "arm", not(target_has_atomic = "ptr"))))]
    {
        a as u64 * b as u64
    }
}

/// `p >> sh` (`sh < 64`) by shifts of 32-bit halves: a variable 64-bit
/// shift is a library call (`__aeabi_llsr`) on ARMv6-M.
#[inline(always)]
#[cfg(any(
    test,
    all(
        feature = "perspective",
        target_arch = "arm",
        not(target_has_atomic = "ptr")
    )
))]
pub(crate) fn shr_u64(p: u64, sh: u32) -> u64 {
    let (lo, hi) = (p as u32, (p >> 32) as u32);
    if sh >= 32 {
        (hi >> (sh - 32)) as u64
    } else if sh == 0 {
        p
    } else {
        (((hi >> sh) as u64) << 32) | ((lo >> sh) | (hi << (32 - sh))) as u64
    }
}

/// `p >> sh` (`sh < 64`) if it is below 2^32, else `None`, by shifts of
/// 32-bit halves: a variable 64-bit shift is a library call
/// (`__aeabi_llsr`) on ARMv6-M.
#[inline(always)]
pub(crate) fn shr_to_u32(p: u64, sh: u32) -> Option<u32> {
    let (lo, hi) = (p as u32, (p >> 32) as u32);
    if sh >= 32 {
        Some(hi >> (sh - 32))
    } else if hi >> sh != 0 {
        None
    } else if sh == 0 {
        Some(lo)
    } else {
        Some((lo >> sh) | (hi << (32 - sh)))
    }
}

/// The perspective projection of a 16.16 view point, `(x·r, y·r, 1/z)`
/// with `r = f/z`, each value rounded as [`Scalar::checked_quotients`]
/// (half away from zero) and [`Scalar::checked_mul`] (half up) round it:
/// the values `Projection::project`'s general route gives, from one
/// reciprocal of `z`, no division and no 64-bit arithmetic but three
/// widening multiplies.
///
/// Answers for `z ≥ 2⁻⁸`, `|x|, |y| ≤ 128` (the general route's bound
/// for sharing `f/z`) and `0 < f < 2^(28−s)` (`s` below: any focus below
/// 16384 pixels from `z = 1`, below 1024 from `z = 2⁻⁴`) when every
/// result fits; `None` sends the caller to the general route.
///
/// Why it is exact. With `z' = z·2^s` in `[2^30, 2^31)` and
/// `R = 2^62/z'`, the quotient `q = ⌊a·2^16/z⌋ = ⌊a·R / 2^(46−s)⌋` for
/// `a = 1` (as 2^16) and `a = f`. [`recip62_floor`] gives `r ≤ R` with
/// `⌊R⌋ − r ≤ 3` (for every divisor: `recip62_exhaustive`), so `R − r < 4`
/// and `e = ⌊a·r / 2^(46−s)⌋` is at most `q` and short by less than
/// `4a/2^(46−s) + 1 ≤ 2` while `a ≤ 2^(44−s)`: `e` is `q` or `q − 1`. The
/// remainder `a·2^16 − e·z` is then in `[0, 2z)`, below 2^32, so it is
/// exact in wrapping 32-bit arithmetic; one conditional subtraction of
/// `z` leaves `q` and `a·2^16 − q·z`, which rounds it.
#[inline]
pub(crate) fn perspective16(x: i32, y: i32, z: i32, f: i32) -> Option<(i32, i32, i32)> {
    const AXIS: u32 = 128 << 16;
    if z < 1 << 8 || f <= 0 || x.unsigned_abs() > AXIS || y.unsigned_abs() > AXIS {
        return None;
    }
    let d = z as u32;
    let s = normalize_shift(d); // in [0, 22]
    let sh = 46 - s; // in [24, 46]
    if (f as u32).checked_shr(sh - 2).unwrap_or(0) != 0 {
        return None;
    }
    // r ≤ 2^62/2^30 = 2^32: clamped, still R − r < 4.
    let r = recip62_floor(d << s).min(u32::MAX as u64) as u32;
    let quotient = |a: u32, e: u32| -> Option<i32> {
        // q ≤ 2^30 (a ≤ 2^(44−s), z ≥ 2^(30−s)): e + 1 cannot overflow.
        let (mut e, mut rem) = (e, (a << 16).wrapping_sub(e.wrapping_mul(d)));
        if rem >= d {
            rem -= d;
            e += 1;
        }
        // rem < z < 2^31: round half away from zero (the values are positive).
        // In u32, checked all the same: the u64 sum it replaced cost
        // ARMv6-M about 21 instructions a vertex (W1/W2 per frame 5.43 M /
        // 6.40 M -> 5.39 M / 6.36 M).
        let q = e.checked_add(u32::from(rem >= d - rem))?;
        i32::try_from(q).ok()
    };
    // a = 2^16: a·r / 2^sh is a shift of r.
    let inv_z = quotient(1 << 16, r >> (sh - 16))?;
    let ratio = quotient(f as u32, shr_to_u32(widening_mul_u32(f as u32, r), sh)?)?;
    // |x| ≤ 2^23, ratio < 2^31: the product is below 2^54.
    let mul = |v: i32| i32::try_from((widening_mul(v, ratio) + (1 << 15)) >> 16).ok();
    Some((mul(x)?, mul(y)?, inv_z))
}

/// The shift `s` that puts `d` (in `[1, 2^31)`) into `[2^30, 2^31)`:
/// `d.leading_zeros() − 1`. ARMv6-M has no count-leading-zeros
/// instruction (`__clzsi2` is a call of about 30 instructions), so there
/// `d`'s bits below its top one are all set (five shifts and ORs), which
/// leaves one of 32 values, and a multiply by a de Bruijn constant maps
/// each of them to its own 5-bit table index ([`LOG2_SMEARED`]): about
/// 18 instructions where a binary search took 33 (instructions per
/// frame on ARMv6-M: W1 5.51 M -> 5.46 M, W2 6.50 M -> 6.45 M, the exactly
/// divided corridor 30.08 M -> 29.51 M; the flat firmware 104 bytes
/// smaller). Elsewhere `leading_zeros` is one instruction.
#[inline(always)]
pub(crate) fn normalize_shift(d: u32) -> u32 {
    if crate::scalar::ARMV6M {
        normalize_shift_smeared(d)
    } else {
        d.leading_zeros().wrapping_sub(1)
    }
}

/// [`normalize_shift`] by the de Bruijn table (ARMv6-M's route; tested on
/// every target).
#[inline(always)]
pub(crate) fn normalize_shift_smeared(d: u32) -> u32 {
    let mut v = d;
    v |= v >> 1;
    v |= v >> 2;
    v |= v >> 4;
    v |= v >> 8;
    v |= v >> 16;
    // `d ≥ 1`, so the top bit is at 30 or below.
    30u32.wrapping_sub(LOG2_SMEARED[(v.wrapping_mul(DE_BRUIJN) >> 27) as usize] as u32)
}

/// A 32-bit de Bruijn sequence B(2, 5) (every 5-bit pattern occurs once
/// among its cyclic windows): multiplying `2^(k+1) − 1` by it and keeping
/// the top 5 bits gives a different index for each `k` in `0..32`. The
/// constant is the one in Sean Eron Anderson's *Bit Twiddling Hacks*
/// ("Find the log base 2 of an N-bit integer in O(lg(N)) operations with
/// multiply and lookup"); the table below is computed from it.
const DE_BRUIJN: u32 = 0x07C4_ACDD;

/// `LOG2_SMEARED[(v·DE_BRUIJN) >> 27] = k` for `v = 2^(k+1) − 1`, built at
/// compile time; the build fails if two `k` shared an index.
const LOG2_SMEARED: [u8; 32] = {
    let mut t = [0u8; 32];
    let mut seen = 0u32;
    let mut k = 0;
    while k < 32 {
        let v = if k == 31 {
            u32::MAX
        } else {
            (1u32 << (k + 1)) - 1
        };
        let i = (v.wrapping_mul(DE_BRUIJN) >> 27) as usize;
        assert!(
            seen & (1 << i) == 0,
            "DE_BRUIJN maps two values to one index"
        );
        seen |= 1 << i;
        t[i] = k as u8;
        k += 1;
    }
    t
};

/// `a·b = aₕbₕ·2³² + (aₕbₗ + aₗbₕ)·2¹⁶ + aₗbₗ` with 16-bit halves; every
/// partial product is below 2³², and the sum below 2⁶⁴.
#[inline(always)]
#[cfg(any(test, all(target_arch = "arm", not(target_has_atomic = "ptr"))))]
pub(crate) fn split_widening_mul_u32(a: u32, b: u32) -> u64 {
    let (al, ah) = (a & 0xffff, a >> 16);
    let (bl, bh) = (b & 0xffff, b >> 16);
    let mid = (ah * bl) as u64 + (al * bh) as u64;
    (((ah * bh) as u64) << 32) + (mid << 16) + (al * bl) as u64
}

/// `a·b` from 16-bit halves: with `a = aₕ·2¹⁶ + aₗ` (`aₗ` unsigned, `aₕ`
/// signed), `a·b = aₕbₕ·2³² + (aₕbₗ + aₗbₕ)·2¹⁶ + aₗbₗ`. Each cross product
/// lies in (−2³¹, 2³¹) (|aₕ| ≤ 2¹⁵, bₗ < 2¹⁶), `aₗbₗ < 2³²` is unsigned and
/// `|aₕbₕ| ≤ 2³⁰`, so every partial product is a 32-bit multiply.
#[inline(always)]
#[cfg(any(test, all(target_arch = "arm", not(target_has_atomic = "ptr"))))]
pub(crate) fn split_widening_mul(a: i32, b: i32) -> i64 {
    let (al, ah) = ((a & 0xffff) as u32, a >> 16);
    let (bl, bh) = ((b & 0xffff) as u32, b >> 16);
    let low = (al * bl) as i64;
    let mid = (ah * bl as i32) as i64 + (al as i32 * bh) as i64;
    (((ah * bh) as i64) << 32) + (mid << 16) + low
}

impl<Frac: LeEqU32 + 'static> fmt::Debug for Fx<Frac> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.to_f64())
    }
}
impl<Frac: LeEqU32 + 'static> fmt::Display for Fx<Frac> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(&self.to_f64(), f)
    }
}

impl<Frac: LeEqU32> Add for Fx<Frac> {
    type Output = Self;
    #[inline]
    fn add(self, rhs: Self) -> Self {
        Self::from_bits(self.bits.saturating_add(rhs.bits))
    }
}
impl<Frac: LeEqU32> Sub for Fx<Frac> {
    type Output = Self;
    #[inline]
    fn sub(self, rhs: Self) -> Self {
        Self::from_bits(self.bits.saturating_sub(rhs.bits))
    }
}
impl<Frac: LeEqU32> Mul for Fx<Frac> {
    type Output = Self;
    #[inline]
    fn mul(self, rhs: Self) -> Self {
        // On ARMv6-M, 16.16 operands below 128 in magnitude (positions,
        // rotations and normals in view of a small screen: nearly every
        // product of a frame) take three 32-bit multiplies and no 64-bit
        // arithmetic; the result is the same (`mul16_small`).
        #[cfg(all(target_arch = "arm", not(target_has_atomic = "ptr")))]
        if Self::FRAC == 16 {
            if let Some(bits) = mul16_small(self.bits, rhs.bits) {
                return Self::from_bits(bits);
            }
        }
        Self::sat(Self::mul_wide(self.bits, rhs.bits))
    }
}

/// The rounded 16.16 product `(a·b + 2¹⁵) >> 16` (what `mul_wide` gives
/// for 16 fraction bits) when `a` and `b` lie in `[−2²³, 2²³)`, in 32-bit
/// arithmetic; `None` otherwise.
///
/// With `a = aₕ·2¹⁶ + aₗ` (aₗ unsigned) and the same for `b`,
/// `a·b = (a·bₕ + aₕ·bₗ)·2¹⁶ + aₗ·bₗ`, so the floor of `(a·b + 2¹⁵)/2¹⁶`
/// is `a·bₕ + aₕ·bₗ + ⌊(aₗ·bₗ + 2¹⁵)/2¹⁶⌋` exactly. Here `|aₕ|, |bₕ| ≤ 2⁷`:
/// `|a·bₕ| ≤ 2³⁰`, `|aₕ·bₗ| < 2²³`, and `aₗ·bₗ + 2¹⁵ < 2³²`, so no step
/// overflows and the result (at most 2³⁰ + 2²⁴ in magnitude) needs no
/// saturation.
#[inline(always)]
#[cfg(any(test, all(target_arch = "arm", not(target_has_atomic = "ptr"))))]
pub(crate) fn mul16_small(a: i32, b: i32) -> Option<i32> {
    if ((a as u32).wrapping_add(SMALL16) | (b as u32).wrapping_add(SMALL16)) >= 2 * SMALL16 {
        return None;
    }
    Some(mul16_in_range(a, b))
}

/// `a·b` of three 16.16 raw-bit pairs as the plain dot product computes it
/// (each product rounded, summed left to right from zero with
/// saturation) when every operand lies in `[−2²³, 2²³)`, with one range
/// test for all six (the biased operands are all below 2²⁴ exactly when
/// their OR is) and [`mul16_small`]'s products; `None` otherwise.
#[inline(always)]
#[cfg(any(test, all(target_arch = "arm", not(target_has_atomic = "ptr"))))]
pub(crate) fn dot16_small3(a: [i32; 3], b: [i32; 3]) -> Option<i32> {
    if (bias16(a) | bias16(b)) >= 2 * SMALL16 {
        return None;
    }
    Some(dot16_in_range3(a, b))
}

/// [`dot16_small3`] without the range test: every operand in
/// `[−2²³, 2²³)`.
#[inline(always)]
#[cfg(any(test, all(target_arch = "arm", not(target_has_atomic = "ptr"))))]
fn dot16_in_range3(a: [i32; 3], b: [i32; 3]) -> i32 {
    let p0 = mul16_in_range(a[0], b[0]);
    let p1 = mul16_in_range(a[1], b[1]);
    let p2 = mul16_in_range(a[2], b[2]);
    p0.saturating_add(p1).saturating_add(p2)
}

/// `[m[i]·v]` as three [`dot16_small3`] rows compute them, when all
/// twelve operands lie in `[−2²³, 2²³)` (one test: their biased OR);
/// `None` otherwise.
#[inline(always)]
#[cfg(any(test, all(target_arch = "arm", not(target_has_atomic = "ptr"))))]
pub(crate) fn mat3_vec16_small(m: &[[i32; 3]; 3], v: [i32; 3]) -> Option<[i32; 3]> {
    if m.iter().fold(bias16(v), |any, r| any | bias16(*r)) >= 2 * SMALL16 {
        return None;
    }
    Some(m.map(|r| dot16_in_range3(r, v)))
}

/// `m` for many [`mat3_vec16_small`] products: `None` unless its nine
/// entries lie in `[−2²², 2²²)` (±64.0, see [`split16_dot`]), else each
/// entry `a` as `[a, aₕ, aₗ]` (its high half, signed, and its low half),
/// so that a product takes only the vector's halves.
#[inline]
#[cfg(any(test, all(target_arch = "arm", not(target_has_atomic = "ptr"))))]
pub(crate) fn mat3_split16(m: &[[i32; 3]; 3]) -> Option<[[[i32; 3]; 3]; 3]> {
    if !m.iter().all(|r| in_prepared16(*r)) {
        return None;
    }
    Some(m.map(split16_row))
}

/// One row's entries as `[a, aₕ, aₗ]` (see [`mat3_split16`]).
#[inline]
#[cfg(any(test, all(target_arch = "arm", not(target_has_atomic = "ptr"))))]
fn split16_row(r: [i32; 3]) -> [[i32; 3]; 3] {
    r.map(|a| [a, a >> 16, a & 0xffff])
}

/// `v` for many [`dot16_small3`] products with it: `None` unless its
/// entries lie in `[−2²², 2²²)` (as [`mat3_split16`]'s).
#[inline]
#[cfg(any(test, all(target_arch = "arm", not(target_has_atomic = "ptr"))))]
pub(crate) fn vec3_split16(v: [i32; 3]) -> Option<[[i32; 3]; 3]> {
    in_prepared16(v).then(|| split16_row(v))
}

/// Whether every entry of `v` lies in `[−2²², 2²²)`: the bound of a
/// prepared operand (see [`split16_dot`]).
#[inline(always)]
#[cfg(any(test, all(target_arch = "arm", not(target_has_atomic = "ptr"))))]
fn in_prepared16(v: [i32; 3]) -> bool {
    let b = |x: i32| (x as u32).wrapping_add(SMALL16 / 2);
    (b(v[0]) | b(v[1]) | b(v[2])) < SMALL16
}

/// Whether every entry of `v` lies in `[−2²³, 2²³)`.
#[inline(always)]
#[cfg(any(test, all(target_arch = "arm", not(target_has_atomic = "ptr"))))]
fn in_range16(v: [i32; 3]) -> bool {
    bias16(v) < 2 * SMALL16
}

/// The bound of the small 16.16 products' operands: `[−2²³, 2²³)`.
#[cfg(any(test, all(target_arch = "arm", not(target_has_atomic = "ptr"))))]
const SMALL16: u32 = 1 << 23;

/// The OR of `v`'s entries biased by 2²³: below 2²⁴ exactly when every
/// entry lies in `[−2²³, 2²³)`, so one compare tests several vectors.
#[inline(always)]
#[cfg(any(test, all(target_arch = "arm", not(target_has_atomic = "ptr"))))]
fn bias16(v: [i32; 3]) -> u32 {
    let b = |x: i32| (x as u32).wrapping_add(SMALL16);
    b(v[0]) | b(v[1]) | b(v[2])
}

/// The 16-bit halves of `v`'s entries, high (signed) and low.
#[inline(always)]
#[cfg(any(test, all(target_arch = "arm", not(target_has_atomic = "ptr"))))]
fn halves16(v: [i32; 3]) -> ([i32; 3], [i32; 3]) {
    // Written out, not mapped: at opt-level "s" a map over the components
    // became a loop through the stack.
    (
        [v[0] >> 16, v[1] >> 16, v[2] >> 16],
        [v[0] & 0xffff, v[1] & 0xffff, v[2] & 0xffff],
    )
}

/// A split row times a vector given by its halves: [`dot16_in_range3`]'s
/// value (each product is [`mul16_in_range`]'s sum, which is symmetric in
/// its operands, with the row's halves read, not formed).
///
/// The row's entries lie in `[−2²², 2²²)` ([`mat3_split16`] and
/// [`vec3_split16`] prepare no other) and the vector's in `[−2²³, 2²³)`,
/// so each rounded product is at most `2⁴⁵/2¹⁶ + 1 = 2²⁹ + 1` in
/// magnitude and the sum of three below 2³¹: the saturating sum of
/// [`dot16_in_range3`] never saturates here, and plain adds give its
/// value. (With saturating adds here, ARMv6-M W1/W2 took 5.12 M / 6.12 M
/// instructions per frame; 5.10 M / 6.11 M without.)
#[inline(always)]
#[cfg(any(test, all(target_arch = "arm", not(target_has_atomic = "ptr"))))]
fn split16_dot(r: &[[i32; 3]; 3], h: [i32; 3], l: [i32; 3]) -> i32 {
    // Wrapping: exact for a row from `split16_row`, and no overflow panic
    // for any other array given to the public
    // `Scalar::mat3_vec3_prepared` / `dot3_prepared`.
    #[inline(always)]
    fn p([a, ah, al]: [i32; 3], bh: i32, bl: i32) -> i32 {
        let low = ((al as u32).wrapping_mul(bl as u32).wrapping_add(1 << 15) >> 16) as i32;
        a.wrapping_mul(bh)
            .wrapping_add(ah.wrapping_mul(bl))
            .wrapping_add(low)
    }
    p(r[0], h[0], l[0])
        .wrapping_add(p(r[1], h[1], l[1]))
        .wrapping_add(p(r[2], h[2], l[2]))
}

/// [`mat3_vec16_small`]`(m, v)` for `split = mat3_split16(m)`: the same
/// values, `None` when an entry of `v` is out of range.
#[inline(always)]
#[cfg(any(test, all(target_arch = "arm", not(target_has_atomic = "ptr"))))]
pub(crate) fn mat3_split16_vec(split: &[[[i32; 3]; 3]; 3], v: [i32; 3]) -> Option<[i32; 3]> {
    if !in_range16(v) {
        return None;
    }
    let (h, l) = halves16(v);
    Some([
        split16_dot(&split[0], h, l),
        split16_dot(&split[1], h, l),
        split16_dot(&split[2], h, l),
    ])
}

/// [`dot16_small3`]`(w, v)` for `split = vec3_split16(v)`: the same value,
/// `None` when an entry of `w` is out of range.
#[inline(always)]
#[cfg(any(test, all(target_arch = "arm", not(target_has_atomic = "ptr"))))]
pub(crate) fn vec3_split16_dot(split: &[[i32; 3]; 3], w: [i32; 3]) -> Option<i32> {
    if !in_range16(w) {
        return None;
    }
    let (h, l) = halves16(w);
    Some(split16_dot(split, h, l))
}

/// [`mul16_small`] without the range test: `a` and `b` in `[−2²³, 2²³)`.
#[inline(always)]
#[cfg(any(test, all(target_arch = "arm", not(target_has_atomic = "ptr"))))]
fn mul16_in_range(a: i32, b: i32) -> i32 {
    let (al, ah) = ((a & 0xffff) as u32, a >> 16);
    let (bl, bh) = ((b & 0xffff) as u32, b >> 16);
    let low = ((al * bl + (1 << 15)) >> 16) as i32;
    a * bh + ah * bl as i32 + low
}
impl<Frac: LeEqU32> Div for Fx<Frac> {
    type Output = Self;
    #[inline]
    fn div(self, rhs: Self) -> Self {
        match rhs.bits {
            0 => Self::from_bits(match self.bits.cmp(&0) {
                Ordering::Greater => i32::MAX,
                Ordering::Less => i32::MIN,
                Ordering::Equal => 0,
            }),
            b => Self::sat(Self::div_wide(self.bits, b)),
        }
    }
}
impl<Frac: LeEqU32> Neg for Fx<Frac> {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Self::from_bits(self.bits.saturating_neg())
    }
}
macro_rules! assign_ops {
    ($($tr:ident $m:ident $op:tt),*) => {$(
        impl<Frac: LeEqU32> $tr for Fx<Frac> {
            #[inline]
            fn $m(&mut self, rhs: Self) {
                *self = *self $op rhs;
            }
        }
    )*};
}
assign_ops!(AddAssign add_assign +, SubAssign sub_assign -, MulAssign mul_assign *, DivAssign div_assign /);

impl<Frac: LeEqU32> From<FixedI32<Frac>> for Fx<Frac> {
    fn from(v: FixedI32<Frac>) -> Self {
        Self::from_fixed(v)
    }
}

// Constants in Q2.30 (and Q0.32 for the turn conversion), from exact decimal
// expansions rounded to nearest.
const Q30_ONE: i64 = 1 << 30;
const PI_Q30: i64 = 3_373_259_426;
const PI_2_Q30: i64 = 1_686_629_713;
const PI_4_Q30: i64 = 843_314_857;
const TAN_PI_8_Q30: i64 = 444_758_426;
/// round(2³² / 2π): radians → turns in Q0.32.
const INV_TAU_Q32: i64 = 683_565_276;
/// round(π · 2⁶¹): π for every `Frac` by one rounded shift.
const PI_Q61: i64 = 7_244_019_458_077_122_842;

/// Saturates an `i64` into `i32`, usable in constants.
const fn sat_i32(v: i64) -> i32 {
    if v > i32::MAX as i64 {
        i32::MAX
    } else if v < i32::MIN as i64 {
        i32::MIN
    } else {
        v as i32
    }
}

#[inline]
fn q30_mul(a: i64, b: i64) -> i64 {
    (a * b + (1 << 29)) >> 30
}

/// sin(x) and cos(x) for 0 ≤ x ≤ π/4, in Q2.30 (Taylor to x⁹ and x¹⁰).
fn sin_cos_octant_q30(x: i64) -> (i64, i64) {
    let x2 = q30_mul(x, x);
    // 1/3!, 1/5!, 1/7!, 1/9! and 1/2!, 1/4!, ..., 1/10! in Q2.30.
    let mut s = 2_959; // 1/9!
    s = 213_044 - q30_mul(x2, s); // 1/7!
    s = 8_947_849 - q30_mul(x2, s); // 1/5!
    s = 178_956_971 - q30_mul(x2, s); // 1/3!
    s = Q30_ONE - q30_mul(x2, s);
    let sin = q30_mul(x, s);
    let mut c = 296; // 1/10!
    c = 26_631 - q30_mul(x2, c); // 1/8!
    c = 1_491_308 - q30_mul(x2, c); // 1/6!
    c = 44_739_243 - q30_mul(x2, c); // 1/4!
    c = 536_870_912 - q30_mul(x2, c); // 1/2!
    let cos = Q30_ONE - q30_mul(x2, c);
    (sin, cos)
}

/// atan(w) for |w| ≤ tan(π/8), in Q2.30 (Taylor to w¹⁵).
fn atan_small_q30(w: i64) -> i64 {
    let w2 = q30_mul(w, w);
    // 1/15, 1/13, ..., 1/3 in Q2.30, alternating.
    let mut p = 71_582_788;
    p = 82_595_525 - q30_mul(w2, p);
    p = 97_612_893 - q30_mul(w2, p);
    p = 119_304_647 - q30_mul(w2, p);
    p = 153_391_689 - q30_mul(w2, p);
    p = 214_748_365 - q30_mul(w2, p);
    p = 357_913_941 - q30_mul(w2, p);
    p = Q30_ONE - q30_mul(w2, p);
    q30_mul(w, p)
}

fn isqrt_u64(n: u64) -> u64 {
    // Digit-by-digit (base 4) square root, floor.
    let mut x = n;
    let mut r = 0u64;
    let mut one = 1u64 << 62;
    while one > x {
        one >>= 2;
    }
    while one != 0 {
        if x >= r + one {
            x -= r + one;
            r = (r >> 1) + one;
        } else {
            r >>= 1;
        }
        one >>= 2;
    }
    // Round to nearest: n - r² > r  ⇔  n > (r + ½)².
    if x > r { r + 1 } else { r }
}

impl<Frac: LeEqU32 + 'static> Scalar for Fx<Frac> {
    const ZERO: Self = Self::from_bits(0);
    const ONE: Self = Self::from_bits(1 << Self::FRAC);
    const TWO: Self = Self::from_bits(sat_i32((2i64) << Self::FRAC));
    const HALF: Self = Self::from_bits(1 << (Self::FRAC - 1));
    const PI: Self = Self::from_bits(sat_i32(
        (PI_Q61 + (1i64 << (60 - Self::FRAC))) >> (61 - Self::FRAC),
    ));
    const EPSILON: Self = Self::from_bits(1);
    const MAX: Self = Self::from_bits(i32::MAX);
    const MIN: Self = Self::from_bits(i32::MIN);
    const IS_FLOAT: bool = false;
    const NAME: &'static str = match Self::FRAC {
        8 => "I24F8",
        12 => "I20F12",
        16 => "I16F16",
        30 => "I2F30",
        _ => "Fx",
    };

    fn from_f64(x: f64) -> Self {
        if x.is_nan() {
            return Self::ZERO;
        }
        let v = x * (1u64 << Self::FRAC) as f64;
        // Round half away from zero without libm: `as` truncates and saturates.
        let r = if v >= 0.0 { v + 0.5 } else { v - 0.5 };
        Self::from_bits(r as i32)
    }
    /// The same value as `from_f64(x as f64)` (round half away from zero,
    /// saturated, NaN → 0), decoded from the bits in integers: a firmware
    /// on a core without an FPU that converts an `f32` scene description
    /// links no soft-float code for it (`from_f64` needs 64-bit float
    /// multiply, add and compares, about 2.5 KB on ARMv6-M).
    fn from_f32(x: f32) -> Self {
        Self::from_bits(f32_to_fixed_bits(x, Self::FRAC))
    }
    fn from_i32(x: i32) -> Self {
        Self::sat((x as i64) << Self::FRAC)
    }
    fn try_from_f64(x: f64) -> Option<Self> {
        let v = x * (1u64 << Self::FRAC) as f64;
        if v.is_finite() && v > i32::MIN as f64 - 0.5 && v < i32::MAX as f64 + 0.5 {
            Some(Self::from_f64(x))
        } else {
            None
        }
    }
    fn to_f64(self) -> f64 {
        self.bits as f64 / (1u64 << Self::FRAC) as f64
    }
    fn to_f32(self) -> f32 {
        self.to_f64() as f32
    }
    fn is_finite(self) -> bool {
        true
    }
    fn abs(self) -> Self {
        Self::from_bits(self.bits.saturating_abs())
    }
    fn sqrt(self) -> Self {
        if self.bits <= 0 {
            return Self::ZERO;
        }
        let n = (self.bits as u64) << Self::FRAC;
        // sqrt(2³¹ · 2³⁰) < 2³¹: always fits.
        Self::from_bits(isqrt_u64(n) as i32)
    }
    fn sin_cos(self) -> (Self, Self) {
        // Radians → turns in Q0.32; the `as u32` wrap is the exact reduction
        // modulo one turn.
        let turns = ((self.bits as i64 * INV_TAU_Q32) >> Self::FRAC) as u32;
        let octant = turns >> 29;
        let mut r = (turns & ((1 << 29) - 1)) as i64;
        if octant & 1 == 1 {
            r = (1 << 29) - r;
        }
        let x = (r * PI_4_Q30 + (1 << 28)) >> 29;
        let (s, c) = sin_cos_octant_q30(x);
        let (s, c) = if octant & 1 == 1 { (c, s) } else { (s, c) };
        let (s, c) = match octant >> 1 {
            0 => (s, c),
            1 => (c, -s),
            2 => (-s, -c),
            _ => (-c, s),
        };
        (Self::from_q30(s), Self::from_q30(c))
    }
    fn atan2(self, x: Self) -> Self {
        let (y, x) = (self.bits as i64, x.bits as i64);
        if x == 0 && y == 0 {
            return Self::ZERO;
        }
        let (ax, ay) = (x.abs(), y.abs());
        let (num, den, swapped) = if ay > ax {
            (ax, ay, true)
        } else {
            (ay, ax, false)
        };
        let z = (num << 30) / den; // Q2.30 in [0, 1]
        let mut a = if z > TAN_PI_8_Q30 {
            PI_4_Q30 + atan_small_q30(((z - Q30_ONE) << 30) / (z + Q30_ONE))
        } else {
            atan_small_q30(z)
        };
        if swapped {
            a = PI_2_Q30 - a;
        }
        if x < 0 {
            a = PI_Q30 - a;
        }
        if y < 0 {
            a = -a;
        }
        Self::from_q30(a)
    }
    fn checked_add(self, rhs: Self) -> Option<Self> {
        self.bits.checked_add(rhs.bits).map(Self::from_bits)
    }
    fn checked_sub(self, rhs: Self) -> Option<Self> {
        self.bits.checked_sub(rhs.bits).map(Self::from_bits)
    }
    #[inline]
    fn dot_fast<const N: usize>(a: [Self; N], b: [Self; N]) -> Option<Self> {
        // On ARMv6-M, a 16.16 dot product of three whose operands all lie
        // in [−2^23, 2^23) takes `dot16_small3`: the same value as the
        // plain sum, with one range test and no 64-bit arithmetic.
        #[cfg(all(target_arch = "arm", not(target_has_atomic = "ptr")))]
        if Self::FRAC == 16 && N == 3 {
            let bits = |v: [Self; N]| [v[0].bits, v[1].bits, v[2].bits];
            return dot16_small3(bits(a), bits(b)).map(Self::from_bits);
        }
        let _ = (a, b);
        None
    }
    #[inline]
    fn mat3_vec3_fast(m: &[[Self; 3]; 3], v: [Self; 3]) -> Option<[Self; 3]> {
        // On ARMv6-M, three `dot16_small3` rows behind one range test of
        // the twelve operands (the vector's are shared): the same values.
        #[cfg(all(target_arch = "arm", not(target_has_atomic = "ptr")))]
        if Self::FRAC == 16 {
            let mb = m.map(|r| r.map(|x| x.bits));
            return mat3_vec16_small(&mb, v.map(|x| x.bits)).map(|r| r.map(Self::from_bits));
        }
        let _ = (m, v);
        None
    }
    #[inline]
    fn mat3_prepare(m: &[[Self; 3]; 3]) -> Option<[[[i32; 3]; 3]; 3]> {
        // On ARMv6-M: the twelve-operand range test of `mat3_vec3_fast`
        // split into the matrix's, once, and the vector's, per product.
        #[cfg(all(target_arch = "arm", not(target_has_atomic = "ptr")))]
        if Self::FRAC == 16 {
            return mat3_split16(&m.map(|r| r.map(|x| x.bits)));
        }
        let _ = m;
        None
    }
    #[inline]
    fn dot3_prepare(v: [Self; 3]) -> Option<[[i32; 3]; 3]> {
        #[cfg(all(target_arch = "arm", not(target_has_atomic = "ptr")))]
        if Self::FRAC == 16 {
            return vec3_split16(v.map(|x| x.bits));
        }
        let _ = v;
        None
    }
    #[inline]
    fn dot3_prepared(prepared: &[[i32; 3]; 3], w: [Self; 3]) -> Option<Self> {
        #[cfg(all(target_arch = "arm", not(target_has_atomic = "ptr")))]
        if Self::FRAC == 16 {
            return vec3_split16_dot(prepared, w.map(|x| x.bits)).map(Self::from_bits);
        }
        let _ = (prepared, w);
        None
    }
    #[inline]
    fn mat3_vec3_prepared(prepared: &[[[i32; 3]; 3]; 3], v: [Self; 3]) -> Option<[Self; 3]> {
        #[cfg(all(target_arch = "arm", not(target_has_atomic = "ptr")))]
        if Self::FRAC == 16 {
            return mat3_split16_vec(prepared, v.map(|x| x.bits)).map(|r| r.map(Self::from_bits));
        }
        let _ = (prepared, v);
        None
    }
    fn checked_mul(self, rhs: Self) -> Option<Self> {
        // See `Mul`: small 16.16 operands on ARMv6-M, the same result.
        #[cfg(all(target_arch = "arm", not(target_has_atomic = "ptr")))]
        if Self::FRAC == 16 {
            if let Some(bits) = mul16_small(self.bits, rhs.bits) {
                return Some(Self::from_bits(bits));
            }
        }
        Self::fits(Self::mul_wide(self.bits, rhs.bits))
    }
    fn checked_div(self, rhs: Self) -> Option<Self> {
        if rhs.bits == 0 {
            None
        } else {
            Self::fits(Self::div_wide(self.bits, rhs.bits))
        }
    }
    #[inline]
    fn perspective_fast(x: Self, y: Self, z: Self, focus: Self) -> Option<(Self, Self, Self)> {
        if Self::FRAC != 16 {
            return None;
        }
        let (sx, sy, inv_z) = perspective16(x.bits, y.bits, z.bits, focus.bits)?;
        Some((
            Self::from_bits(sx),
            Self::from_bits(sy),
            Self::from_bits(inv_z),
        ))
    }
    fn checked_quotients<const N: usize>(nums: [Self; N], d: Self) -> [Option<Self>; N] {
        let f = Self::FRAC;
        let dm = d.bits.unsigned_abs();
        // d' = |d|·2^s in [2^30, 2^31); |d| = 0 or 2^31 divide one by one.
        if dm == 0 || dm >= 1 << 31 {
            return nums.map(|n| n.checked_div(d));
        }
        let s = normalize_shift(dm);
        let sh = 62 - f as i32 - s as i32;
        if sh < 0 {
            return nums.map(|n| n.checked_div(d));
        }
        let sh = sh as u32;
        // r = 2^62/d' + ε with 0 ≤ ε < 1, so |n|·r/2^sh exceeds the exact
        // |n|·2^f/|d| by |n|·ε/2^sh: less than one while |n| < 2^sh.
        let r = recip62(dm << s);
        nums.map(|n| {
            let a = n.bits.unsigned_abs();
            if sh < 32 && a >= 1 << sh {
                return n.checked_div(d);
            }
            // a ≤ 2^31 and r ≤ 2^32: the product fits u64.
            let p = if r >> 32 != 0 {
                (a as u64) << 32
            } else {
                widening_mul_u32(a, r as u32)
            };
            // ⌊exact⌋ or one more; beyond 2^32 the quotient is out of range.
            let q = shr_to_u32(p, sh)? as u64;
            let num = (a as u64) << f;
            let qd = widening_mul_u32(q as u32, dm);
            let (q, rem) = if qd > num {
                (q - 1, num - (qd - dm as u64))
            } else {
                (q, num - qd)
            };
            // Round half away from zero, as `div_wide`: rem < |d| < 2^31.
            let q = if 2 * rem >= dm as u64 { q + 1 } else { q };
            let q = q as i64;
            Self::fits(if (n.bits < 0) != (d.bits < 0) { -q } else { q })
        })
    }
    fn sub_mul_noting_overflow(self, a: Self, b: Self, overflow: &mut bool) -> Self {
        let f = Self::FRAC;
        // |self·2ᶠ| ≤ 2⁶¹ and |a·b| ≤ 2⁶², so the i64 never overflows.
        let exact = ((self.bits as i64) << f) - widening_mul(a.bits, b.bits);
        let v = (exact + (1i64 << (f - 1))) >> f;
        match Self::fits(v) {
            Some(r) => r,
            None => {
                *overflow = true;
                Self::sat(v)
            }
        }
    }
    fn div_noting_overflow(self, d: Self, overflow: &mut bool) -> Self {
        match self.checked_div(d) {
            Some(r) => r,
            None => {
                *overflow = true;
                self / d
            }
        }
    }
    fn to_subpixel(self, frac_bits: u32) -> Option<i32> {
        let f = Self::FRAC as i32;
        let s = frac_bits.min(24) as i32 - f;
        let v = self.bits as i64;
        let r = if s >= 0 {
            v << s
        } else {
            let sh = (-s) as u32;
            // Round half away from zero, as the float paths do.
            let half = 1i64 << (sh - 1);
            if v >= 0 {
                (v + half) >> sh
            } else {
                -((-v + half) >> sh)
            }
        };
        i32::try_from(r).ok()
    }
    fn orient2d(a: [Self; 2], b: [Self; 2], c: [Self; 2]) -> Option<Ordering> {
        // Raw differences fit 33 bits, their products 66: exact in i128.
        let w = |v: Self| v.bits as i128;
        let det =
            (w(b[0]) - w(a[0])) * (w(c[1]) - w(a[1])) - (w(b[1]) - w(a[1])) * (w(c[0]) - w(a[0]));
        Some(det.cmp(&0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn q30_conversion_rounds_to_nearest() {
        assert_eq!(I16F16::from_q30(5 << 28), I16F16::from_f64(1.25));
        // 2⁻¹⁷ in Q30 is half a step of Q16: rounds up (ties toward +∞).
        assert_eq!(I16F16::from_q30(1 << 13).to_bits(), 1);
        assert_eq!(I16F16::from_q30((1 << 13) - 1).to_bits(), 0);
    }

    #[test]
    fn isqrt_is_rounded_floor_exact() {
        for n in [
            0u64,
            1,
            2,
            3,
            4,
            15,
            16,
            17,
            1 << 40,
            (1 << 61) + 12345,
            u64::MAX >> 2,
        ] {
            let r = isqrt_u64(n) as u128;
            let n = n as u128;
            // r is the nearest integer to √n: (r-½)² ≤ n < (r+½)², i.e.
            // 4n ≥ (2r-1)² and 4n < (2r+1)².
            assert!(4 * n < (2 * r + 1) * (2 * r + 1), "n={n} r={r}");
            if r > 0 {
                assert!(4 * n >= (2 * r - 1) * (2 * r - 1), "n={n} r={r}");
            }
        }
    }

    #[test]
    fn pi_and_names() {
        assert_eq!(I16F16::PI.to_bits(), 205_887); // round(π·65536)
        // π and 2 do not fit Q2.30's range (±2): they saturate.
        assert_eq!(I2F30::PI, I2F30::MAX);
        assert_eq!(I2F30::TWO, I2F30::MAX);
        assert_eq!(I16F16::NAME, "I16F16");
    }
}
