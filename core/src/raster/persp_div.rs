//! The perspective divide of the texture shaders, `u = (u·q) / q` with
//! q = near/z, without a division instruction: ARMv6-M (Cortex-M0) has
//! none, and a 64-bit division in compiler-builtins costs hundreds of
//! instructions. Used by [`PerspectiveTexture`](super::PerspectiveTexture).

use super::PERSPECTIVE_Q_BITS;
use crate::scalar::{recip46_below, recip62_above};

/// Below this many units of 2^−16 (2^13 texels) [`divide`] returns the
/// exact truncated quotient.
pub(crate) const EXACT_BELOW: u64 = 1 << 29;

/// (u, v) in 16.16 from (u·q, v·q) in 16.16 and q = near/z in 8.24, with
/// one reciprocal instead of two divisions.
///
/// `r` = [`recip62_above`]`(q')` for `q' = q·2^s` normalized to
/// `[2^30, 2^31)`, so `R ≤ r ≤ R + 4` for `R = 2^62/q'`. Each magnitude is then `e = |u·q|·r >> (38 − s)`: never below the
/// truncated exact quotient `T = ⌊|u·q|·2^24 / q⌋`, and above it by at
/// most `4·T/2^31 + 1` units (`r − R ≤ 4`, `R > 2^31`). Below
/// [`EXACT_BELOW`] that excess is below 1, so `e` is `T` or `T + 1`, and
/// the sign of `|u·q|·2^24 − e·q`, which lies in `(−q, q)` and so is exact
/// in wrapping 32-bit arithmetic, says which: the result is exactly `T`
/// with the sign of `u·q` (truncation toward zero, as a division). Beyond
/// it (|u| of 2^13 texels or more) it is within `4·T/2^31 + 1` units
/// above `T`. Checked against the exact quotient in i128 by
/// `perspective_divide_is_the_exact_quotient`. q ≤ 0 is taken as 1.
///
/// On ARMv6-M, which has no divide instruction, this is a table load,
/// a few 32-bit multiplies and no library call, where exact division is
/// two 64-bit divisions (each some hundreds of instructions in
/// compiler-builtins). (With the ceiling reciprocal `recip62`, its unit
/// steps and no correction, within one unit instead of exact, the exactly
/// divided corridor frame cost 35.99 M instructions on ARMv6-M; 30.09 M
/// with this.)
#[inline]
pub(crate) fn divide(v: &[i32; 3]) -> (i64, i64) {
    let (q, estimate) = estimator(v[2]);
    let one = |x: i32| -> i64 {
        let a = x.unsigned_abs();
        let mut m = estimate(a);
        if m < EXACT_BELOW {
            m -= u64::from(one_above(a, m as u32, q));
        }
        // m < 2^55 (sh ≥ 8), so it fits i64 either way.
        if x < 0 { -(m as i64) } else { m as i64 }
    };
    (one(v[0]), one(v[1]))
}

/// [`divide`] where both quotients are small: `Some` with exactly
/// [`divide`]'s values (as i32) when each magnitude is below
/// [`EXACT_BELOW`] before the correction step, else `None`. The
/// subdivided texture shader's fast path, which then steps in i32.
///
/// On ARMv6-M, in 32-bit arithmetic where it can ([`quotients`]: `q` in
/// `[2^8, 2^24]`, quotients below `2^29 − 2^16` in magnitude); elsewhere,
/// and outside that range, by [`recip62_above`]'s reciprocal and 64-bit
/// products, which cores with a 32×32→64 multiply run faster. The same
/// values either way (`bash tests/mcu/run`, ARMv6-M: ipp persp16
/// 41.31 -> 34.19, persp16-depth 47.93 -> 40.81; on the Cortex-M4 the
/// 32-bit route cost 22.50 -> 22.94 and 30.00 -> 30.44, counted on the
/// tests/mcu firmware's `fill` runs by `../shared/tools/qemu-prof`).
#[inline]
pub(crate) fn divide_small(v: &[i32; 3]) -> Option<(i32, i32)> {
    if crate::scalar::ARMV6M {
        quotients(v).or_else(|| divide_small_wide(v))
    } else {
        divide_small_wide(v)
    }
}

