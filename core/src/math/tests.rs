//! Vector and matrix tests, written once and instantiated per scalar.

use super::*;
use crate::scalar::{I16F16, Scalar};
use crate::test_util::Rng;

fn v3<T: Scalar>(x: f64, y: f64, z: f64) -> Vec3<T> {
    Vec3::new(T::from_f64(x), T::from_f64(y), T::from_f64(z))
}

fn close<T: Scalar>(a: Vec3<T>, b: Vec3<T>, tol: f64) -> bool {
    (a - b).max_abs().to_f64() <= tol
}

fn products<T: Scalar>() {
    let (x, y, z) = (Vec3::<T>::X, Vec3::<T>::Y, Vec3::<T>::Z);
    assert_eq!(x.cross(y), z);
    assert_eq!(y.cross(z), x);
    assert_eq!(z.cross(x), y);
    let a = v3::<T>(1.0, 2.0, 3.0);
    let b = v3::<T>(-2.0, 0.5, 4.0);
    assert_eq!(a.dot(b).to_f64(), 11.0);
    assert_eq!(a.cross(b), v3(6.5, -10.0, 4.5));
    assert_eq!(a.cross(b).dot(a), T::ZERO);
    assert_eq!(
        Vec2::new(T::ONE, T::ZERO).perp_dot(Vec2::new(T::ZERO, T::ONE)),
        T::ONE
    );
}

fn normalize_is_robust<T: Scalar>(small: f64, large: f64) {
    let tol = 4.0 * T::EPSILON.to_f64();
    for s in [small, 1.0, large] {
        let v = v3::<T>(3.0 * s, -4.0 * s, 0.0);
        let n = v.try_normalize().expect("non-zero vector normalizes");
        assert!(
            close(n, v3(0.6, -0.8, 0.0), tol),
            "{}: {n:?} at scale {s}",
            T::NAME
        );
        assert!((v.length().to_f64() - 5.0 * s).abs() <= 5.0 * s * tol + tol);
    }
    assert_eq!(Vec3::<T>::ZERO.try_normalize(), None);
    assert_eq!(Vec3::<T>::ZERO.normalize(), Vec3::ZERO);
}

fn rotations_are_orthonormal_and_right_handed<T: Scalar>(tol_steps: f64) {
    let tol = tol_steps * T::EPSILON.to_f64();
    let mut rng = Rng::new(11);
    for _ in 0..200 {
        let a = T::from_f64(rng.range(-4.0, 4.0));
        for r in [
            Mat3::rotation_x(a),
            Mat3::rotation_y(a),
            Mat3::rotation_z(a),
        ] {
            let rrt = r.mul_mat3(&r.transpose());
            for i in 0..3 {
                assert!(close(rrt.row(i), Mat3::<T>::IDENTITY.row(i), tol));
            }
            assert!((r.determinant().to_f64() - 1.0).abs() <= tol);
        }
    }
    let q = T::PI * T::HALF;
    let tolv = 2.0 * T::EPSILON.to_f64();
    // Right-hand rule: X→Y about Z, Y→Z about X, Z→X about Y.
    assert!(close(Mat3::rotation_z(q).mul_vec3(Vec3::X), Vec3::Y, tolv));
    assert!(close(Mat3::rotation_x(q).mul_vec3(Vec3::Y), Vec3::Z, tolv));
    assert!(close(Mat3::rotation_y(q).mul_vec3(Vec3::Z), Vec3::X, tolv));
}

fn affine_inverse_round_trips<T: Scalar>(tol: f64) {
    let mut rng = Rng::new(12);
    for _ in 0..100 {
        let r = Mat3::rotation_y(T::from_f64(rng.range(-3.0, 3.0)))
            .mul_mat3(&Mat3::rotation_x(T::from_f64(rng.range(-3.0, 3.0))));
        let s = Mat3::from_diagonal(v3(rng.range(0.5, 2.0), rng.range(0.5, 2.0), 1.0));
        let a = Affine3::new(
            r.mul_mat3(&s),
            v3(rng.range(-10.0, 10.0), rng.range(-10.0, 10.0), 3.0),
        );
        let inv = a.try_inverse().expect("well-conditioned");
        let p = v3::<T>(
            rng.range(-5.0, 5.0),
            rng.range(-5.0, 5.0),
            rng.range(-5.0, 5.0),
        );
        let back = inv.transform_point3(a.transform_point3(p));
        assert!(close(back, p, tol), "{}: {back:?} vs {p:?}", T::NAME);
        // A vector ignores the translation.
        assert_eq!(a.transform_vector3(p), a.matrix.mul_vec3(p),);
        // The 4×4 form agrees with the affine form.
        let m4 = a.to_mat4();
        assert_eq!(m4.transform_point3(p), a.transform_point3(p));
        assert!(close(
            m4.project_point3(p).expect("w = 1"),
            a.transform_point3(p),
            0.0
        ));
    }
}

