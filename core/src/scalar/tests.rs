//! The scalar suite, written once and instantiated per representation with
//! tolerances in units of each type's `EPSILON`.

use super::*;
use crate::test_util::Rng;
use std::vec;
use std::vec::Vec;

/// One step of the representation near `x` (an ulp for floats, EPSILON for
/// fixed point), in f64.
fn ulp_at<T: Scalar>(x: f64) -> f64 {
    if T::IS_FLOAT {
        T::EPSILON.to_f64() * x.abs().max(f64::MIN_POSITIVE)
    } else {
        T::EPSILON.to_f64()
    }
}

fn arithmetic_is_exact_on_representable_values<T: Scalar>() {
    let v = |x: f64| T::from_f64(x);
    assert_eq!(v(1.5) + v(2.25), v(3.75));
    assert_eq!(v(1.5) - v(2.25), v(-0.75));
    assert_eq!(v(1.5) * v(-2.25), v(-3.375));
    assert_eq!(v(-3.375) / v(1.5), v(-2.25));
    assert_eq!(T::ONE + T::ONE, T::TWO);
    assert_eq!(T::TWO * T::HALF, T::ONE);
    assert_eq!(T::from_i32(-7).to_f64(), -7.0);
    assert!((T::PI.to_f64() - core::f64::consts::PI).abs() <= ulp_at::<T>(3.2));
}

fn sin_cos_match_f64<T: Scalar>(max_ulps: f64) {
    let mut rng = Rng::new(1);
    let mut worst: f64 = 0.0;
    for i in 0..20_000 {
        // Dense near the octant boundaries, uniform elsewhere.
        let a = if i < 64 {
            (i as f64 - 32.0) * core::f64::consts::FRAC_PI_4
        } else {
            rng.range(-40.0, 40.0)
        };
        let t = T::from_f64(a);
        // Compare against the angle the representation actually holds.
        let exact = t.to_f64();
        let (s, c) = t.sin_cos();
        assert_eq!(s, t.sin());
        assert_eq!(c, t.cos());
        let es = (s.to_f64() - exact.sin()).abs() / ulp_at::<T>(exact.sin().abs().max(1e-3));
        let ec = (c.to_f64() - exact.cos()).abs() / ulp_at::<T>(exact.cos().abs().max(1e-3));
        worst = worst.max(es).max(ec);
    }
    assert!(
        worst <= max_ulps,
        "{}: sin/cos error {worst} steps",
        T::NAME
    );
}

fn atan2_asin_match_f64<T: Scalar>(max_ulps: f64) {
    let mut rng = Rng::new(2);
    let mut worst: f64 = 0.0;
    for _ in 0..20_000 {
        let y = T::from_f64(rng.range(-100.0, 100.0));
        let x = T::from_f64(rng.range(-100.0, 100.0));
        let exact = y.to_f64().atan2(x.to_f64());
        let e = (y.atan2(x).to_f64() - exact).abs();
        worst = worst.max(e / ulp_at::<T>(exact.abs().max(1e-3)));
        let s = T::from_f64(rng.range(-1.0, 1.0));
        let exact = s.to_f64().asin();
        let e = (s.asin().to_f64() - exact).abs();
        // Fixed point computes asin through sqrt(1 − s²), whose rounding is
        // amplified by asin's slope 1/√(1 − s²) near ±1.
        let slope = if T::IS_FLOAT {
            1.0
        } else {
            1.0 / (1.0 - s.to_f64() * s.to_f64()).max(1e-12).sqrt()
        };
        worst = worst.max(e / (ulp_at::<T>(exact.abs().max(1e-3)) * slope));
    }
    assert!(
        worst <= max_ulps,
        "{}: atan2/asin error {worst} steps",
        T::NAME
    );
    assert_eq!(T::ZERO.atan2(T::ZERO), T::ZERO);
    let pi = T::ZERO.atan2(-T::ONE).to_f64();
    assert!((pi - core::f64::consts::PI).abs() <= max_ulps * ulp_at::<T>(3.2));
}

fn sqrt_is_correctly_rounded<T: Scalar>() {
    let mut rng = Rng::new(3);
    for _ in 0..20_000 {
        let x = T::from_f64(rng.range(0.0, 30_000.0) * rng.unit().powi(4));
        let r = x.sqrt().to_f64();
        let exact = x.to_f64().sqrt();
        // Within half a step of the exact root (plus f64 noise).
        assert!(
            (r - exact).abs() <= 0.5 * ulp_at::<T>(exact) * (1.0 + 1e-9) + 1e-300,
            "{}: sqrt({x:?}) = {r}, exact {exact}",
            T::NAME
        );
    }
    assert_eq!(T::ZERO.sqrt(), T::ZERO);
}

