//! Solver tests: LAPACK-style residual ratios on random systems of chosen
//! condition, and the stiff and extreme cases with their documented
//! outcomes.

use super::*;
use crate::scalar::{I16F16, Scalar};
use crate::test_util::Rng;
use std::println;
use std::vec::Vec;

/// LAPACK's relative machine precision (`xLAMCH('E')`): half of Rust's
/// `EPSILON` for round-to-nearest floats. Used so the ratios below are
/// exactly those of `TESTING/LIN` (`xGET02`).
fn lapack_eps<T: Scalar>() -> f64 {
    T::EPSILON.to_f64() * if T::IS_FLOAT { 0.5 } else { 1.0 }
}

fn to_f64<T: Scalar, const N: usize, const M: usize>(a: &[[T; M]; N]) -> [[f64; M]; N] {
    a.map(|r| r.map(|v| v.to_f64()))
}

fn norm1_f64<const N: usize, const M: usize>(a: &[[f64; M]; N]) -> f64 {
    (0..M)
        .map(|j| (0..N).map(|i| a[i][j].abs()).sum::<f64>())
        .fold(0.0, f64::max)
}

/// max over columns j of ‖b_j − A x_j‖₁ / (‖A‖₁ ‖x_j‖₁ ε): `xGET02`.
fn residual_ratio<T: Scalar, const N: usize, const M: usize>(
    a: &[[T; N]; N],
    x: &[[T; M]; N],
    b: &[[T; M]; N],
) -> f64 {
    let (a, x, b) = (to_f64(a), to_f64(x), to_f64(b));
    let an = norm1_f64(&a);
    let mut worst: f64 = 0.0;
    for j in 0..M {
        let mut r = 0.0;
        let mut xn = 0.0;
        for i in 0..N {
            // The residual is formed in f64 (for f64 data with a compensated
            // sum of exact products, so it is not itself dominated by
            // rounding).
            let mut s = b[i][j];
            let mut c = 0.0;
            for k in 0..N {
                let p = a[i][k] * x[k][j];
                let pe = a[i][k].mul_add(x[k][j], -p);
                let t = s - p;
                let z = t - s;
                c += (s - (t - z)) - (p + z) - pe;
                s = t;
            }
            r += (s + c).abs();
            xn += x[i][j].abs();
        }
        worst = worst.max(r / (an * xn * lapack_eps::<T>()));
    }
    worst
}

/// A random orthogonal matrix: a product of N Householder reflections of
/// random normal vectors.
fn random_orthogonal<const N: usize>(rng: &mut Rng) -> [[f64; N]; N] {
    let mut q = [[0.0; N]; N];
    for (i, row) in q.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    for _ in 0..N {
        let v: [f64; N] = core::array::from_fn(|_| rng.normal());
        let vv: f64 = v.iter().map(|x| x * x).sum();
        // Q ← Q (I − 2 v vᵀ / vᵀv)
        for row in q.iter_mut() {
            let d: f64 = row.iter().zip(v.iter()).map(|(a, b)| a * b).sum();
            for (x, vi) in row.iter_mut().zip(v.iter()) {
                *x -= 2.0 * d / vv * vi;
            }
        }
    }
    q
}

/// `U Σ Vᵀ` with singular values geometric from 1 to 1/κ (LAPACK `xLATMS`
/// mode 3), so the 2-norm condition number is κ.
fn random_with_condition<const N: usize>(rng: &mut Rng, kappa: f64) -> [[f64; N]; N] {
    let u = random_orthogonal::<N>(rng);
    let v = random_orthogonal::<N>(rng);
    let sigma: [f64; N] = core::array::from_fn(|i| {
        if N == 1 {
            1.0
        } else {
            kappa.powf(-(i as f64) / (N as f64 - 1.0))
        }
    });
    core::array::from_fn(|i| {
        core::array::from_fn(|j| (0..N).map(|k| u[i][k] * sigma[k] * v[j][k]).sum())
    })
}

