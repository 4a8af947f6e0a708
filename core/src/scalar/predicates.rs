//! Exact geometric signs for floats: a fast filter with a proven error
//! bound, and an exact fallback on the dyadic inputs. Fixed point needs
//! neither (its orientation is exact in `i128`, see `fixed_point`).
//!
//! The scheme is Shewchuk's (J. R. Shewchuk, "Adaptive Precision
//! Floating-Point Arithmetic and Fast Robust Geometric Predicates",
//! Discrete & Computational Geometry 18, 1997): evaluate in the input
//! type, accept the sign when it exceeds an a-priori bound on the rounding
//! error, and otherwise compute exactly. The bound below is derived here
//! (it also covers gradual underflow, which Shewchuk's analysis excludes),
//! and the exact stage is a plain big-integer sum instead of his
//! floating-point expansions, since it runs rarely and this form is exact
//! for every finite input, with no overflow or underflow conditions.
//!
//! # The filter and its bound
//!
//! With `u` the unit roundoff (2⁻²⁴ for `f32`, 2⁻⁵³ for `f64`) and `η`
//! half the smallest subnormal (2⁻¹⁵⁰, 2⁻¹⁰⁷⁵), each subtraction has
//! relative error ≤ u (a subnormal difference is exact), and each product
//! relative error ≤ u plus absolute error ≤ η. For
//! `det = (b.x − a.x)(c.y − a.y) − (b.y − a.y)(c.x − a.x)` computed as
//! `t₁ − t₂` this gives `|det~ − det| ≤ γ₃(|t₁| + |t₂|) + u|t~₁ − t~₂| + 2η`
//! (γ₃ = 3u/(1 − 3u)), hence, with `s~ = fl(|t~₁| + |t~₂|)`,
//! `|det~ − det| ≤ 4.01·u·s~ + 3η`. The filter accepts the computed sign when
//! `|det~| > fl(fl(5u·s~) + K)` with `K = 16η`: the rounding of the bound
//! itself costs at most a factor (1 − u)² and one η, so the bound is at
//! least `4.98·u·s~ + 14η`. Any overflow makes `s~` infinite or NaN and
//! the comparison false, so overflow always goes to the exact stage.
//!
//! # The exact stage
//!
//! Every finite `f64` (and so every `f32`) is `±m·2^e` with an integer
//! `m < 2⁵³`. `det` expands to the six products
//! `b.x·c.y − b.x·a.y − a.x·c.y − b.y·c.x + b.y·a.x + a.y·c.x`, each
//! `±(m₁m₂)·2^(e₁+e₂)` with `m₁m₂ < 2¹⁰⁶`. Shifted to the smallest
//! exponent they are integers of at most `1942 + 2148 + 106` bits, summed
//! exactly (positive and negative terms apart) in 64-bit limbs on the
//! stack, and compared. Trailing zero bits of `m` are dropped first, so
//! inputs of similar magnitude use a few limbs; `f32` inputs never need
//! more than 10.

use core::cmp::Ordering;

/// Limbs for any pair of finite `f64` exponent ranges (see the module
/// docs: at most 4196 bits plus two carry bits).
const WIDE: usize = 66;
/// Limbs that suffice whenever the terms span at most 570 bits (every
/// `f32` input: exponents in [−356, 150] plus 106 bits of mantissa).
const NARROW: usize = 10;

/// `x = ±m·2^e` with odd `m` (or `m = 0`); `x` finite.
fn decompose(x: f64) -> (bool, u64, i32) {
    let bits = x.to_bits();
    let neg = bits >> 63 == 1;
    let exp = ((bits >> 52) & 0x7ff) as i32;
    let frac = bits & ((1u64 << 52) - 1);
    let (m, e) = if exp == 0 {
        (frac, -1074)
    } else {
        (frac | (1u64 << 52), exp - 1075)
    };
    if m == 0 {
        return (neg, 0, 0);
    }
    let z = m.trailing_zeros();
    (neg, m >> z, e + z as i32)
}

