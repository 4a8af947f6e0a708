//! 64-bit division for the rare paths: the set-up of triangles beyond the
//! 32-bit bound and of clipped polygons, the clipper's intersection ratio,
//! fixed-point `/` and the scene's normals.
//!
//! ARMv6-M (Cortex-M0/M0+) has no divide instruction, and a 64-bit `/`
//! there links compiler-builtins' `u64_div_rem` with the 32-bit routine
//! and the `__divmoddi4`/`__udivmoddi4` wrappers it comes with, about
//! 1.4 KB of .text, for code that a W1/W2 frame calls a few times. On that
//! target every such division goes through `div_rem_u64_small` and
//! `word_steps` instead, 386 bytes together; elsewhere it is the
//! hardware's or the library's `/`. Both give the exact quotient and
//! remainder (`div_rem_u64_matches_division`).
//!
//! Measured with `bash tests/mcu/run` (thumbv6m, I16F16): the flat cube
//! firmware 23 176 -> 22 172 bytes of .text, the Gouraud bunny 30 384 ->
//! 29 488, everything 96 228 -> 94 256; W1 and W2 +0.01 % and +0.03 %
//! instructions per frame; the sphere ray-casting frame, where `/` is on
//! every ray, +7.7 % (4.14 G -> 4.46 G).

/// `(n / d, n % d)`, with `d = 0` taken as 1 (callers never divide by
/// zero; a broken contract gives a defined value, not a panic).
#[inline]
pub(crate) fn div_rem_u64(n: u64, d: u64) -> (u64, u64) {
    #[cfg(all(target_arch = "arm", not(target_has_atomic = "ptr")))]
    {
        div_rem_u64_small(n, d)
    }
    #[cfg(not(all(target_arch = "arm", not(target_has_atomic = "ptr"))))]
    {
        let d = core::num::NonZeroU64::new(d).unwrap_or(core::num::NonZeroU64::MIN);
        (n / d, n % d)
    }
}

/// `(n / d, n % d)` truncated towards zero, as `/` and `%` on `i64`, with
/// `d = 0` taken as 1; the quotient wraps for `i64::MIN / −1` (where `/`
/// would panic).
#[inline]
pub(crate) fn div_rem_i64(n: i64, d: i64) -> (i64, i64) {
    let (q, r) = div_rem_u64(n.unsigned_abs(), d.unsigned_abs());
    let q = if (n < 0) != (d < 0) {
        (q as i64).wrapping_neg()
    } else {
        q as i64
    };
    let r = if n < 0 {
        (r as i64).wrapping_neg()
    } else {
        r as i64
    };
    (q, r)
}

/// `div_rem_u64` without a divide instruction. A divisor below 2^31
/// (every caller's usual case) takes restoring division on a 32-bit
/// remainder, one dividend word at a time (`word_steps`): at most 32
/// steps when the quotient fits 32 bits, 64 otherwise. A larger divisor
/// leaves a quotient below 2^33: the divisor is doubled up to the dividend, then
/// halved back, one quotient bit a step. Out of line: one copy for every
/// caller. (The bit-at-a-time loop for every divisor cost the sphere
/// ray-casting frame 38 % more instructions than the library division.)
#[cfg(any(test, all(target_arch = "arm", not(target_has_atomic = "ptr"))))]
#[inline(never)]
fn div_rem_u64_small(mut n: u64, d: u64) -> (u64, u64) {
    let d = d.max(1);
    if d < 1 << 31 {
        let d = d as u32;
        let (hi, lo) = ((n >> 32) as u32, n as u32);
        let (q_hi, r) = if hi < d {
            (0, hi)
        } else {
            word_steps(0, hi, d)
        };
        let (q_lo, r) = word_steps(r, lo, d);
        return ((u64::from(q_hi) << 32) | u64::from(q_lo), u64::from(r));
    }
    if n < d {
        return (0, n);
    }
    // The 64-bit twin of the edge set-up's `udiv_small` (raster::edge). One
    // generic loop for both changed the 32-bit instance's code: W1 on
    // ARMv6-M +0.6 % and the flat firmware +176 bytes, so each width keeps
    // its own.
    let (mut s, mut bit) = (d, 1u64);
    // `s ≤ n/2` keeps `2s ≤ n`: no overflow.
    while s <= n >> 1 {
        s <<= 1;
        bit <<= 1;
    }
    let mut q = 0;
    loop {
        if n >= s {
            n -= s;
            q |= bit;
        }
        if bit == 1 {
            return (q, n);
        }
        s >>= 1;
        bit >>= 1;
    }
}