/// [`divide_small`] by [`recip62_above`]: a reciprocal good to 32 bits
/// and 64-bit products, for any `q`. (Exact mode calls it where
/// [`texels`] has no answer, and then [`quotients`] has none either.)
#[inline]
pub(crate) fn divide_small_wide(v: &[i32; 3]) -> Option<(i32, i32)> {
    let (q, estimate) = estimator(v[2]);
    let one = |x: i32| -> Option<i32> {
        let a = x.unsigned_abs();
        let m = estimate(a);
        if m >= EXACT_BELOW {
            return None;
        }
        // m < 2^29, so it is exact in i32.
        let m = (m as u32 - u32::from(one_above(a, m as u32, q))) as i32;
        Some(if x < 0 { -m } else { m })
    };
    Some((one(v[0])?, one(v[1])?))
}

/// The texels exact mode samples at varyings `v` = (u·q, v·q, q): each
/// `T >> 16` for the truncated quotient `T = trunc(x·2^24/q)` of
/// [`divide`], found at texel precision: `Some` when `q` is in
/// `[2^8, 2^24]` and each texel lies within about ±2^15, else `None` (the
/// caller then divides at full precision).
///
/// With `a = |x|` and `G = ⌊a·2^8/q⌋`, `E = a·2^8 − G·q` in `[0, q)`,
/// the texel is `G` for `x ≥ 0`; for `x < 0` it is `−G`, or `−G − 1` when
/// `E ≥ ⌈q/2^16⌉` (T truncated toward zero, then floored by the shift).
/// The estimate `g = ⌊⌊a·r/2^16⌋ / 2^(22−s)⌋` with `r` =
/// [`recip46_below`]`(q·2^s)` (at or below `2^46/(q·2^s)`, within 2^−13 of
/// it) is never above `G`, and below 2^15 at most 7 below it: then
/// `a·2^8 − g·q` lies in `[0, 8q)`, below 2^27, so wrapping 32-bit
/// arithmetic computes it exactly, and `g` steps up to `G` by it. Checked
/// against i128 quotients by `texels_are_the_exact_quotients` and
/// `texels_at_the_sign_rule`.
///
/// On ARMv6-M that is a table load and six 32-bit multiplies where
/// [`divide_small_wide`] forms 64-bit products and a second Newton step
/// (`bash tests/mcu/run`, I16F16 corridor scene frame: ARMv6-M
/// 6 226 884 -> 5 851 281 instructions, Cortex-M4 4 618 491 ->
/// 4 565 987; 332 bytes in the v6m texture firmware). On the x86-64
/// host, with its 64-bit multiplier, it is about even (`workload fill
/// persp`, callgrind: 45.9 -> 46.1 instructions per pixel); one routine
/// everywhere.
#[inline]
pub(crate) fn texels(v: &[i32; 3]) -> Option<(i32, i32)> {
    let d = Short::new(v[2])?;
    let ceil = (d.q + 0xffff) >> 16;
    let one = |x: i32| -> Option<i32> {
        let (g, e) = d.floor(x.unsigned_abs(), 1 << 15)?;
        let g = g as i32;
        Some(if x < 0 { -g - i32::from(e >= ceil) } else { g })
    };
    Some((one(v[0])?, one(v[1])?))
}