fn mat4_projection_rejects_w_zero<T: Scalar>() {
    let mut m = Mat4::<T>::IDENTITY;
    m.m[3] = [T::ZERO, T::ZERO, T::ONE, T::ZERO]; // w = z
    assert_eq!(m.project_point3(v3(1.0, 2.0, 0.0)), None);
    assert_eq!(m.project_point3(v3(1.0, 2.0, 2.0)), Some(v3(0.5, 1.0, 1.0)));
}

/// The exact inverse of an integer matrix: `adj(A)` and `det(A)` in i128.
fn exact_adjugate(a: &[[i64; 3]; 3]) -> ([[i128; 3]; 3], i128) {
    let e = |i: usize, j: usize| a[i % 3][j % 3] as i128;
    let mut adj = [[0i128; 3]; 3];
    for (i, row) in adj.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            // Cofactor C_ji (transposed), by cyclic indices.
            *x = e(j + 1, i + 1) * e(j + 2, i + 2) - e(j + 1, i + 2) * e(j + 2, i + 1);
        }
    }
    let det = (0..3).map(|k| a[0][k] as i128 * adj[k][0]).sum();
    (adj, det)
}

/// `Mat3::try_inverse` against the exact rational inverse of random
/// integer matrices (exact in every scalar), with the first-order error
/// bound of the row-scaled adjugate: for `N = D⁻¹A` (rows of largest
/// |entry| 1) the computed inverse's error is at most `K·ε·κ∞(N)·‖N⁻¹‖∞`
/// scaled back by the column's row scale, `K = 16` (the rounding of N, of
/// the three cross products and of the triple product, each γ₂…γ₅ on
/// terms ≤ 1, and two divisions), plus for fixed point the absolute grid
/// step of each of the two final divisions. The oracle `adj/det` is
/// rounded once to f64 (2⁻⁵³ relative, below 1/32 of the f64 bound).
/// Exactly singular integer matrices must give `None`.
#[allow(clippy::needless_range_loop)] // indices mirror the matrix formulas
fn mat3_inverse_matches_exact<T: Scalar>() -> f64 {
    let mut rng = Rng::new(77);
    let eps = T::EPSILON.to_f64();
    let mut worst = 0.0f64;
    let mut tested = 0;
    for trial in 0..4000 {
        let mut a = [[0i64; 3]; 3];
        for x in a.iter_mut().flatten() {
            *x = rng.range(-20.0, 21.0).floor() as i64;
        }
        if trial % 4 == 0 {
            // An exactly singular matrix: row 2 = p·row 0 + q·row 1.
            let (p, q) = (
                rng.range(-2.0, 3.0).floor() as i64,
                rng.range(-2.0, 3.0).floor() as i64,
            );
            for j in 0..3 {
                a[2][j] = p * a[0][j] + q * a[1][j];
            }
        }
        let (adj, det) = exact_adjugate(&a);
        let m = Mat3 {
            m: a.map(|r| r.map(|x| T::from_i32(x as i32))),
        };
        let inv = m.try_inverse();
        if det == 0 {
            assert_eq!(inv, None, "{}: singular {a:?}", T::NAME);
            continue;
        }
        let exact = |i: usize, j: usize| adj[i][j] as f64 / det as f64;
        let s: [f64; 3] =
            core::array::from_fn(|i| a[i].iter().map(|x| x.abs()).max().unwrap() as f64);
        // κ∞(N) = ‖N‖∞·‖N⁻¹‖∞ with N⁻¹ = A⁻¹·D.
        let norm_n = (0..3)
            .map(|i| a[i].iter().map(|&x| x.abs() as f64).sum::<f64>() / s[i])
            .fold(0.0, f64::max);
        let norm_ninv = (0..3)
            .map(|i| (0..3).map(|j| (exact(i, j) * s[j]).abs()).sum::<f64>())
            .fold(0.0, f64::max);
        let kappa = norm_n * norm_ninv;
        let fixed_step = if T::IS_FLOAT { 0.0 } else { 2.0 * eps };
        // Near-singular to working precision: `None` is allowed there.
        if kappa * eps > 1e-3 {
            continue;
        }
        let inv = inv.unwrap_or_else(|| panic!("{}: {a:?} (κ = {kappa}) refused", T::NAME));
        tested += 1;
        for i in 0..3 {
            for j in 0..3 {
                let err = (inv.m[i][j].to_f64() - exact(i, j)).abs();
                let bound = 16.0 * eps * kappa * norm_ninv / s[j] + fixed_step;
                worst = worst.max(err / bound);
                assert!(
                    err <= bound,
                    "{}: {a:?} entry ({i},{j}): {} vs {} (err {err:e} > {bound:e})",
                    T::NAME,
                    inv.m[i][j].to_f64(),
                    exact(i, j)
                );
            }
        }
    }
    assert!(tested > 2000, "{}: only {tested} matrices tested", T::NAME);
    worst
}

