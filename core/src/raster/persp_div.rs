//! The perspective divide of the texture shaders, `u = (u·q) / q` with
//! q = near/z, without a division instruction: ARMv6-M (Cortex-M0) has
//! none, and a 64-bit division in compiler-builtins costs hundreds of
//! instructions. Used by [`PerspectiveTexture`](super::PerspectiveTexture).

use super::PERSPECTIVE_Q_BITS;
use crate::scalar::recip62;

/// (u, v) in 16.16 from (u·q, v·q) in 16.16 and q = near/z in 8.24, with
/// one reciprocal instead of two divisions: `r = ⌈2^62 / q'⌉` for
/// `q' = q·2^s` normalized to `[2^30, 2^31)`, then `|u·q|·r >> (38 − s)`
/// with the sign of `u·q` (truncation toward zero, as a division). `r`
/// rounds up, so the magnitude is never below the exact quotient's and
/// exceeds it by less than 2^−31 of it: by less than one unit of 2^−16
/// while |u| is below 2^15 texels (the i32 range of the varyings), where
/// the result equals the truncated exact quotient or is one unit larger,
/// and an exact quotient stays exact (test
/// `perspective_divide_is_within_one_unit_of_the_exact_quotient`). q ≤ 0
/// is taken as 1. On ARMv6-M, which has no divide instruction, this is a
/// table load, three 32-bit and five 64-bit multiplies (library calls
/// there), where exact division is two 64-bit divisions (each some
/// hundreds of instructions in compiler-builtins).
#[inline]
pub(crate) fn divide(v: &[i32; 3]) -> (i64, i64) {
    // q in [1, 2^31); s in [0, 30].
    let q = v[2].max(1) as u32;
    #[cfg(all(target_arch = "arm", not(target_has_atomic = "ptr")))]
    let (s, mag) = (crate::scalar::normalize_shift(q), mag_halves);
    #[cfg(not(all(target_arch = "arm", not(target_has_atomic = "ptr"))))]
    let (s, mag) = (q.leading_zeros() - 1, mag_wide);
    let r = recip62(q << s);
    let sh = 62 - PERSPECTIVE_Q_BITS - s;
    let one = |x: i32| -> i64 {
        let m = mag(x.unsigned_abs(), r, sh);
        // m < 2^55 (sh ≥ 8), so it fits i64 either way.
        if x < 0 { -(m as i64) } else { m as i64 }
    };
    (one(v[0]), one(v[1]))
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
