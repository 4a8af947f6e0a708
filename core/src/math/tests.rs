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
    let inv = m.try_inverse();
    assert!(inv.is_err(), "the last row makes this matrix singular");
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

// Normalisation is scaled by the largest component, so it holds from the
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