#[test]
fn mat3_inverse_is_exact_to_its_bound() {
    let w = [
        mat3_inverse_matches_exact::<f64>(),
        mat3_inverse_matches_exact::<f32>(),
        mat3_inverse_matches_exact::<I16F16>(),
    ];
    std::println!("worst error / bound (f64, f32, I16F16): {w:?}");
}

/// Non-finite entries and zero rows are refused, not propagated.
#[test]
fn mat3_inverse_refuses_bad_input() {
    let mut m = Mat3::<f32>::IDENTITY;
    m.m[1][2] = f32::NAN;
    assert_eq!(m.try_inverse(), None);
    m.m[1][2] = f32::INFINITY;
    assert_eq!(m.try_inverse(), None);
    let mut z = Mat3::<I16F16>::IDENTITY;
    z.m[2] = [I16F16::ZERO; 3];
    assert_eq!(z.try_inverse(), None);
    // A large scale: the inverse's entries would be below the fixed-point
    // grid, but row scaling keeps them (1/20000 is 3 grid steps).
    let big = Mat3::<I16F16>::from_diagonal(Vec3::new(
        I16F16::from_i32(20000),
        I16F16::from_i32(2),
        I16F16::from_i32(-4),
    ));
    let inv = big.try_inverse().unwrap();
    assert!((inv.m[0][0].to_f64() - 1.0 / 20000.0).abs() <= I16F16::EPSILON.to_f64());
    assert_eq!(inv.m[2][2].to_f64(), -0.25);
}

macro_rules! math_suite {
    ($name:ident, $t:ty, small = $small:expr, large = $large:expr, rot_steps = $rs:expr, inv_tol = $it:expr) => {
        mod $name {
            use super::*;
            #[test]
            fn vector_products() {
                products::<$t>();
            }
            #[test]
            fn normalize() {
                normalize_is_robust::<$t>($small, $large);
            }
            #[test]
            fn rotations() {
                rotations_are_orthonormal_and_right_handed::<$t>($rs);
            }
            #[test]
            fn affine_inverse() {
                affine_inverse_round_trips::<$t>($it);
            }
            #[test]
            fn mat4_projection() {
                mat4_projection_rejects_w_zero::<$t>();
            }
        }
    };
}

// Normalization is scaled by the largest component, so it holds from the
// smallest normal magnitudes to the largest finite ones.
math_suite!(
    f64_suite,
    f64,
    small = 1e-300,
    large = 1e300,
    rot_steps = 8.0,
    inv_tol = 1e-12
);
math_suite!(
    f32_suite,
    f32,
    small = 1e-35,
    large = 1e35,
    rot_steps = 8.0,
    inv_tol = 1e-4
);
// I16F16: components from 2⁻¹⁰ (so the direction is still resolvable) to
// 5000 (so the length fits); rotation entries carry ≤ 1 step of trig error,
// sums of 3 products ≤ 8 steps; the round trip through a scaled inverse is
// within 2·10⁻² for |p| ≤ 10.
math_suite!(
    i16f16_suite,
    I16F16,
    small = 1.0 / 1024.0,
    large = 5000.0,
    rot_steps = 8.0,
    inv_tol = 2e-2
);

