//! `2^62 / d` without a division instruction: the ceiling for the
//! fixed-point divisions that share a divisor (`Scalar::checked_quotients`),
//! and estimates at most a few units off for callers that correct their
//! quotients (the 16.16 perspective projection, the raster's gradient
//! set-up and perspective divide). ARMv6-M (Cortex-M0) has no divide
//! instruction, and a 64-bit division in compiler-builtins costs hundreds
//! of instructions there.

/// Seeds for [`recip62`]: `⌊2^24 / (257 + i)⌋`, the reciprocal of the
/// top of the interval `[256 + i, 257 + i)·2^22` that a normalized
/// divisor with those leading bits lies in, shifted to 16 bits. Never
/// above the true reciprocal, within 1/256 of it.
const RECIP_SEED: [u16; 256] = {
    let mut t = [0u16; 256];
    let mut i = 0;
    while i < 256 {
        t[i] = ((1u32 << 24) / (257 + i as u32)) as u16;
        i += 1;
    }
    t
};

/// `⌈2^62 / d⌉` for `d` in `[2^30, 2^31)` (so the result is in
/// `(2^31, 2^32]`), without a division: a table seed good to 8 bits, two
/// Newton steps `x ← x + x·(2^62 − d·x)/2^62` (each doubles the correct
/// bits and, truncating, stays at or below the true reciprocal), then
/// unit steps up to the ceiling. Exact for every `d`: checked for all
/// 2^30 divisors by the release-mode test `recip62_exhaustive`, which
/// `.ci/run` runs (`cargo test --release -p sightline --features full
/// --lib recip62_exhaustive -- --ignored`), and on a sample by
/// `recip62_is_the_exact_ceiling` in every test run. At most 3 unit steps
/// were needed (an instrumented copy on the host); the code takes 4. Any
/// other `d` is clamped into the range first.
#[inline]
pub(crate) fn recip62(d: u32) -> u64 {
    let d = d.clamp(1 << 30, (1 << 31) - 1);
    let mut x = first_step(d);
    // Second step in 64-bit arithmetic: x ≤ 2^62/d, so d·x ≤ 2^62 and
    // e ≥ 0; x is within 2^−14 of the reciprocal, so e >> 22 < 2^32 and
    // the product fits u64. A Newton step from below stays at or below
    // the reciprocal (x·(2 − d·x/2^62) ≤ 2^62/d), and truncation only
    // lowers it. (Written as in `recip62_floor`, this copy, out of line
    // in what was then the perspective-texture span loop, cost about 30
    // instructions more per call on ARMv6-M.)
    let two62 = 1u64 << 62;
    let e = two62 - mul_u32_u64(d, x);
    x += mul_u32_u64((e >> 22) as u32, x) >> 40;
    // Now 2^62/d − x is a few units at most: step up to the ceiling,
    // branch-free (LLVM turns an early-exit loop into a 64-bit division).
    let mut p = mul_u32_u64(d, x);
    for _ in 0..4 {
        let below = (p < two62) as u64;
        p += d as u64 & below.wrapping_neg();
        x += below;
    }
    x
}

/// [`recip62`] before its unit steps: at or below `2^62 / d` and at most
/// 3 units below its floor, for `d` in `[2^30, 2^31)` (other `d` are
/// clamped into the range; both bounds are checked for every `d` by
/// `recip62_exhaustive`). For callers that check their quotients against
/// the divisor anyway (`perspective16`, the raster's gradient set-up):
/// they take the last units there.
#[inline]
pub(crate) fn recip62_floor(d: u32) -> u64 {
    let d = d.clamp(1 << 30, (1 << 31) - 1);
    let x = first_step(d);
    // The second step as in `recip62`, with e >> 22 formed from the
    // product's halves: inlined into the perspective projection, the
    // 64-bit subtraction became a multiply by a 54-bit constant
    // (`__aeabi_lmul`, about 40 instructions on ARMv6-M).
    let p = mul_u32_u64(d, x);
    let (lo, hi) = (p as u32, (p >> 32) as u32);
    let (e_lo, borrow) = 0u32.overflowing_sub(lo);
    let e_hi = (1u32 << 30).wrapping_sub(hi).wrapping_sub(borrow as u32);
    let e22 = (e_hi << 10) | (e_lo >> 22);
    x + (mul_u32_u64(e22, x) >> 40)
}