/// The exact sign of `Σ sᵢ·xᵢ·yᵢ` for finite `f64` pairs, `sᵢ` being
/// `+1` when the flag is false and `−1` when it is true.
pub(crate) fn exact_sign_of_products(terms: &[(f64, f64, bool)]) -> Ordering {
    #[cfg(test)]
    tests::EXACT_CALLS.with(|c| c.set(c.get() + 1));
    // (negative, mantissa product, exponent) per nonzero term.
    let mut t = [(false, 0u128, 0i32); 6];
    let mut k = 0;
    for &(x, y, minus) in terms.iter().take(6) {
        let (nx, mx, ex) = decompose(x);
        let (ny, my, ey) = decompose(y);
        if mx == 0 || my == 0 {
            continue;
        }
        t[k] = (nx ^ ny ^ minus, mx as u128 * my as u128, ex + ey);
        k += 1;
    }
    let t = &t[..k];
    let Some(lo) = t.iter().map(|v| v.2).min() else {
        return Ordering::Equal;
    };
    let hi = t.iter().map(|v| v.2).max().unwrap_or(lo);
    // Bits needed: the largest shift, 106 bits of product, 2 of carry.
    let bits = (hi - lo) as usize + 106 + 2;
    if bits <= NARROW * 64 {
        sum_sign::<NARROW>(t, lo)
    } else {
        sum_sign::<WIDE>(t, lo)
    }
}

/// Sign of the sum of `t` in `L` limbs (enough by the caller's count).
fn sum_sign<const L: usize>(t: &[(bool, u128, i32)], lo: i32) -> Ordering {
    let mut pos = [0u64; L];
    let mut neg = [0u64; L];
    for &(minus, m, e) in t {
        let acc = if minus { &mut neg } else { &mut pos };
        add_shifted(acc, m, (e - lo) as usize);
    }
    for i in (0..L).rev() {
        match pos[i].cmp(&neg[i]) {
            Ordering::Equal => continue,
            o => return o,
        }
    }
    Ordering::Equal
}

/// `acc += m·2^shift`; the caller sized `acc` so that nothing carries out.
fn add_shifted(acc: &mut [u64], m: u128, shift: usize) {
    let (idx, bit) = (shift / 64, (shift % 64) as u32);
    let (v0, v1) = (m as u64, (m >> 64) as u64);
    let parts = if bit == 0 {
        [v0, v1, 0]
    } else {
        [
            v0 << bit,
            (v1 << bit) | (v0 >> (64 - bit)),
            v1 >> (64 - bit),
        ]
    };
    let mut carry = 0u64;
    let mut i = idx;
    for p in parts {
        if i >= acc.len() {
            return;
        }
        let (s1, c1) = acc[i].overflowing_add(p);
        let (s2, c2) = s1.overflowing_add(carry);
        acc[i] = s2;
        carry = (c1 as u64) + (c2 as u64);
        i += 1;
    }
    while carry != 0 && i < acc.len() {
        let (s, c) = acc[i].overflowing_add(carry);
        acc[i] = s;
        carry = c as u64;
        i += 1;
    }
}