fn cast<T: Scalar, const N: usize, const M: usize>(a: &[[f64; M]; N]) -> [[T; M]; N] {
    a.map(|r| r.map(T::from_f64))
}

/// True 1-norm reciprocal condition number of the stored matrix, from its
/// inverse computed in f64.
fn true_rcond<const N: usize>(a: &[[f64; N]; N]) -> f64 {
    let mut id = [[0.0; N]; N];
    for (i, r) in id.iter_mut().enumerate() {
        r[i] = 1.0;
    }
    let cfg = SolveConfig { rcond_min: 0.0 };
    let inv = solve_with(a, &id, &cfg).expect("reference inverse").x;
    1.0 / (norm1_f64(a) * norm1_f64(&inv))
}

#[derive(Default, Debug)]
struct Stats {
    systems: usize,
    worst_ratio: f64,
    worst_rcond_overestimate: f64,
}

fn residual_suite<T: Scalar, const N: usize, const M: usize>(stats: &mut Stats) {
    let mut rng = Rng::new(0x5eed + (N * 31 + M) as u64);
    let max_kappa = 0.1 / T::EPSILON.to_f64();
    let mut kappas = Vec::new();
    let mut k = 2.0;
    while k <= max_kappa {
        kappas.push(k);
        k *= 10.0;
    }
    kappas.push(max_kappa);
    for &kappa in &kappas {
        for _ in 0..3 {
            let a64 = random_with_condition::<N>(&mut rng, kappa);
            let b64: [[f64; M]; N] =
                core::array::from_fn(|_| core::array::from_fn(|_| rng.range(-1.0, 1.0)));
            let (a, b) = (cast::<T, N, N>(&a64), cast::<T, N, M>(&b64));
            let sol = solve(&a, &b)
                .unwrap_or_else(|e| panic!("{} n={N} m={M} κ₂={kappa:e}: unexpected {e}", T::NAME));
            let ratio = residual_ratio(&a, &sol.x, &b);
            assert!(
                ratio < 30.0,
                "{} n={N} m={M} κ₂={kappa:e}: residual ratio {ratio}",
                T::NAME
            );
            // In exact arithmetic the estimate bounds the true rcond from
            // above (‖A⁻¹‖₁ is estimated from below); the solves behind it
            // carry a relative error of order n·κ₁·ε, which loosens that
            // bound by the same factor. It is also within a small factor.
            let rc = sol.diagnostics.rcond.to_f64();
            let truth = true_rcond(&to_f64(&a));
            let rounding = 1.0 + N as f64 * T::EPSILON.to_f64() / truth;
            assert!(
                rc >= truth / rounding,
                "{} n={N}: rcond {rc} < true {truth}",
                T::NAME
            );
            let over = rc / truth;
            assert!(
                over <= N as f64,
                "{} n={N}: rcond {rc} vs true {truth}",
                T::NAME
            );
            assert!(sol.diagnostics.growth.to_f64() >= 1.0);
            stats.systems += 1;
            stats.worst_ratio = stats.worst_ratio.max(ratio);
            stats.worst_rcond_overestimate = stats.worst_rcond_overestimate.max(over);
        }
    }
}

macro_rules! residual_sizes {
    ($t:ty, $stats:ident; $($n:literal),*) => {
        $(
            residual_suite::<$t, $n, 1>(&mut $stats);
            residual_suite::<$t, $n, 3>(&mut $stats);
        )*
        residual_suite::<$t, 4, 4>(&mut $stats);
        residual_suite::<$t, 12, 5>(&mut $stats);
    };
}

#[test]
fn residual_ratio_below_30_f64() {
    let mut stats = Stats::default();
    residual_sizes!(f64, stats; 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12);
    println!("f64 residual suite: {stats:?}");
}