fn checked_ops_report_overflow<T: Scalar>() {
    assert_eq!(T::MAX.checked_add(T::MAX), None);
    assert_eq!(T::MIN.checked_sub(T::MAX), None);
    assert_eq!(T::MAX.checked_mul(T::TWO), None);
    assert_eq!(T::ONE.checked_div(T::ZERO), None);
    assert_eq!(T::ONE.checked_add(T::ONE), Some(T::TWO));
    assert_eq!(T::ONE.checked_div(T::TWO), Some(T::HALF));
    assert_eq!(T::from_f64(f64::NAN), T::ZERO);
    assert_eq!(T::try_from_f64(f64::NAN), None);
    assert_eq!(T::try_from_f64(f64::INFINITY), None);
    // A value beyond the range (for f64 only ∞ is).
    let big = if T::MAX.to_f64() < 1e300 {
        1e300
    } else {
        f64::INFINITY
    };
    assert_eq!(T::try_from_f64(big), None);
    assert_eq!(T::from_f64(big), T::MAX);
    assert_eq!(T::from_f64(-big), T::MIN);
    let mut flag = false;
    let _ = T::ONE.sub_mul_noting_overflow(T::ONE, T::ONE, &mut flag);
    assert!(!flag);
}

/// The float path against `round` (half away from zero) and the range
/// rule, on ties, near-ties and both ends of the i32 range.
#[test]
fn float_to_subpixel_matches_libm_round() {
    let want64 = |x: f64, bits: u32| {
        let v = libm::round(x * (1u32 << bits) as f64);
        (-2_147_483_648.0..2_147_483_648.0)
            .contains(&v)
            .then_some(v as i32)
    };
    let want32 = |x: f32, bits: u32| {
        let v = libm::roundf(x * (1u32 << bits) as f32);
        (-2_147_483_648.0..2_147_483_648.0)
            .contains(&v)
            .then_some(v as i32)
    };
    let mut xs: std::vec::Vec<f64> = std::vec![
        0.0,
        -0.0,
        0.5,
        -0.5,
        1.5,
        -2.5,
        0.49999999999999994,
        -0.49999999999999994,
        2147483647.0,
        2147483647.4,
        2147483647.5,
        2147483647.6,
        2147483648.0,
        -2147483648.0,
        -2147483648.4,
        -2147483648.5,
        -2147483648.6,
        -2147483649.0,
        1e300,
        -1e300,
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        4503599627370497.0,
    ];
    let mut rng = crate::test_util::Rng::new(0x5b);
    for _ in 0..20000 {
        let e = rng.range(-12.0, 33.0);
        let x = rng.range(-1.0, 1.0) * libm::exp2(e);
        xs.push(x);
        xs.push((x * 2.0).round() / 2.0); // ties
        xs.push(libm::nextafter((x * 2.0).round() / 2.0, 0.0)); // near ties
    }
    for &x in &xs {
        for bits in [0, 4, 16, 24] {
            assert_eq!(
                x.to_subpixel(bits),
                want64(x, bits),
                "f64 {x:e} bits {bits}"
            );
            let y = x as f32;
            assert_eq!(
                y.to_subpixel(bits),
                want32(y, bits),
                "f32 {y:e} bits {bits}"
            );
            let z = libm::nextafterf(y, 0.0);
            assert_eq!(
                z.to_subpixel(bits),
                want32(z, bits),
                "f32 {z:e} bits {bits}"
            );
        }
    }
}

fn to_subpixel_rounds_to_nearest<T: Scalar>() {
    let v = |x: f64| T::from_f64(x);
    assert_eq!(v(1.5).to_subpixel(4), Some(24));
    assert_eq!(v(-1.5).to_subpixel(4), Some(-24));
    assert_eq!(v(10.03125).to_subpixel(4), Some(161)); // 160.5 rounds away
    assert_eq!(v(-10.03125).to_subpixel(4), Some(-161));
    assert_eq!(v(0.0).to_subpixel(4), Some(0));
}

macro_rules! scalar_suite {
    ($name:ident, $t:ty, trig_ulps = $trig:expr, atan_ulps = $atan:expr) => {
        mod $name {
            use super::*;
            #[test]
            fn arithmetic() {
                arithmetic_is_exact_on_representable_values::<$t>();
            }
            #[test]
            fn sin_cos() {
                sin_cos_match_f64::<$t>($trig);
            }
            #[test]
            fn atan2_asin() {
                atan2_asin_match_f64::<$t>($atan);
            }
            #[test]
            fn sqrt() {
                sqrt_is_correctly_rounded::<$t>();
            }
            #[test]
            fn checked() {
                checked_ops_report_overflow::<$t>();
            }
            #[test]
            fn subpixel() {
                to_subpixel_rounds_to_nearest::<$t>();
            }
        }
    };
}