/// The exact orientation of finite `f64` points (the exact stage alone).
pub(crate) fn orient2d_exact(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> Ordering {
    exact_sign_of_products(&[
        (b[0], c[1], false),
        (b[0], a[1], true),
        (a[0], c[1], true),
        (b[1], c[0], true),
        (b[1], a[0], false),
        (a[1], c[0], false),
    ])
}

/// The filter in the float type, then the exact stage (see the module
/// docs for the bound); `None` for a non-finite input.
macro_rules! orient2d_float {
    ($name:ident, $t:ty, $u:expr, $k:expr) => {
        pub(crate) fn $name(a: [$t; 2], b: [$t; 2], c: [$t; 2]) -> Option<Ordering> {
            let t1 = (b[0] - a[0]) * (c[1] - a[1]);
            let t2 = (b[1] - a[1]) * (c[0] - a[0]);
            let det = t1 - t2;
            let bound = 5.0 * $u * (t1.abs() + t2.abs()) + $k;
            if det > bound {
                return Some(Ordering::Greater);
            }
            if -det > bound {
                return Some(Ordering::Less);
            }
            if !(a.iter().chain(&b).chain(&c).all(|v| v.is_finite())) {
                return None;
            }
            let w = |p: [$t; 2]| [p[0] as f64, p[1] as f64];
            Some(orient2d_exact(w(a), w(b), w(c)))
        }
    };
}

/// Unit roundoff u of `f32` (2⁻²⁴) and the absolute slack K = 16η = 2⁻¹⁴⁶.
const U32: f32 = f32::EPSILON / 2.0;
const K32: f32 = f32::from_bits(1 << 3);
/// The same for `f64`: 2⁻⁵³ and 2⁻¹⁰⁷¹.
const U64: f64 = f64::EPSILON / 2.0;
const K64: f64 = f64::from_bits(1 << 3);

orient2d_float!(orient2d_f32, f32, U32, K32);
orient2d_float!(orient2d_f64, f64, U64, K64);

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    extern crate std;

    std::thread_local! {
        /// How often the exact stage ran on this thread.
        pub(crate) static EXACT_CALLS: core::cell::Cell<usize> = const { core::cell::Cell::new(0) };
    }

    /// The filter decides almost every orientation of random points (the
    /// hot path), in both float types; only exactly collinear triples and
    /// those within rounding of collinear reach the exact stage.
    #[test]
    fn filter_decides_random_queries() {
        let mut rng = crate::test_util::Rng::new(3);
        let n = 200_000;
        let before = EXACT_CALLS.with(|c| c.get());
        for _ in 0..n {
            let mut r = || rng.range(-10.0, 10.0);
            let (a, b, c) = ([r(), r()], [r(), r()], [r(), r()]);
            let f = |p: [f64; 2]| [p[0] as f32, p[1] as f32];
            let want = orient2d_exact(a, b, c);
            assert_eq!(orient2d_f64(a, b, c), Some(want));
            let _ = orient2d_f32(f(a), f(b), f(c));
        }
        // Each loop calls the exact stage once directly.
        let fallbacks = EXACT_CALLS.with(|c| c.get()) - before - n;
        std::println!("exact stage: {fallbacks} of {} filtered calls", 2 * n);
        assert!(fallbacks * 10_000 <= 2 * n, "{fallbacks} fallbacks");
    }

    #[test]
    fn constants_are_the_documented_powers_of_two() {
        assert_eq!(U32, 2f32.powi(-24));
        assert_eq!(K32 as f64, 2f64.powi(-146));
        assert_eq!(U64, 2f64.powi(-53));
        assert_eq!(K64, 2f64.powi(-1000) * 2f64.powi(-71));
    }

    #[test]
    fn exact_stage_on_extreme_exponents() {
        let tiny = f64::from_bits(1); // 2^-1074
        let big = f64::MAX;
        // Collinear: c = a + 2·(b − a) along a line of slope one.
        assert_eq!(
            orient2d_exact([0.0, 0.0], [1.0, 1.0], [2.0, 2.0]),
            Ordering::Equal
        );
        // A huge edge and a point a subnormal step off it.
        assert_eq!(
            orient2d_exact([0.0, 0.0], [big, 0.0], [1.0, tiny]),
            Ordering::Greater
        );
        assert_eq!(
            orient2d_exact([0.0, 0.0], [big, 0.0], [1.0, -tiny]),
            Ordering::Less
        );
        // The filter overflows here (big·big); the exact stage decides.
        assert_eq!(
            orient2d_f64([-big, -big], [big, big], [big, big - 1e292]),
            Some(Ordering::Less)
        );
        assert_eq!(orient2d_f64([0.0, f64::NAN], [1.0, 0.0], [0.0, 1.0]), None);
        // One ulp off the line y = x at 1: 1·(1 + 2^-52) − (1)·1 > 0.
        let e = 1.0 + f64::EPSILON;
        assert_eq!(
            orient2d_f64([0.0, 0.0], [1.0, 1.0], [1.0, e]),
            Some(Ordering::Greater)
        );
        assert_eq!(
            orient2d_f32([0.0, 0.0], [1.0, 1.0], [1.0, 1.0 + f32::EPSILON]),
            Some(Ordering::Greater)
        );
    }

    #[test]
    fn exact_stage_against_i128_on_random_dyadics() {
        let mut rng = crate::test_util::Rng::new(99);
        for _ in 0..20_000 {
            // Integers below 2^40 times a shared power of two: exact in i128.
            let s = rng.int(-60, 60) as i32;
            let mut v = [0i64; 6];
            for x in &mut v {
                *x = rng.int(-(1 << 40), 1 << 40);
            }
            // Make some cases collinear or nearly so.
            if rng.int(0, 2) == 0 {
                v[4] = v[0] + 2 * (v[2] - v[0]);
                v[5] = v[1] + 2 * (v[3] - v[1]) + rng.int(-1, 1);
            }
            let f = |x: i64| x as f64 * 2f64.powi(s);
            let (a, b, c) = ([f(v[0]), f(v[1])], [f(v[2]), f(v[3])], [f(v[4]), f(v[5])]);
            let w = |x: i64| x as i128;
            let want = ((w(v[2]) - w(v[0])) * (w(v[5]) - w(v[1]))
                - (w(v[3]) - w(v[1])) * (w(v[4]) - w(v[0])))
            .cmp(&0);
            assert_eq!(orient2d_exact(a, b, c), want, "{v:?} 2^{s}");
            assert_eq!(orient2d_f64(a, b, c), Some(want), "{v:?} 2^{s}");
        }
    }
}