#[test]
fn residual_ratio_below_30_f32() {
    let mut stats = Stats::default();
    residual_sizes!(f32, stats; 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12);
    println!("f32 residual suite: {stats:?}");
}

fn hilbert<const N: usize>() -> [[f64; N]; N] {
    core::array::from_fn(|i| core::array::from_fn(|j| 1.0 / (i + j + 1) as f64))
}

/// Solves H x = H·1 and reports (outcome, forward error, residual ratio,
/// growth, rcond).
fn hilbert_case<T: Scalar, const N: usize>() -> Result<(f64, f64, f64, f64), SolveError> {
    let h: [[T; N]; N] = cast(&hilbert::<N>());
    let hf = to_f64(&h);
    // b = H_stored · 1, rounded to T.
    let b: [[T; 1]; N] = core::array::from_fn(|i| [T::from_f64(hf[i].iter().sum())]);
    let s = solve(&h, &b)?;
    let fwd =
        s.x.iter()
            .map(|r| (r[0].to_f64() - 1.0).abs())
            .fold(0.0, f64::max);
    Ok((
        fwd,
        residual_ratio(&h, &s.x, &b),
        s.diagnostics.growth.to_f64(),
        s.diagnostics.rcond.to_f64(),
    ))
}

/// Hilbert matrices: solved while κ₁ < 1/ε, then reported ill-conditioned.
/// κ₁(H₄) ≈ 2.8·10⁴, κ₁(H₇) ≈ 9.9·10⁸, κ₁(H₁₂) ≈ 4·10¹⁶.
#[test]
fn hilbert_growing_order() {
    macro_rules! run {
        ($t:ty; $($n:literal),*) => {{
            std::vec![$(($n, hilbert_case::<$t, $n>())),*]
        }};
    }
    let f64_results = run!(f64; 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14);
    let f32_results = run!(f32; 2, 3, 4, 5, 6, 7, 8);
    for (name, results, last_ok) in [("f64", &f64_results, 11), ("f32", &f32_results, 5)] {
        for (n, r) in results.iter() {
            match r {
                Ok((fwd, ratio, growth, rcond)) => {
                    println!(
                        "{name} Hilbert n={n}: forward error {fwd:.2e}, residual ratio {ratio:.3}, growth {growth:.3}, rcond {rcond:.3e}"
                    );
                    assert!(
                        *n <= last_ok,
                        "{name} H{n} should be reported ill-conditioned"
                    );
                    assert!(*ratio < 30.0);
                    // Forward error ≤ κ·ε·(small constant): checks the
                    // solution, not only the residual.
                    let eps = if name == "f64" {
                        f64::EPSILON
                    } else {
                        f32::EPSILON as f64
                    };
                    assert!(
                        *fwd <= 10.0 * eps / rcond,
                        "{name} H{n}: forward error {fwd}"
                    );
                }
                Err(e) => {
                    println!("{name} Hilbert n={n}: {e}");
                    assert!(*n > last_ok, "{name} H{n}: unexpected {e}");
                    assert!(
                        matches!(e, SolveError::IllConditioned { .. }),
                        "{name} H{n}: {e}"
                    );
                }
            }
        }
    }
}

fn wilkinson<const N: usize>() -> [[f64; N]; N] {
    core::array::from_fn(|i| {
        core::array::from_fn(|j| {
            if j == N - 1 || i == j {
                1.0
            } else if i > j {
                -1.0
            } else {
                0.0
            }
        })
    })
}