/// A reciprocal at or above `R = 2^62 / d` and at most 4 above it, at
/// most 2^32, for `d` in `[2^30, 2^31)` (others are clamped): what a
/// caller needs whose estimate `⌊u·r / 2^k⌋` must never fall below the
/// quotient and exceed it by less than one while `4u/2^k < 1`, so that one
/// 32-bit check of the remainder's sign corrects it (the raster's
/// perspective divide). [`recip62_floor`] is at or below `R`
/// and less than 4 below it, so adding 4 gives `R < r ≤ R + 4`; the cap
/// at 2^32 takes effect only at `d = 2^30`, where `R = 2^32` exactly and
/// `r = R`.
#[cfg(any(test, feature = "perspective"))]
#[inline]
pub(crate) fn recip62_above(d: u32) -> u64 {
    (recip62_floor(d) + 4).min(1 << 32)
}

/// `2^46 / d` from below to within 2^−13 of it, for `d` in
/// `[2^30, 2^31)` (others are clamped): `r·d ≤ 2^46` and
/// `2^46 − r·d ≤ 2^33`, so `r` is in `[2^15, 2^16)`. The top half of
/// [`recip62`]'s seed and first Newton step, with neither its 64-bit
/// second step nor its unit steps: for the perspective texel divide
/// (`raster::persp_div::texels`), which corrects its estimate by exact
/// 32-bit remainders. Both bounds are checked for every `d` by
/// `recip62_exhaustive`.
#[cfg(any(test, feature = "perspective"))]
#[inline]
pub(crate) fn recip46_below(d: u32) -> u32 {
    let d = d.clamp(1 << 30, (1 << 31) - 1);
    (first_step(d) >> 16) as u32
}

/// The seed and first Newton step of [`recip62`] for `d` in
/// `[2^30, 2^31)`: at or below `2^62 / d`, within 2^−14 of it.
#[inline(always)]
fn first_step(d: u32) -> u64 {
    let s0 = RECIP_SEED[((d >> 22) & 0xff) as usize] as u32;
    // In 32-bit arithmetic (ARMv6-M has only a 32×32→32 multiply):
    // p = d·s0/2^15 from d's two 15/16-bit halves (the seed is below
    // 2^24/(d >> 22), so d·s0 < 2^46 and p < 2^31), e its shortfall from
    // 2^31 (below 2^31/128), then x = s0·2^16·(1 + e/2^31). The products
    // fit u32. Rounding can leave x a few units above the reciprocal,
    // which is why it steps back 8 units (2^−29 of it).
    let p = (d >> 15) * s0 + (((d & 0x7fff) * s0) >> 15);
    let e = (1u32 << 31).saturating_sub(p);
    ((s0 as u64) << 16) + ((s0 * (e >> 8)) >> 7) as u64 - 8
}

/// `a·b` for a product known to fit `u64` (here `b` < 2^33), as one
/// 32×32→64 multiply of `b`'s low half and a 32-bit multiply of its high
/// half: four 16×16 multiplies and no `__aeabi_lmul` call on ARMv6-M (a
/// full 64×64 multiply was three calls per reciprocal). Exact modulo 2^64,
/// hence exact when the product fits.
#[inline(always)]
fn mul_u32_u64(a: u32, b: u64) -> u64 {
    let (lo, hi) = (b as u32, (b >> 32) as u32);
    super::fixed_point::widening_mul_u32(a, lo).wrapping_add((a.wrapping_mul(hi) as u64) << 32)
}
