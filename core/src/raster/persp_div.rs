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
    let s = crate::scalar::normalize_shift(q);
    let r = recip62(q << s);
    let sh = 62 - PERSPECTIVE_Q_BITS - s;
    let one = |x: i32| -> i64 {
        // |x| ≤ 2^31 and r ≤ 2^32: the product is below 2^63 (u64). As a
        // 32×32→64 multiply (r = 2^32 exactly is a shift) and a shift of
        // 32-bit halves: on ARMv6-M a u64 product and a variable u64
        // shift are library calls (`__aeabi_lmul`, `__aeabi_llsr`).
        let a = x.unsigned_abs();
        let p = if r >> 32 != 0 {
            (a as u64) << 32
        } else {
            crate::scalar::widening_mul_u32(a, r as u32)
        };
        let m = crate::scalar::shr_u64(p, sh);
        // m < 2^55 (sh ≥ 8), so it fits i64 either way.
        if x < 0 { -(m as i64) } else { m as i64 }
    };
    (one(v[0]), one(v[1]))
}