#[test]
fn non_finite_vectors_do_not_normalize() {
    assert_eq!(Vec3::new(f32::NAN, 1.0, 0.0).try_normalize(), None);
    assert_eq!(Vec3::new(f32::INFINITY, 1.0, 0.0).try_normalize(), None);
    assert_eq!(Vec3::new(f32::NAN, 1.0, 0.0).normalize(), Vec3::ZERO);
}

/// `try_orthonormalize` restores a drifted rotation: the result is
/// orthonormal and right-handed to a few ε, keeps row 0's direction, stays
/// close to the input, and rejects parallel or zero leading rows.
/// (Regression: exactly parallel rows used to return a "rotation" built
/// from the rounding residue of row 1 instead of `None`.)
#[test]
fn orthonormalize_repairs_a_drifted_rotation() {
    let r = Mat3::rotation_x(0.4f64)
        .mul_mat3(&Mat3::rotation_y(-1.1))
        .mul_mat3(&Mat3::rotation_z(2.0));
    // Drift: scale and shear the rows by ~1e-3.
    let d = Mat3::from_rows(
        r.row(0) * 1.001,
        r.row(1) + r.row(0) * 2e-3,
        r.row(2) * 0.999 + r.row(1) * 1e-3,
    );
    let o = d.try_orthonormalize().unwrap();
    let oot = o.mul_mat3(&o.transpose());
    for i in 0..3 {
        let e = Vec3::new(
            f64::from(u8::from(i == 0)),
            f64::from(u8::from(i == 1)),
            f64::from(u8::from(i == 2)),
        );
        assert!((oot.row(i) - e).max_abs() < 4.0 * f64::EPSILON, "row {i}");
        // Within the drift of the exact rotation.
        assert!((o.row(i) - r.row(i)).max_abs() < 5e-3, "row {i}");
    }
    assert!((o.determinant() - 1.0).abs() < 4.0 * f64::EPSILON);
    assert!(
        o.row(0).cross(r.row(0)).max_abs() < 1e-15,
        "row 0 keeps its direction"
    );
    let parallel = Mat3::from_rows(r.row(0), r.row(0) * 2.0, r.row(2));
    assert_eq!(parallel.try_orthonormalize(), None);
    let zero = Mat3::from_rows(Vec3::ZERO, r.row(1), r.row(2));
    assert_eq!(zero.try_orthonormalize(), None);
}

/// `Affine3::for_points` gives `transform_point3`'s values for every point,
/// whether or not the matrix and the point are in the range of a prepared
/// route (16.16 on ARMv6-M; elsewhere the plain route, checked here the
/// same way), with saturating translations and non-finite floats.
fn point_transform_is_transform_point3<T: Scalar>() {
    let mut rng = Rng::new(909);
    for i in 0..4000 {
        let s = if i % 2 == 0 { 2.0 } else { 300.0 };
        let mut r = |m: f64| T::from_f64(rng.range(-m, m));
        let m = Mat3::from_rows(
            Vec3::new(r(s), r(s), r(s)),
            Vec3::new(r(s), r(s), r(s)),
            Vec3::new(r(s), r(s), r(s)),
        );
        let a = Affine3::new(m, Vec3::new(r(3e4), r(3e4), r(3e4)));
        let pt = a.for_points();
        assert_eq!(pt.affine(), &a);
        for _ in 0..4 {
            let q = if i % 3 == 0 { 1e5 } else { 100.0 };
            let p = Vec3::new(r(q), r(q), r(q));
            let (want, got) = (a.transform_point3(p), pt.apply(p));
            // Bitwise (NaN included), through the scalar's own encoding.
            let bits = |v: Vec3<T>| v.to_array().map(|c| std::format!("{c:?}"));
            assert_eq!(bits(got), bits(want), "{a:?} at {p:?}");
        }
    }
}

#[test]
fn point_transform_matches_transform_point3() {
    point_transform_is_transform_point3::<f32>();
    point_transform_is_transform_point3::<f64>();
    point_transform_is_transform_point3::<I16F16>();
}