// Float trig is libm (≤ 1 ulp of the result, which is ≤ EPSILON near 1).
// Fixed-point trig is the Q2.30 polynomial: its error is the final rounding
// to the format (½ step) plus the polynomial's (< 2·10⁻⁸, far below a
// step), so one step bounds it.
scalar_suite!(f64_suite, f64, trig_ulps = 1.0, atan_ulps = 2.0);
scalar_suite!(f32_suite, f32, trig_ulps = 1.0, atan_ulps = 2.0);
scalar_suite!(i16f16_suite, I16F16, trig_ulps = 1.0, atan_ulps = 1.0);
scalar_suite!(i20f12_suite, I20F12, trig_ulps = 1.0, atan_ulps = 1.0);

#[test]
fn fixed_operators_saturate_instead_of_wrapping() {
    type T = I16F16;
    assert_eq!(T::MAX + T::ONE, T::MAX);
    assert_eq!(T::MIN - T::ONE, T::MIN);
    assert_eq!(T::MAX * T::TWO, T::MAX);
    assert_eq!(T::MAX * -T::TWO, T::MIN);
    assert_eq!(-T::MIN, T::MAX);
    assert_eq!(T::MIN.abs(), T::MAX);
    assert_eq!(T::ONE / T::ZERO, T::MAX);
    assert_eq!(-T::ONE / T::ZERO, T::MIN);
    assert_eq!(T::ZERO / T::ZERO, T::ZERO);
    assert_eq!(T::from_i32(40_000), T::MAX);
    assert_eq!((-T::ONE).sqrt(), T::ZERO);
    let mut flag = false;
    assert_eq!(
        T::from_i32(300).sub_mul_noting_overflow(T::from_i32(300), T::from_i32(300), &mut flag),
        T::MIN
    );
    assert!(flag);
}

#[test]
fn fixed_mul_div_round_to_nearest() {
    type T = I16F16;
    // 3 steps × 0.5 = 1.5 steps → 2 (ties toward +∞).
    assert_eq!((T::from_bits(3) * T::HALF).to_bits(), 2);
    assert_eq!((T::from_bits(-3) * T::HALF).to_bits(), -1);
    // 1/3 = 21845.33 steps → 21845; 2/3 = 43690.67 → 43691.
    assert_eq!((T::ONE / T::from_i32(3)).to_bits(), 21_845);
    assert_eq!((T::TWO / T::from_i32(3)).to_bits(), 43_691);
    assert_eq!((-T::TWO / T::from_i32(3)).to_bits(), -43_691);
}

#[test]
fn fixed_interop_with_the_fixed_crate() {
    let f = fixed::types::I16F16::from_num(2.5);
    let x = I16F16::from_fixed(f);
    assert_eq!(x.to_f64(), 2.5);
    assert_eq!(x.to_fixed(), f);
}

#[test]
fn split_widening_mul_is_exact() {
    use super::fixed_point::split_widening_mul;
    let edges = [
        0,
        1,
        -1,
        2,
        0xffff,
        0x1_0000,
        -0x1_0000,
        0x7fff,
        -0x8000,
        0x8000,
        i32::MAX,
        i32::MIN,
        i32::MAX - 1,
        i32::MIN + 1,
        0x1234_5678,
        -0x1234_5678,
    ];
    for &a in &edges {
        for &b in &edges {
            assert_eq!(split_widening_mul(a, b), a as i64 * b as i64, "{a}·{b}");
        }
    }
    // A fixed pseudo-random sweep (xorshift), 2^20 pairs.
    let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
    for _ in 0..1 << 20 {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        let (a, b) = (x as i32, (x >> 32) as i32);
        assert_eq!(split_widening_mul(a, b), a as i64 * b as i64, "{a}·{b}");
    }
}