/// Wilkinson's matrix reaches the partial-pivoting bound ρ = 2ⁿ⁻¹ exactly
/// (Higham §9.4); the growth is reported exactly.
#[test]
fn wilkinson_growth_is_reported_exactly() {
    fn check<T: Scalar, const N: usize>() {
        let a: [[T; N]; N] = cast(&wilkinson::<N>());
        let lu = Lu::factor(&a).expect("nonsingular");
        assert_eq!(
            lu.growth().to_f64(),
            (1u64 << (N - 1)) as f64,
            "{} n={N}",
            T::NAME
        );
    }
    check::<f64, 2>();
    check::<f64, 8>();
    check::<f64, 12>();
    check::<f32, 12>();
    check::<f32, 24>();
    check::<f64, 50>();
    check::<I16F16, 12>();
    // 2¹⁵ exceeds I16F16's range (±32768): reported, not wrapped.
    let a: [[I16F16; 17]; 17] = cast(&wilkinson::<17>());
    assert_eq!(Lu::factor(&a).unwrap_err(), SolveError::Overflow);
}

#[test]
fn near_singular_2x2() {
    let sys = |d: f64| ([[1.0, 1.0], [1.0, 1.0 + d]], [[2.0], [2.0 + d]]);
    // Well separated: solved, with rcond ≈ d/4.
    let (a, b) = sys(1e-3);
    let s = solve(&a, &b).unwrap();
    assert!((s.x[0][0] - 1.0).abs() < 1e-12 && (s.x[1][0] - 1.0).abs() < 1e-12);
    let rc = s.diagnostics.rcond;
    assert!((rc / (1e-3 / 4.0) - 1.0).abs() < 0.01, "rcond {rc}");
    // d below half an ulp of 1: the stored matrix is exactly singular.
    let (a, b) = sys(f64::EPSILON / 4.0);
    assert_eq!(
        solve(&a, &b).unwrap_err(),
        SolveError::Singular { column: 1 }
    );
    // d a few ulps: nonzero pivot, but singular to working precision.
    let (a, b) = sys(4.0 * f64::EPSILON);
    assert!(matches!(
        solve(&a, &b),
        Err(SolveError::IllConditioned { .. })
    ));
    // The same in f32.
    let a = [[1.0f32, 1.0], [1.0, 1.0 + 2.0 * f32::EPSILON]];
    assert!(matches!(
        solve(&a, &[[2.0f32], [2.0]]),
        Err(SolveError::IllConditioned { .. })
    ));
}

/// Rank 2 in exact arithmetic (row 3 = row 1 + row 2 in decimals that are
/// not binary fractions), so rounding leaves a tiny, nonzero last pivot.
#[test]
fn rank_deficient_without_exact_zero_pivot() {
    let a = [[0.1, 0.2, 0.3], [0.4, 0.5, 0.6], [0.5, 0.7, 0.9]];
    let lu = Lu::factor(&a).expect("no exactly zero pivot");
    assert!(lu.rcond() < f64::EPSILON, "rcond {}", lu.rcond());
    assert!(matches!(
        solve(&a, &[[1.0], [2.0], [3.0]]),
        Err(SolveError::IllConditioned { .. })
    ));
    let af: [[f32; 3]; 3] = cast(&a);
    assert!(matches!(
        solve(&af, &[[1.0], [2.0], [3.0]]),
        Err(SolveError::IllConditioned { .. } | SolveError::Singular { .. })
    ));
}

#[test]
fn zero_column_names_the_column() {
    for col in 0..3 {
        let mut a = [[2.0, 1.0, 3.0], [1.0, 4.0, 1.0], [3.0, 1.0, 5.0]];
        for row in a.iter_mut() {
            row[col] = 0.0;
        }
        assert_eq!(
            solve(&a, &[[1.0], [1.0], [1.0]]).unwrap_err(),
            SolveError::Singular { column: col }
        );
        let af: [[I16F16; 3]; 3] = cast(&a);
        assert_eq!(
            solve(&af, &[[I16F16::ONE]; 3]).unwrap_err(),
            SolveError::Singular { column: col }
        );
    }
}

