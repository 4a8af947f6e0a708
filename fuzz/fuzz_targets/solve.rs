//! `solve`: Gaussian elimination on arbitrary systems (n = 1..6, 1..3
//! right-hand sides; f64, f32 or I16F16; entries that include NaN, ±∞,
//! huge, tiny and exactly singular patterns).
//!
//! Oracle: non-finite input must give `NonFinite`; a returned solution must
//! be finite and satisfy the documented backward-error bound
//! (`solve::residual_bound` for floats, `solve::fixed_residual_bound` for
//! fixed point), with residuals formed in f64 (exact products via fma and
//! a compensated sum) from the stored values; any error other than
//! `NonFinite` must be consistent with its diagnostics.
#![no_main]

use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;
use sightline::scalar::{I16F16, Scalar};
use sightline::solve::{SolveError, fixed_residual_bound, residual_bound, solve};

#[derive(Arbitrary, Debug)]
enum Entry {
    /// A small multiple of 1/8: systems where elimination is often exact,
    /// singular or nearly so.
    Small(i8),
    /// Any f64 bit pattern: NaN, ±∞, subnormal, huge.
    Bits(u64),
    /// A value near 1 at a chosen binary scale.
    Scaled(i16, i8),
}

impl Entry {
    fn value(&self) -> f64 {
        match *self {
            Entry::Small(k) => k as f64 / 8.0,
            Entry::Bits(b) => f64::from_bits(b),
            Entry::Scaled(m, e) => (m as f64 / 4096.0) * 2f64.powi(e as i32 / 2),
        }
    }
}

#[derive(Arbitrary, Debug)]
struct Input {
    n: u8,
    m: u8,
    kind: u8,
    entries: [Entry; 54],
}

fn compensated_residual(a: &[Vec<f64>], x: &[f64], b: f64, i: usize) -> f64 {
    let mut s = b;
    let mut c = 0.0;
    for (k, xk) in x.iter().enumerate() {
        let p = a[i][k] * xk;
        let pe = a[i][k].mul_add(*xk, -p);
        let t = s - p;
        let z = t - s;
        c += (s - (t - z)) - (p + z) - pe;
        s = t;
    }
    s + c
}

fn check<T: Scalar, const N: usize, const M: usize>(vals: &[f64]) {
    let a: [[T; N]; N] =
        core::array::from_fn(|i| core::array::from_fn(|j| T::from_f64(vals[i * N + j])));
    let b: [[T; M]; N] =
        core::array::from_fn(|i| core::array::from_fn(|j| T::from_f64(vals[N * N + i * M + j])));
    let finite = a
        .iter()
        .flatten()
        .chain(b.iter().flatten())
        .all(|v| v.is_finite());
    let result = solve(&a, &b);
    if !finite {
        assert_eq!(
            result.unwrap_err(),
            SolveError::NonFinite,
            "{} non-finite input",
            T::NAME
        );
        return;
    }
    let sol = match result {
        Ok(s) => s,
        Err(SolveError::NonFinite) => panic!("{}: NonFinite for finite input", T::NAME),
        Err(SolveError::Singular { column }) => {
            assert!(column < N);
            return;
        }
        Err(SolveError::IllConditioned { rcond }) => {
            // The error carries rcond rounded to f32: allow that rounding.
            let limit = T::EPSILON.to_f64() * (1.0 + f32::EPSILON as f64);
            assert!(
                !(rcond as f64 > limit),
                "{}: rcond {rcond} reported ill-conditioned",
                T::NAME
            );
            return;
        }
        Err(SolveError::Overflow) => return,
    };
    let d = sol.diagnostics;
    assert!(
        d.rcond >= T::EPSILON && d.rcond <= T::ONE,
        "{}: rcond {:?}",
        T::NAME,
        d.rcond
    );
    let growth = d.growth.to_f64();
    assert!(growth >= 1.0 - 1e-3, "{}: growth {growth}", T::NAME);
    let a64: Vec<Vec<f64>> = a
        .iter()
        .map(|r| r.iter().map(|v| v.to_f64()).collect())
        .collect();
    let max_a = a64.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    let norm_a = (0..N)
        .map(|j| (0..N).map(|i| a64[i][j].abs()).sum::<f64>())
        .fold(0.0, f64::max);
    for j in 0..M {
        let x: Vec<f64> = (0..N).map(|i| sol.x[i][j].to_f64()).collect();
        assert!(
            x.iter().all(|v| v.is_finite()),
            "{}: non-finite solution",
            T::NAME
        );
        let r: Vec<f64> = (0..N)
            .map(|i| compensated_residual(&a64, &x, b[i][j].to_f64(), i))
            .collect();
        if T::IS_FLOAT {
            let u = T::EPSILON.to_f64() / 2.0;
            let xn: f64 = x.iter().map(|v| v.abs()).sum();
            let rn: f64 = r.iter().map(|v| v.abs()).sum();
            let scale = norm_a * xn;
            if !scale.is_finite() {
                continue;
            }
            let ratio = rn / (scale * u);
            // Gradual underflow adds an absolute error (below the smallest
            // normal) to each operation, outside the relative model
            // (Higham §2.1): allow n² of them, scaled by ‖A‖.
            let min_normal = if T::EPSILON.to_f64() < 1e-10 {
                f64::MIN_POSITIVE
            } else {
                f32::MIN_POSITIVE as f64
            };
            let underflow = (N * N) as f64 * (1.0 + norm_a) * min_normal;
            assert!(
                ratio <= residual_bound(N, growth) || rn <= underflow,
                "{} n={N}: residual ratio {ratio} > bound {} (growth {growth})",
                T::NAME,
                residual_bound(N, growth)
            );
        } else {
            let max_x = x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let rmax = r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let bound = fixed_residual_bound(N, growth, max_a, max_x, T::EPSILON.to_f64());
            assert!(
                rmax <= bound,
                "{} n={N}: residual {rmax} > bound {bound}",
                T::NAME
            );
        }
    }
}

fn dispatch<T: Scalar>(n: u8, m: u8, vals: &[f64]) {
    macro_rules! go {
        ($($n:literal),*) => {
            match (n % 6 + 1, m % 3 + 1) {
                $( ($n, 1) => check::<T, $n, 1>(vals), ($n, 2) => check::<T, $n, 2>(vals), ($n, 3) => check::<T, $n, 3>(vals), )*
                _ => unreachable!(),
            }
        };
    }
    go!(1, 2, 3, 4, 5, 6)
}

fuzz_target!(|input: Input| {
    let vals: Vec<f64> = input.entries.iter().map(Entry::value).collect();
    match input.kind % 3 {
        0 => dispatch::<f64>(input.n, input.m, &vals),
        1 => dispatch::<f32>(input.n, input.m, &vals),
        _ => dispatch::<I16F16>(input.n, input.m, &vals),
    }
});