/// `Fx::from_f32` (integer decoding of the bits) equals
/// `from_f64(x as f64)` (the float path it replaces on FPU-less cores)
/// for every fraction width: special values, the rounding and saturation
/// boundaries, and one f32 bit pattern in every 4099.
#[test]
fn from_f32_equals_from_f64_of_the_widened_value() {
    use super::fixed_point::f32_to_fixed_bits;
    fn check<F: Scalar>(x: f32) {
        assert_eq!(
            F::from_f32(x),
            F::from_f64(x as f64),
            "{} from_f32({x:e}) (bits {:#010x})",
            F::NAME,
            x.to_bits()
        );
    }
    fn all(x: f32) {
        check::<super::I16F16>(x);
        check::<super::I24F8>(x);
        check::<super::I2F30>(x);
    }
    let mut specials = std::vec![
        0.0f32,
        -0.0,
        f32::NAN,
        -f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::MIN_POSITIVE,
        -f32::MIN_POSITIVE,
        f32::from_bits(1),
        f32::from_bits(0x8000_0001),
        f32::MAX,
        f32::MIN,
    ];
    // Around every half-integer step and the saturation limits of each
    // width: the neighbours of ±(j + ½)·2^-frac and ±2^(31 − frac).
    for frac in [8, 16, 30] {
        let unit = (2.0f64).powi(-frac);
        for j in [
            0.5,
            1.5,
            2.5,
            1000.5,
            65535.5,
            2147483647.0,
            2147483647.5,
            2147483648.0,
        ] {
            for sign in [1.0, -1.0] {
                let v = (sign * j * unit) as f32;
                specials.extend([
                    v,
                    f32::from_bits(v.to_bits() + 1),
                    f32::from_bits(v.to_bits().wrapping_sub(1)),
                ]);
            }
        }
    }
    for &x in &specials {
        all(x);
    }
    let mut b = 0u32;
    while let Some(next) = b.checked_add(4099) {
        all(f32::from_bits(b));
        b = next;
    }
    // The helper saturates and rounds like `as` after adding ½.
    assert_eq!(f32_to_fixed_bits(0.5 / 65536.0, 16), 1);
    assert_eq!(f32_to_fixed_bits(-0.5 / 65536.0, 16), -1);
    assert_eq!(f32_to_fixed_bits(32768.0, 16), i32::MAX);
    assert_eq!(f32_to_fixed_bits(-32768.0, 16), i32::MIN);
}

/// Every one of the 2^32 f32 bit patterns, for I16F16 (about a minute in
/// release): `cargo test --release -p sightline --lib
/// from_f32_exhaustive -- --ignored`.
#[test]
#[ignore = "exhaustive: 2^32 values; run with --ignored in release"]
fn from_f32_exhaustive() {
    for b in 0..=u32::MAX {
        let x = f32::from_bits(b);
        assert_eq!(
            super::I16F16::from_f32(x),
            super::I16F16::from_f64(x as f64),
            "bits {b:#010x}"
        );
    }
}

/// Every one of the 2^30 divisors (about 25 s in the optimized test
/// profile, far longer without optimization, hence opt-in; CI runs it):
/// `cargo test --workspace --lib recip62_exhaustive -- --ignored`.
/// The sampled test above runs by default.
#[test]
#[ignore = "2^30 divisors: about 25 s in the test profile; CI runs it with --ignored"]
fn recip62_exhaustive() {
    use super::{recip46_below, recip62, recip62_above, recip62_floor};
    for d in (1u32 << 30)..(1u32 << 31) {
        let exact = (1u128 << 62).div_ceil(d as u128) as u64;
        assert_eq!(recip62(d), exact, "d = {d}");
        let floor = ((1u128 << 62) / d as u128) as u64;
        let x = recip62_floor(d);
        // perspective16's exactness rests on this bound.
        assert!(x <= floor && floor - x < 4, "d = {d}: {x} against {floor}");
        // The raster's one-step corrections rest on R ≤ r ≤ R + 4.
        assert!(recip62_above_holds(d, recip62_above(d)), "d = {d}");
        // The perspective texel divide's estimate rests on this bound.
        assert!(recip46_holds(d, recip46_below(d)), "d = {d}");
    }
}

/// `r·d ≤ 2^46` and `2^46 − r·d ≤ 2^33` (r within 2^−13 below `2^46/d`),
/// in exact integers.
fn recip46_holds(d: u32, r: u32) -> bool {
    let p = d as u64 * r as u64;
    p <= 1 << 46 && (1u64 << 46) - p <= 1 << 33
}

/// Normalized divisors for the sampled reciprocal tests: both ends, every
/// seed interval's ends and a stride through the rest (all 2^30 divisors:
/// `recip62_exhaustive`).
fn sample_divisors() -> Vec<u32> {
    let mut ds: Vec<u32> = vec![1 << 30, (1 << 31) - 1];
    for i in 0..256u32 {
        let b = (256 + i) << 22;
        ds.extend([b.wrapping_sub(1), b, b + 1]);
    }
    ds.extend((0..200_000u32).map(|k| (1 << 30) + k.wrapping_mul(5_368_709) % (1 << 30)));
    ds.retain(|d| (1 << 30..1 << 31).contains(d));
    ds
}