/// A tiny leading entry: without pivoting the multiplier 10²⁰ would wipe
/// out the second row.
#[test]
fn tiny_leading_entry_needs_pivoting() {
    let a = [[1e-20, 1.0], [1.0, 1.0]];
    let b = [[1.0], [2.0]];
    let s = solve(&a, &b).unwrap();
    // Exact solution: x₁ = 1/(1 − 10⁻²⁰) ≈ 1, x₂ = 1 − 10⁻²⁰·x₁ ≈ 1.
    assert!((s.x[0][0] - 1.0).abs() <= f64::EPSILON);
    assert!((s.x[1][0] - 1.0).abs() <= f64::EPSILON);
    let af = [[1e-20f32, 1.0], [1.0, 1.0]];
    let s = solve(&af, &[[1.0f32], [2.0]]).unwrap();
    assert!((s.x[0][0] - 1.0).abs() <= f32::EPSILON);
}

/// Scaling the whole system by 2ᵏ, or a column of A by 2ᵏ, changes no
/// pivot choice and no multiplier: the solution is bit-identical (scaled by
/// 2⁻ᵏ in the column's unknown).
#[test]
fn power_of_two_scaling_is_bit_identical() {
    let mut rng = Rng::new(99);
    for _ in 0..50 {
        let a: [[f64; 5]; 5] = random_with_condition(&mut rng, 1e4);
        let b: [[f64; 2]; 5] = core::array::from_fn(|_| [rng.normal(), rng.normal()]);
        let x = solve(&a, &b).unwrap().x;
        for k in [-40, -3, 1, 17, 60] {
            let s = 2f64.powi(k);
            let as_ = a.map(|r| r.map(|v| v * s));
            let bs = b.map(|r| r.map(|v| v * s));
            assert_eq!(solve(&as_, &bs).unwrap().x, x, "system × 2^{k}");
            let mut ac = a;
            for row in ac.iter_mut() {
                row[2] *= s;
            }
            // Column scaling changes the condition number, so the rcond
            // threshold is switched off for this half of the check.
            let xc = solve_with(&ac, &b, &SolveConfig { rcond_min: 0.0 })
                .unwrap()
                .x;
            for i in 0..5 {
                for j in 0..2 {
                    let expect = if i == 2 { x[i][j] / s } else { x[i][j] };
                    assert_eq!(xc[i][j], expect, "column 2 × 2^{k}");
                }
            }
        }
    }
}

#[test]
fn many_right_hand_sides_equal_separate_solves() {
    fn check<T: Scalar>() {
        let mut rng = Rng::new(7);
        let a: [[T; 6]; 6] = cast(&random_with_condition::<6>(&mut rng, 100.0));
        let b: [[T; 4]; 6] =
            core::array::from_fn(|_| core::array::from_fn(|_| T::from_f64(rng.normal())));
        let together = solve(&a, &b).unwrap().x;
        for j in 0..4 {
            let bj: [[T; 1]; 6] = core::array::from_fn(|i| [b[i][j]]);
            let xj = solve(&a, &bj).unwrap().x;
            for i in 0..6 {
                assert_eq!(together[i][j], xj[i][0], "{}", T::NAME);
            }
        }
    }
    check::<f64>();
    check::<f32>();
    check::<I16F16>();
}