/// [`divide`]'s quotients `T = trunc(x·2^24/q)` in 32-bit arithmetic:
/// `Some` when `q` is in `[2^8, 2^24]` and each `|T|` is below
/// `2^29 − 2^16`, where [`divide`] is exact too, else `None`.
///
/// `|T| = G·2^16 + ⌊E·2^16/q⌋` for `G = ⌊|x|·2^8/q⌋` and its remainder
/// `E` (see [`texels`]); the fraction is estimated from the same
/// reciprocal, never above it and at most 10 below it (`f·2^−13` plus
/// two truncations, for `f < 2^16`), so `E·2^16 − f̂·q` lies in
/// `[0, 11q)`, below 2^28, and is exact in wrapping 32-bit arithmetic:
/// it steps the estimate up to the fraction. Checked against i128
/// quotients by `quotients_are_the_exact_quotients`,
/// `quotients_near_a_unit` and `quotients_at_their_limit`.
#[inline]
pub(crate) fn quotients(v: &[i32; 3]) -> Option<(i32, i32)> {
    const G_MAX: u32 = (1 << (29 - 16)) - 1;
    let d = Short::new(v[2])?;
    let one = |x: i32| -> Option<i32> {
        let (g, e) = d.floor(x.unsigned_abs(), G_MAX)?;
        if g >= G_MAX {
            return None;
        }
        let t = ((g << 16) | d.fraction(e)) as i32;
        Some(if x < 0 { -t } else { t })
    };
    Some((one(v[0])?, one(v[1])?))
}

/// A divisor `q` in `[2^8, 2^24]` with the reciprocal estimate that
/// [`texels`] and [`quotients`] share: `r` = [`recip46_below`]`(q·2^s)`
/// for `q·2^s` in `[2^30, 2^31)` (so `s` is in `[6, 22]`), at or below
/// `2^46/(q·2^s)` and within 2^−13 of it.
#[derive(Clone, Copy)]
struct Short {
    q: u32,
    r: u32,
    /// `22 − s`, in `[0, 16]`.
    sh: u32,
}

impl Short {
    #[inline(always)]
    fn new(q: i32) -> Option<Self> {
        if !(1 << 8..=1 << PERSPECTIVE_Q_BITS).contains(&q) {
            return None;
        }
        let q = q as u32;
        let s = crate::scalar::normalize_shift(q);
        Some(Self {
            q,
            r: recip46_below(q << s),
            sh: 22 - s,
        })
    }

    /// `G = ⌊a·2^8/q⌋` and `E = a·2^8 − G·q` when the estimate of `G` is
    /// below `limit` (at most 2^15), else `None`. `G ≈ a·2^(8+s)/(q·2^s)
    /// ≈ a·r/2^(38−s)`: the estimate `g = ⌊⌊a·r/2^16⌋ / 2^(22−s)⌋` is never
    /// above `G`, and below 2^15 at most 7 below it, so `a·2^8 − g·q` lies
    /// in `[0, 8q)`, below 2^27: exact in wrapping 32-bit arithmetic.
    #[inline(always)]
    fn floor(&self, a: u32, limit: u32) -> Option<(u32, u32)> {
        // ⌊a·r/2^16⌋ from a's halves: each product is below 2^32, the sum
        // below 2^31 + 2^16.
        let p = (a >> 16) * self.r + (((a & 0xffff) * self.r) >> 16);
        let mut g = p >> self.sh;
        if g >= limit {
            return None;
        }
        let mut e = (a << 8).wrapping_sub(g.wrapping_mul(self.q));
        while e >= self.q {
            g += 1;
            e -= self.q;
        }
        Some((g, e))
    }

    /// `⌊e·2^16/q⌋` for `e` in `[0, q)`: estimated as
    /// `⌊⌊e·r/2^8⌋ / 2^(22−s)⌋` (at most 10 below, never above), then
    /// stepped up by the exact remainder `e·2^16 − f·q` (below 2^28).
    #[inline(always)]
    fn fraction(&self, e: u32) -> u32 {
        // ⌊e·r/2^8⌋ from e's halves (e < 2^24): (e >> 16)·r < 2^24, and
        // the sum is at most e·r/2^8 < 2^32.
        let p = (((e >> 16) * self.r) << 8) + (((e & 0xffff) * self.r) >> 8);
        let mut f = p >> self.sh;
        let mut rest = (e << 16).wrapping_sub(f.wrapping_mul(self.q));
        while rest >= self.q {
            f += 1;
            rest -= self.q;
        }
        f
    }
}