#[test]
fn recip46_is_below_within_2_13() {
    use super::recip46_below;
    for d in sample_divisors() {
        assert!(recip46_holds(d, recip46_below(d)), "d = {d}");
    }
}

/// `R ≤ r ≤ R + 4` for `R = 2^62/d`, and `r ≤ 2^32`, in exact integers.
fn recip62_above_holds(d: u32, r: u64) -> bool {
    let (d, r) = (d as u128, r as u128);
    r * d >= 1 << 62 && (r - 4) * d <= 1 << 62 && r <= 1 << 32
}

#[test]
fn recip62_above_is_above_by_at_most_four() {
    use super::recip62_above;
    for d in sample_divisors() {
        assert!(recip62_above_holds(d, recip62_above(d)), "d = {d}");
    }
}

#[test]
fn recip62_is_the_exact_ceiling() {
    use super::recip62;
    let exact = |d: u32| (1u128 << 62).div_ceil(d as u128) as u64;
    // Both ends, every seed interval's ends and a stride through the rest.
    let mut ds: Vec<u32> = vec![1 << 30, (1 << 31) - 1];
    for i in 0..=256u32 {
        let b = (256 + i) << 22;
        ds.extend([b.wrapping_sub(1), b, b + 1]);
    }
    ds.extend((0..200_000u32).map(|k| (1 << 30) + k.wrapping_mul(5_368_709) % (1 << 30)));
    for d in ds {
        if (1 << 30..1 << 31).contains(&d) {
            assert_eq!(recip62(d), exact(d), "d = {d}");
            // The unstepped estimate: never above 2^62/d, within 4 units.
            let floor = ((1u128 << 62) / d as u128) as u64;
            let x = super::recip62_floor(d);
            assert!(x <= floor && floor - x < 4, "d = {d}: {x} against {floor}");
        }
    }
}

#[test]
fn normalize_shift_is_leading_zeros_less_one() {
    use super::fixed_point::{normalize_shift, normalize_shift_smeared};
    let mut ds: Vec<u32> = Vec::new();
    for k in 0..31 {
        ds.extend([1u32 << k, (1u32 << k) | 1, (2u32 << k) - 1]);
    }
    let mut x = 0x9e37_79b9_u32;
    for _ in 0..10_000 {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        ds.push((x >> (x % 32)).clamp(1, (1 << 31) - 1));
    }
    for d in ds {
        assert_eq!(normalize_shift(d), d.leading_zeros() - 1, "d = {d}");
        assert_eq!(normalize_shift_smeared(d), d.leading_zeros() - 1, "d = {d}");
    }
}

/// `perspective16` against an exact i128 oracle of the general route's
/// roundings (quotients half away from zero, products half up), and it
/// answers throughout the range its doc promises one step for.
#[test]
fn perspective16_is_the_general_route() {
    use super::fixed_point::perspective16;
    let q = |n: i128, d: i128| -> i128 {
        // Half away from zero, n and d positive.
        (2 * n + d) / (2 * d)
    };
    let oracle = |x: i32, y: i32, z: i32, f: i32| -> Option<(i32, i32, i32)> {
        let inv = i32::try_from(q(1 << 32, z as i128)).ok()?;
        let r = i32::try_from(q((f as i128) << 16, z as i128)).ok()?;
        let m = |v: i32| i32::try_from((v as i128 * r as i128 + (1 << 15)) >> 16).ok();
        Some((m(x)?, m(y)?, inv))
    };
    let mut rng = Rng::new(7);
    let mut answered = 0;
    let cases = 200_000;
    for i in 0..cases {
        let pick = |rng: &mut Rng, lo: f64, hi: f64| rng.range(lo, hi).exp2() as i64;
        let z = match i % 4 {
            0 => pick(&mut rng, 8.0, 31.0) as i32,
            1 => (pick(&mut rng, 12.0, 20.0) as i32) | 1,
            2 => 1 << (8 + i % 23),
            _ => (1 << (8 + i % 23)) - 1 + (i & 2),
        };
        let z = z.max(1 << 8);
        let f = if i % 3 == 0 {
            // At the bound f < 2^(44−s), where the estimate may be 2 short.
            let s = z.leading_zeros() - 1;
            let lim = 1i64 << (44 - s).min(31);
            (lim - 1 - (pick(&mut rng, 0.0, 20.0) % lim)) as i32
        } else {
            pick(&mut rng, 10.0, 31.0) as i32
        };
        let sign = |rng: &mut Rng, v: i64| if rng.range(0.0, 1.0) < 0.5 { -v } else { v };
        let x = pick(&mut rng, 0.0, 23.0);
        let x = sign(&mut rng, x) as i32;
        let y = pick(&mut rng, 0.0, 23.0);
        let y = sign(&mut rng, y) as i32;
        let (x, y) = if i % 97 == 0 {
            (128 << 16, -(128 << 16))
        } else {
            (x, y)
        };
        let got = perspective16(x, y, z, f);
        if let Some(g) = got {
            answered += 1;
            assert_eq!(Some(g), oracle(x, y, z, f), "x {x} y {y} z {z} f {f}");
        } else if z >= 1 << 12 && f < 1 << 26 {
            // The promised range: z ≥ 2^−4, focus below 1024.
            assert_eq!(
                oracle(x, y, z, f),
                None,
                "no answer for x {x} y {y} z {z} f {f}"
            );
        }
    }
    assert!(answered > cases / 2, "answered {answered} of {cases}");
    // Outside its domain it leaves the work to the general route.
    assert_eq!(perspective16(0, 0, (1 << 8) - 1, 1 << 16), None);
    assert_eq!(perspective16(0, 0, 1 << 16, 0), None);
    assert_eq!(perspective16((128 << 16) + 1, 0, 1 << 16, 1 << 16), None);
    assert!(perspective16(0, 0, i32::MAX, 1 << 16).is_some());
    // From z = 1 (s = 14), a focus of 2^14 pixels is one too many.
    assert!(perspective16(0, 0, 1 << 16, (1 << 30) - 1).is_some());
    assert_eq!(perspective16(0, 0, 1 << 16, 1 << 30), None);
}