/// `(hi·2^32 + lo) / d` and its remainder, for `hi < d < 2^31`: steps of
/// restoring division on the pair `(hi, lo)` shifted left one bit a step,
/// where the remainder stays in `hi` (below `2d < 2^32`) and each quotient
/// bit enters `lo` at the bit its shift vacated: after 32 steps `lo` is the
/// quotient (32 bits, because `hi < d`) and `hi` the remainder.
///
/// Leading steps whose quotient bits are certainly 0 go a byte at a time:
/// when `hi·2^8 + ⌊lo/2^24⌋ < d`, so is every value between. So a quotient
/// of k bits costs about k steps, not 32. (The sphere ray-casting frame on
/// ARMv6-M, whose quotients are mostly 16.16 values of a few units: 5.22 G
/// instructions with 32 steps every call, 4.46 G with the byte skip, 4.14 G
/// with compiler-builtins' division.)
#[cfg(any(test, all(target_arch = "arm", not(target_has_atomic = "ptr"))))]
#[inline(never)]
fn word_steps(mut hi: u32, mut lo: u32, d: u32) -> (u32, u32) {
    let mut steps = 32;
    while steps > 0 && hi >> 24 == 0 && ((hi << 8) | (lo >> 24)) < d {
        hi = (hi << 8) | (lo >> 24);
        lo <<= 8;
        steps -= 8;
    }
    for _ in 0..steps {
        let top = lo >> 31;
        lo <<= 1;
        hi = (hi << 1) | top;
        if hi >= d {
            hi -= d;
            lo |= 1;
        }
    }
    (lo, hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The shift-and-subtract division (ARMv6-M's route) and the signed
    /// wrapper against the hardware's quotient and remainder.
    #[test]
    fn div_rem_u64_matches_division() {
        let edge = [
            0u64,
            1,
            2,
            3,
            15,
            16,
            17,
            (1 << 31) - 1,
            1 << 31,
            (1 << 32) - 1,
            1 << 32,
            (1 << 32) + 1,
            (1 << 47) + 12345,
            (1 << 62) - 1,
            1 << 62,
            (1 << 63) - 1,
            1 << 63,
            u64::MAX - 1,
            u64::MAX,
        ];
        let check = |n: u64, d: u64| {
            let want = (n / d.max(1), n % d.max(1));
            assert_eq!(div_rem_u64_small(n, d), want, "n = {n}, d = {d}");
            assert_eq!(div_rem_u64(n, d), want, "n = {n}, d = {d}");
            let (ni, di) = (n as i64, d as i64);
            if di != 0 && !(ni == i64::MIN && di == -1) {
                assert_eq!(
                    div_rem_i64(ni, di),
                    (ni / di, ni % di),
                    "n = {ni}, d = {di}"
                );
            }
        };
        for &n in &edge {
            for &d in &edge {
                check(n, d);
            }
        }
        // A deterministic sweep (xorshift) over sizes of both operands.
        let mut x = 0x9e37_79b9_7f4a_7c15_u64;
        for _ in 0..200_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let n = x >> (x % 64);
            let d = x.rotate_left(23) >> ((x >> 6) % 64);
            check(n, d);
        }
        // A zero divisor is taken as 1 on both routes.
        assert_eq!(div_rem_u64(7, 0), (7, 0));
        assert_eq!(div_rem_i64(-7, 0), (-7, 0));
    }
}