/// `q = max(q, 1)` and the estimate `a ↦ e = a·r >> (38 − s)` of the
/// truncated quotient `⌊a·2^24 / q⌋` (see [`divide`]: never below it).
#[inline(always)]
fn estimator(q: i32) -> (u32, impl Fn(u32) -> u64) {
    // q in [1, 2^31); s in [0, 30].
    let q = q.max(1) as u32;
    let s = crate::scalar::normalize_shift(q);
    #[cfg(all(target_arch = "arm", not(target_has_atomic = "ptr")))]
    let mag = mag_halves;
    #[cfg(not(all(target_arch = "arm", not(target_has_atomic = "ptr"))))]
    let mag = mag_wide;
    let r = recip62_above(q << s);
    let sh = 62 - PERSPECTIVE_Q_BITS - s;
    (q, move |a| mag(a, r, sh))
}

/// Whether the estimate `m` (the truncated quotient of `a·2^24` by `q`,
/// or one above it, below [`EXACT_BELOW`]) is the one above: then
/// `a·2^24 − m·q`, which lies in `(−q, q)` and so is exact in its low 32
/// bits read as i32, is negative.
#[inline(always)]
fn one_above(a: u32, m: u32, q: u32) -> bool {
    ((a << PERSPECTIVE_Q_BITS).wrapping_sub(m.wrapping_mul(q)) as i32) < 0
}

/// `a·r >> sh` for `r ≤ 2^32` (the product is below 2^64), in u64: what
/// cores with a 32×32→64 multiply and a clz instruction run best (the
/// Cortex-M4F lost 13 % of the corridor frame to [`mag_halves`]).
#[cfg(any(test, not(all(target_arch = "arm", not(target_has_atomic = "ptr")))))]
#[inline(always)]
fn mag_wide(a: u32, r: u64, sh: u32) -> u64 {
    (a as u64 * r) >> sh
}

/// [`mag_wide`] on ARMv6-M, where a u64 product and a variable u64 shift
/// are library calls (`__aeabi_lmul`, `__aeabi_llsr`): a 32×32→64
/// multiply (`r = 2^32` exactly is a shift) and a shift of 32-bit halves.
#[cfg(any(test, all(target_arch = "arm", not(target_has_atomic = "ptr"))))]
#[inline(always)]
fn mag_halves(a: u32, r: u64, sh: u32) -> u64 {
    let p = if r >> 32 != 0 {
        (a as u64) << 32
    } else {
        crate::scalar::widening_mul_u32(a, r as u32)
    };
    crate::scalar::shr_u64(p, sh)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::vec;

    #[test]
    fn mag_halves_is_mag_wide() {
        let mut x = 0x2545_f491_4f6c_dd1d_u64;
        let mut rs = vec![1u64 << 32, (1 << 31) + 1, u32::MAX as u64];
        let mut cases = std::vec::Vec::new();
        for _ in 0..50_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            rs.push((1 << 31) + (x >> 33) + 1);
            let a = (x >> (x & 31)) as u32;
            cases.push((a, rs[rs.len() - 1], 8 + (x >> 40) as u32 % 31));
        }
        for a in [0, 1, u32::MAX, 1 << 31] {
            for &r in &rs[..3] {
                for sh in 8..=38 {
                    cases.push((a, r, sh));
                }
            }
        }
        for (a, r, sh) in cases {
            assert_eq!(
                mag_halves(a, r, sh),
                mag_wide(a, r, sh),
                "a {a} r {r} sh {sh}"
            );
        }
    }
}