#[test]
fn split_widening_mul_u32_is_exact() {
    use super::fixed_point::split_widening_mul_u32;
    let edges = [
        0u32,
        1,
        2,
        0xffff,
        0x1_0000,
        0x8000_0000,
        0x7fff_ffff,
        u32::MAX,
        u32::MAX - 1,
    ];
    for &a in &edges {
        for &b in &edges {
            assert_eq!(split_widening_mul_u32(a, b), a as u64 * b as u64, "{a}·{b}");
        }
    }
    let mut rng = Rng::new(7);
    for _ in 0..1 << 18 {
        let x = rng.next_u64();
        let (a, b) = (x as u32, (x >> 32) as u32);
        assert_eq!(split_widening_mul_u32(a, b), a as u64 * b as u64, "{a}·{b}");
    }
}

/// `checked_quotients` (one shared reciprocal, then an exact correction)
/// gives exactly `checked_div` for each numerator, in every fraction
/// width: divisors at the ends of the range, at every power of two and
/// its neighbours (the normalization shifts), numerators at both ends and
/// next to rounding ties, and a pseudo-random sweep of the full bit range.
fn quotients_equal_checked_div<T: Scalar>(from_bits: fn(i32) -> T) {
    let mut special = vec![
        0i32,
        1,
        -1,
        2,
        -2,
        3,
        i32::MAX,
        i32::MIN,
        i32::MAX - 1,
        i32::MIN + 1,
    ];
    for k in 0..31 {
        let p = 1i32 << k;
        special.extend([p, p - 1, p + 1, -p, -p + 1, -p - 1]);
    }
    let check = |n: [i32; 3], d: i32| {
        let (n, d) = (n.map(from_bits), from_bits(d));
        let got = T::checked_quotients(n, d);
        for k in 0..3 {
            assert_eq!(
                got[k],
                n[k].checked_div(d),
                "{} {:?} / {:?}",
                T::NAME,
                n[k],
                d
            );
        }
    };
    for &d in &special {
        for &a in &special {
            check([a, a.wrapping_add(d / 2), a.wrapping_sub(d / 2)], d);
        }
    }
    let mut rng = Rng::new(11);
    for _ in 0..1 << 17 {
        let x = rng.next_u64();
        let y = rng.next_u64();
        // Divisors of every magnitude: shift a random value right by 0..31.
        let d = (x as i32) >> (y % 31);
        // Numerators of every magnitude, and ties: a multiple of d plus half.
        let a = ((x >> 32) as i32) >> ((y >> 8) % 31);
        let tie = (((y >> 16) as i32) >> 16)
            .wrapping_mul(d)
            .wrapping_add(d / 2);
        check([a, tie, (y >> 40) as i32], d);
    }
}