#[test]
fn fixed_point_systems() {
    type T = I16F16;
    // A well-conditioned system: residual within the fixed-point bound.
    let mut rng = Rng::new(5);
    for _ in 0..100 {
        let a64 = random_with_condition::<4>(&mut rng, 10.0).map(|r| r.map(|v| v * 8.0));
        let b64: [[f64; 2]; 4] =
            core::array::from_fn(|_| [rng.range(-8.0, 8.0), rng.range(-8.0, 8.0)]);
        let (a, b) = (cast::<T, 4, 4>(&a64), cast::<T, 4, 2>(&b64));
        let s = solve(&a, &b).unwrap();
        // Fixed point has an absolute, not relative, step, so the LAPACK
        // ratio is formed with ε = one step; the bound stays 30.
        let ratio = residual_ratio(&a, &s.x, &b);
        assert!(ratio < 30.0, "I16F16 ratio {ratio}");
    }
    // Products that overflow during elimination: −20000 − 0.9·20000.
    let a: [[T; 2]; 2] = cast(&[[1.0, 20000.0], [0.9, -20000.0]]);
    assert_eq!(Lu::factor(&a).unwrap_err(), SolveError::Overflow);
    // A solution outside the range (|x| ≈ 4·10⁴ > 32768) is reported.
    let a: [[T; 2]; 2] = cast(&[[0.5, 1.0], [1.0, 0.5]]);
    let b: [[T; 1]; 2] = cast(&[[30000.0], [-30000.0]]);
    assert_eq!(solve(&a, &b).unwrap_err(), SolveError::Overflow);
    // Nearly singular for the format: ill-conditioned, not garbage.
    let a: [[T; 2]; 2] = cast(&[[1.0, 1.0], [1.0, 1.0 + 1.0 / 32768.0]]);
    assert!(matches!(
        solve(&a, &[[T::ONE], [T::ONE]]),
        Err(SolveError::IllConditioned { .. })
    ));
}

#[test]
fn non_finite_input_is_rejected() {
    let good = [[1.0f32, 0.0], [0.0, 1.0]];
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        let mut a = good;
        a[1][0] = bad;
        assert_eq!(
            solve(&a, &[[1.0], [1.0]]).unwrap_err(),
            SolveError::NonFinite
        );
        assert_eq!(
            solve(&good, &[[1.0], [bad]]).unwrap_err(),
            SolveError::NonFinite
        );
    }
}

/// Entries near f64's limits: the solution overflows to ∞, which is
/// reported, never returned.
#[test]
fn float_overflow_is_reported() {
    // Well conditioned (rcond ½), but x₁ = 2·10³⁰⁸ is beyond f64.
    let a = [[0.5, 0.0], [0.0, 1.0]];
    let b = [[1e308], [1.0]];
    assert_eq!(solve(&a, &b).unwrap_err(), SolveError::Overflow);
    // Badly scaled instead: reported as ill-conditioned before any overflow.
    let a = [[1e-300, 0.0], [0.0, 1.0]];
    assert!(matches!(
        solve(&a, &[[1e300], [1.0]]),
        Err(SolveError::IllConditioned { .. })
    ));
    let a = [[f64::MAX, f64::MAX], [-f64::MAX, f64::MAX]];
    assert!(solve(&a, &[[1.0], [1.0]]).is_err());
}

#[test]
fn errors_display() {
    use std::string::ToString;
    assert_eq!(
        SolveError::Singular { column: 2 }.to_string(),
        "matrix is singular: zero pivot in column 2"
    );
    assert!(
        SolveError::IllConditioned { rcond: 1e-9 }
            .to_string()
            .contains("1e-9")
    );
}

/// `invert` is the solver on `A X = I`; a singular 4×4 (last row = w = z)
/// is reported with its column, and `invert_affine` round-trips.
#[test]
fn invert_reports_singular_and_round_trips() {
    let mut m = [[0.0f64; 4]; 4];
    for (i, r) in m.iter_mut().enumerate().take(3) {
        r[i] = 1.0;
    }
    m[3] = [0.0, 0.0, 1.0, 0.0];
    assert_eq!(invert(&m).unwrap_err(), SolveError::Singular { column: 3 });
    let a = crate::math::Affine3::new(
        crate::math::Mat3::from_diagonal(crate::math::Vec3::new(2.0f64, 4.0, -0.5)),
        crate::math::Vec3::new(1.0, 2.0, 3.0),
    );
    let inv = invert_affine(&a).unwrap();
    let p = crate::math::Vec3::new(0.25, -8.0, 3.5);
    assert_eq!(inv.transform_point3(a.transform_point3(p)), p);
    let mut bad = a;
    bad.matrix.m[1] = [0.0; 3];
    assert!(invert_affine(&bad).is_err());
}