#[test]
fn quotients_equal_checked_div_every_format() {
    quotients_equal_checked_div::<I16F16>(I16F16::from_bits);
    quotients_equal_checked_div::<I24F8>(I24F8::from_bits);
    quotients_equal_checked_div::<I20F12>(I20F12::from_bits);
    quotients_equal_checked_div::<I2F30>(I2F30::from_bits);
}

/// The 32-bit 16.16 product equals the 64-bit one (`mul_wide`, then the
/// range check) wherever it answers, and answers exactly when both
/// operands lie in [−2^23, 2^23): at and around every power of two
/// up to the limit, at the limit itself, and on a random sweep.
#[test]
fn mul16_small_equals_the_wide_product() {
    use super::fixed_point::mul16_small;
    let reference = |a: i32, b: i32| ((a as i64 * b as i64 + (1 << 15)) >> 16) as i32;
    let lim = 1i32 << 23;
    let mut edge = std::vec![0, 1, -1, lim - 1, -(lim - 1), -lim, lim, i32::MAX, i32::MIN];
    for k in 0..23 {
        for d in [-1, 0, 1] {
            edge.push((1 << k) + d);
            edge.push(-(1 << k) + d);
        }
    }
    edge.extend([
        0xffff, 0x10000, 0x7fff, 0x8000, 0x1_8000, -0x8000, -0x1_8000,
    ]);
    let check = |a: i32, b: i32| {
        let small = (-(1 << 23)..1 << 23).contains(&a) && (-(1 << 23)..1 << 23).contains(&b);
        match mul16_small(a, b) {
            Some(r) => {
                assert!(small, "{a}·{b} answered outside the limit");
                assert_eq!(r, reference(a, b), "{a}·{b}");
            }
            None => assert!(!small, "{a}·{b} refused inside the limit"),
        }
    };
    for &a in &edge {
        for &b in &edge {
            check(a, b);
        }
    }
    let mut rng = crate::test_util::Rng::new(1616);
    for _ in 0..1 << 18 {
        let a = rng.range(-(lim as f64) * 1.01, lim as f64 * 1.01) as i32;
        let b = rng.range(-(lim as f64) * 1.01, lim as f64 * 1.01) as i32;
        check(a, b);
        check(a >> 8, b);
    }
}

/// The one-test 16.16 dot product equals the generic one (rounded
/// products, saturating sum from zero, left to right) wherever it answers,
/// and answers exactly when every operand lies in [−2^23, 2^23): operands
/// at the limits, sums that saturate either way, and a random sweep.
#[test]
fn dot16_small_equals_the_generic_dot() {
    use super::fixed_point::dot16_small3 as dot16_small;
    let generic = |a: [i32; 3], b: [i32; 3]| {
        let mut acc = I16F16::ZERO;
        for i in 0..3 {
            acc += I16F16::from_bits(a[i]) * I16F16::from_bits(b[i]);
        }
        acc.to_bits()
    };
    let lim = 1i32 << 23;
    let inside = |v: &[i32; 3]| v.iter().all(|x| (-lim..lim).contains(x));
    let check = |a: [i32; 3], b: [i32; 3]| match dot16_small(a, b) {
        Some(r) => {
            assert!(
                inside(&a) && inside(&b),
                "{a:?}·{b:?} answered outside the limit"
            );
            assert_eq!(r, generic(a, b), "{a:?}·{b:?}");
        }
        None => assert!(
            !(inside(&a) && inside(&b)),
            "{a:?}·{b:?} refused inside the limit"
        ),
    };
    let big = lim - 1;
    // Saturates upwards, downwards, and up then back down (order matters).
    check([big, big, big], [big, big, big]);
    check([-lim, -lim, -lim], [big, big, big]);
    check([big, big, -lim], [big, big, big]);
    // The only first sum that overflows: two products of exactly 2^30.
    check([-lim, -lim, 0], [-lim, -lim, 0]);
    check([-lim, -lim, -lim], [-lim, -lim, lim - 1]);
    check([lim, 0, 0], [1, 0, 0]);
    check([0, 0, 0], [0, -lim - 1, 0]);
    let mut rng = crate::test_util::Rng::new(1617);
    for _ in 0..1 << 17 {
        let r = |rng: &mut crate::test_util::Rng, m: f64| rng.range(-m, m) as i32;
        let m = if rng.range(0.0, 1.0) < 0.5 {
            lim as f64 * 1.001
        } else {
            65536.0 * 4.0
        };
        let a = [r(&mut rng, m), r(&mut rng, m), r(&mut rng, m)];
        let b = [r(&mut rng, m), r(&mut rng, m), r(&mut rng, m)];
        check(a, b);
    }
    assert_eq!(
        dot16_small([3 << 16, 1 << 15, 0], [1 << 16, 1 << 16, 5]),
        Some(7 << 15)
    );
}

/// `shr_to_u32` is `p >> sh` when that is below 2^32 and `None`
/// otherwise, and `shr_u64` is `p >> sh`, for every shift and values at
/// the boundaries.
#[test]
fn shr_to_u32_is_the_64_bit_shift() {
    use super::fixed_point::shr_to_u32;
    let mut x = 0x9e37_79b9_7f4a_7c15_u64;
    let mut ps = vec![0u64, 1, u32::MAX as u64, 1 << 32, u64::MAX, (1 << 63) | 1];
    for k in 0..64 {
        ps.extend([1u64 << k, (1u64 << k).wrapping_sub(1), (1u64 << k) | 1]);
    }
    for _ in 0..2000 {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        ps.push(x >> (x & 63));
    }
    for &p in &ps {
        for sh in 0..64 {
            let want = u32::try_from(p >> sh).ok();
            assert_eq!(shr_to_u32(p, sh), want, "p = {p:#x}, sh = {sh}");
            assert_eq!(
                super::fixed_point::shr_u64(p, sh),
                p >> sh,
                "p = {p:#x}, sh = {sh}"
            );
        }
    }
}

/// `mat3_vec16_small` is the three rows' `dot16_small3` whenever it
/// answers, and answers exactly when every operand is inside the limit;
/// the prepared routes (`mat3_split16` then `mat3_split16_vec`, and
/// `vec3_split16` then `vec3_split16_dot`, with the row as the prepared
/// operand: `dot16_small3(v, row)`) prepare exactly the operands within
/// half the limit and then give the same answers (their sums, unlike
/// `dot16_small3`'s, do not saturate: they cannot reach it).
#[test]
fn mat3_vec16_small_equals_three_dots() {
    use super::fixed_point::{
        dot16_small3, mat3_split16, mat3_split16_vec, mat3_vec16_small, vec3_split16,
        vec3_split16_dot,
    };
    let lim = 1i32 << 23;
    let inside = |x: &i32| (-lim..lim).contains(x);
    let check = |m: [[i32; 3]; 3], v: [i32; 3]| {
        let all_in = v.iter().all(inside) && m.iter().flatten().all(inside);
        let got = mat3_vec16_small(&m, v);
        match got {
            Some(r) => {
                assert!(all_in, "{m:?}·{v:?} answered outside the limit");
                for i in 0..3 {
                    assert_eq!(Some(r[i]), dot16_small3(m[i], v), "{m:?}·{v:?}, row {i}");
                }
            }
            None => assert!(!all_in, "{m:?}·{v:?} refused inside the limit"),
        }
        let half = |x: &i32| (-lim / 2..lim / 2).contains(x);
        let split = mat3_split16(&m);
        assert_eq!(split.is_some(), m.iter().flatten().all(half), "{m:?}");
        if let Some(s) = split {
            assert_eq!(mat3_split16_vec(&s, v), got, "prepared {m:?}·{v:?}");
        }
        for row in m {
            let split = vec3_split16(row);
            assert_eq!(split.is_some(), row.iter().all(half), "{row:?}");
            if let Some(s) = split {
                let dot = vec3_split16_dot(&s, v);
                assert_eq!(dot, dot16_small3(v, row), "prepared {v:?}·{row:?}");
            }
        }
    };
    let big = lim - 1;
    check([[big; 3]; 3], [big; 3]);
    // The largest prepared sums: each product 2^29 in magnitude.
    let p = lim / 2 - 1;
    check([[p; 3], [-lim / 2; 3], [p, -lim / 2, p]], [big; 3]);
    check([[p; 3], [-lim / 2; 3], [p, -lim / 2, p]], [-lim; 3]);
    check([[-lim, -lim, 0], [0; 3], [big, -lim, 1]], [-lim, -lim, 0]);
    check([[0; 3], [0, lim, 0], [0; 3]], [1, 1, 1]);
    check([[0; 3]; 3], [0, 0, -lim - 1]);
    let mut rng = crate::test_util::Rng::new(4711);
    for _ in 0..1 << 15 {
        let m = match rng.int(0, 2) {
            0 => lim as f64 * 1.0003,
            1 => lim as f64 * 0.5002,
            _ => 65536.0 * 4.0,
        };
        let mut r = || rng.range(-m, m) as i32;
        let mm = [[r(), r(), r()], [r(), r(), r()], [r(), r(), r()]];
        let v = [r(), r(), r()];
        check(mm, v);
    }
}
