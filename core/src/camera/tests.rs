//! Camera, transform and projection tests, written once per scalar.

use super::*;
use crate::scalar::{I16F16, Scalar};
use crate::test_util::Rng;
use crate::transform::{Euler, Pose};

fn v3<T: Scalar>(x: f64, y: f64, z: f64) -> Vec3<T> {
    Vec3::new(T::from_f64(x), T::from_f64(y), T::from_f64(z))
}

fn dist<T: Scalar>(a: Vec3<T>, b: Vec3<T>) -> f64 {
    let d = a.cast::<f64>() - b.cast::<f64>();
    d.max_abs()
}

fn random_euler<T: Scalar>(rng: &mut Rng) -> Euler<T> {
    let pi = core::f64::consts::PI;
    Euler::new(
        T::from_f64(rng.range(-pi, pi)),
        T::from_f64(rng.range(-1.5, 1.5)),
        T::from_f64(rng.range(-pi, pi)),
    )
}

/// `to_mat3` is the product Ry(yaw)·Rx(pitch)·Rz(roll) (roll first).
fn euler_matrix_is_the_product<T: Scalar>(tol: f64) {
    let mut rng = Rng::new(21);
    for _ in 0..200 {
        let e = random_euler::<T>(&mut rng);
        let prod = Mat3::rotation_y(e.yaw)
            .mul_mat3(&Mat3::rotation_x(e.pitch))
            .mul_mat3(&Mat3::rotation_z(e.roll));
        let m = e.to_mat3();
        for i in 0..3 {
            assert!(dist(m.row(i), prod.row(i)) <= tol, "{}", T::NAME);
        }
    }
}

fn euler_round_trip<T: Scalar>(tol: f64) {
    let mut rng = Rng::new(22);
    for _ in 0..500 {
        let e = random_euler::<T>(&mut rng);
        let back = Euler::from_mat3(&e.to_mat3());
        let d = [
            (back.roll - e.roll).to_f64(),
            (back.pitch - e.pitch).to_f64(),
            (back.yaw - e.yaw).to_f64(),
        ];
        // Near gimbal lock (|pitch| → π/2) roll and yaw lose conditioning
        // as 1/cos(pitch); the random pitches stay within ±1.5 rad.
        let amp = 1.0 / e.pitch.to_f64().cos();
        for x in d {
            assert!(x.abs() <= tol * amp, "{}: {e:?} → {back:?}", T::NAME);
        }
    }
    // Gimbal lock: pitch = π/2, only yaw − roll matters; the matrix is
    // reproduced.
    let e = Euler::new(T::from_f64(0.3), T::PI * T::HALF, T::from_f64(0.5));
    let back = Euler::from_mat3(&e.to_mat3());
    assert_eq!(back.roll, T::ZERO);
    let (m1, m2) = (e.to_mat3(), back.to_mat3());
    for i in 0..3 {
        assert!(
            dist(m1.row(i), m2.row(i)) <= 4.0 * tol,
            "{}: gimbal lock",
            T::NAME
        );
    }
}

/// Camera conventions: zero angles look along −Z with +Y up on screen;
/// positive yaw turns left; positive pitch tilts up.
fn camera_angle_conventions<T: Scalar>(tol: f64) {
    let eye = v3::<T>(1.0, 2.0, 3.0);
    let cam = Camera::from_angles(eye, Euler::ZERO);
    let w2v = cam.world_to_view();
    assert!(dist(w2v.transform_point3(v3(1.0, 2.0, -2.0)), v3(0.0, 0.0, 5.0)) <= tol);
    // World +Y is screen up, i.e. view −Y; world +X is screen right.
    assert!(dist(w2v.transform_vector3(Vec3::Y), -Vec3::Y) <= tol);
    assert!(dist(w2v.transform_vector3(Vec3::X), Vec3::X) <= tol);
    let q = T::PI * T::HALF;
    let yawed = Camera::from_angles(eye, Euler::new(T::ZERO, T::ZERO, q));
    // Looking along world −X after a left turn.
    assert!(dist(yawed.view_axes().2, -Vec3::X) <= tol);
    let pitched = Camera::from_angles(eye, Euler::new(T::ZERO, q, T::ZERO));
    assert!(dist(pitched.view_axes().2, Vec3::Y) <= tol);
    assert_eq!(cam.position(), eye);
}

/// The three constructions agree on the same camera: angles → axes →
/// orthonormal camera, and the general solver camera on the same vectors.
fn camera_forms_agree<T: Scalar>(tol: f64) {
    let mut rng = Rng::new(23);
    for _ in 0..200 {
        let e = random_euler::<T>(&mut rng);
        let eye = v3::<T>(
            rng.range(-10.0, 10.0),
            rng.range(-10.0, 10.0),
            rng.range(-10.0, 10.0),
        );
        let a = Camera::from_angles(eye, e);
        let (r, d, f) = a.view_axes();
        let b = Camera::from_orthonormal(eye, r, d, f).expect("axes of a rotation");
        let (c, diag) =
            Camera::from_vectors(eye, r, d, f).expect("orthonormal is well conditioned");
        assert!(
            diag.rcond.to_f64() > 0.3,
            "orthonormal rcond {:?}",
            diag.rcond
        );
        let p = v3::<T>(
            rng.range(-20.0, 20.0),
            rng.range(-20.0, 20.0),
            rng.range(-20.0, 20.0),
        );
        let pa = a.world_to_view().transform_point3(p);
        assert!(
            dist(pa, b.world_to_view().transform_point3(p)) <= tol,
            "{}",
            T::NAME
        );
        assert!(
            dist(pa, c.world_to_view().transform_point3(p)) <= tol,
            "{}",
            T::NAME
        );
        // look_at with the same eye, a target ahead and the screen's up.
        let l = Camera::look_at(eye, eye + f * T::from_i32(5), -d).expect("valid look_at");
        assert!(
            dist(pa, l.world_to_view().transform_point3(p)) <= tol,
            "{}",
            T::NAME
        );
    }
}

/// A general (sheared, scaled) camera: view coordinates reproduce
/// `P − V = x·u + y·v + z·w`.
fn general_camera_solves_the_matrix_equation<T: Scalar>(tol: f64) {
    let mut rng = Rng::new(24);
    for _ in 0..200 {
        let u = v3::<T>(
            rng.range(0.5, 2.0),
            rng.range(-0.5, 0.5),
            rng.range(-0.5, 0.5),
        );
        let v = v3::<T>(
            rng.range(-0.5, 0.5),
            rng.range(0.5, 2.0),
            rng.range(-0.5, 0.5),
        );
        let w = v3::<T>(
            rng.range(-0.5, 0.5),
            rng.range(-0.5, 0.5),
            rng.range(0.5, 2.0),
        );
        let eye = v3::<T>(
            rng.range(-5.0, 5.0),
            rng.range(-5.0, 5.0),
            rng.range(-5.0, 5.0),
        );
        let (cam, _) = Camera::from_vectors(eye, u, v, w).expect("independent vectors");
        let (x, y, z) = (
            rng.range(-3.0, 3.0),
            rng.range(-3.0, 3.0),
            rng.range(-3.0, 3.0),
        );
        let p = eye + u * T::from_f64(x) + v * T::from_f64(y) + w * T::from_f64(z);
        let got = cam.world_to_view().transform_point3(p);
        assert!(
            dist(got, v3(x, y, z)) <= tol,
            "{}: {got:?} vs ({x}, {y}, {z})",
            T::NAME
        );
    }
}

fn bad_camera_input<T: Scalar>() {
    let o = Vec3::<T>::ZERO;
    let (x, y, z) = (Vec3::<T>::X, Vec3::<T>::Y, Vec3::<T>::Z);
    assert_eq!(Camera::look_at(o, o, y), Err(CameraError::ZeroVector));
    assert_eq!(Camera::look_at(o, z, o), Err(CameraError::ZeroVector));
    assert_eq!(
        Camera::look_at(o, z, z * T::TWO),
        Err(CameraError::UpParallelToView)
    );
    assert_eq!(
        Camera::look_at(o, z, -z),
        Err(CameraError::UpParallelToView)
    );
    assert_eq!(
        Camera::from_orthonormal(o, x, y * T::TWO, z),
        Err(CameraError::NotOrthonormal)
    );
    assert_eq!(
        Camera::from_orthonormal(o, x, x, z),
        Err(CameraError::NotOrthonormal)
    );
    // Right-handed view: right × down = forward. Passing "up" mirrors.
    assert_eq!(
        Camera::from_orthonormal(o, x, -y, z),
        Err(CameraError::LeftHanded)
    );
    assert!(Camera::from_orthonormal(o, x, y, z).is_ok());
    // Parallel and coplanar general vectors.
    assert!(matches!(
        Camera::from_vectors(o, x, x * T::TWO, z),
        Err(CameraError::Degenerate(SolveError::Singular { .. }))
    ));
    assert!(matches!(
        Camera::from_vectors(o, x, y, x + y),
        Err(CameraError::Degenerate(_))
    ));
    // Nearly parallel: 2⁻¹² rad apart is below √ε for fixed and f32 (the
    // reciprocal condition is then ≈ 2⁻¹³), but fine for f64.
    let tilt = v3::<T>(1.0, 1.0 / 4096.0, 0.0);
    let near = Camera::from_vectors(o, x, tilt, z);
    if T::EPSILON.to_f64() > 1e-10 {
        assert!(
            matches!(
                near,
                Err(CameraError::Degenerate(SolveError::IllConditioned { .. }))
            ),
            "{}: {near:?}",
            T::NAME
        );
    } else {
        assert!(near.is_ok());
    }
}

fn projection_matches_its_matrix<T: Scalar>(tol: f64) {
    let mut proj = Projection::<T>::perspective(T::from_i32(200), 320, 240);
    let p = v3::<T>(0.5, -0.25, 2.0);
    let (s, inv_z) = proj.project(p).unwrap();
    assert!((s.x.to_f64() - 210.0).abs() <= tol && (s.y.to_f64() - 95.0).abs() <= tol);
    assert!((inv_z.to_f64() - 0.5).abs() <= tol);
    let m = proj.to_mat4().project_point3(p).unwrap();
    assert!(dist(m, v3(210.0, 95.0, 0.5)) <= tol);
    // At or behind the eye: no projection.
    assert_eq!(proj.project(v3(1.0, 1.0, 0.0)), None);
    assert_eq!(proj.project(v3(1.0, 1.0, -1.0)), None);
    // The focus distance changes at run time.
    proj.set_focus(T::from_i32(100));
    assert!((proj.project(p).unwrap().0.x.to_f64() - 185.0).abs() <= tol);
    let par = Projection::<T>::parallel(T::from_i32(10), 320, 240);
    let (s, z) = par.project(p).unwrap();
    assert!((s.x.to_f64() - 165.0).abs() <= tol && (s.y.to_f64() - 117.5).abs() <= tol);
    assert_eq!(z, p.z);
    assert!(
        dist(
            par.to_mat4().project_point3(p).unwrap(),
            v3(165.0, 117.5, 2.0)
        ) <= tol
    );
    // 90° horizontal field of view on 240 px: focus 120 px.
    let fov = Projection::<T>::perspective_fov(T::PI * T::HALF, 240, 240).unwrap();
    match fov.kind {
        ProjectionKind::Perspective { focus } => {
            assert!((focus.to_f64() - 120.0).abs() <= 1e3 * tol)
        }
        ProjectionKind::Parallel { .. } => unreachable!(),
    }
    assert_eq!(Projection::<T>::perspective_fov(T::PI, 240, 240), None);
    assert_eq!(Projection::<T>::perspective_fov(T::ZERO, 240, 240), None);
}

macro_rules! camera_suite {
    ($name:ident, $t:ty, tol = $tol:expr) => {
        mod $name {
            use super::*;
            #[test]
            fn euler_product() {
                euler_matrix_is_the_product::<$t>($tol);
            }
            #[test]
            fn euler_round_trip() {
                super::euler_round_trip::<$t>($tol);
            }
            #[test]
            fn angle_conventions() {
                camera_angle_conventions::<$t>($tol);
            }
            #[test]
            fn forms_agree() {
                camera_forms_agree::<$t>(64.0 * $tol);
            }
            #[test]
            fn general_camera() {
                general_camera_solves_the_matrix_equation::<$t>(64.0 * $tol);
            }
            #[test]
            fn bad_input() {
                bad_camera_input::<$t>();
            }
            #[test]
            fn projection() {
                projection_matches_its_matrix::<$t>($tol);
            }
        }
    };
}

// tol = 16 steps of the type near 1 (a rotation entry is a sum of products
// of sin/cos, each within one step); transforms of points within ±30 units
// are checked at 64× that.
camera_suite!(f64_suite, f64, tol = 16.0 * f64::EPSILON);
camera_suite!(f32_suite, f32, tol = 16.0 * f32::EPSILON as f64);
camera_suite!(i16f16_suite, I16F16, tol = 16.0 / 65536.0);

#[test]
fn non_finite_camera_input() {
    let nan = Vec3::new(f32::NAN, 0.0, 0.0);
    let (o, x, y, z) = (Vec3::<f32>::ZERO, Vec3::X, Vec3::Y, Vec3::Z);
    assert_eq!(Camera::look_at(nan, z, y), Err(CameraError::NonFinite));
    assert_eq!(
        Camera::from_orthonormal(o, nan, y, z),
        Err(CameraError::NonFinite)
    );
    assert!(matches!(
        Camera::from_vectors(o, x, y, nan),
        Err(CameraError::NonFinite)
    ));
    let inf = Vec3::new(0.0, f32::INFINITY, 0.0);
    assert_eq!(Camera::look_at(o, inf, y), Err(CameraError::NonFinite));
    let p = Projection::<f32>::perspective(200.0, 320, 240);
    assert_eq!(p.project(Vec3::new(f32::NAN, 0.0, 1.0)), None);
    assert_eq!(p.project(Vec3::new(1e38, 0.0, 1e-38)), None);
}

/// Object→view in I16F16 against f64 for a 240×240 scene within ±100
/// units. Bound: each entry of the concatenated rotation carries ≤ 4 steps
/// (products of sin/cos within one step each, plus roundings), each
/// coordinate sums 3 such products with |p| ≤ 100 and the translation:
/// 4·ε·(3·100) + 4·ε·|t| ≤ 2·10⁻² for |t| ≤ 200.
#[test]
fn fixed_object_to_view_agrees_with_f64() {
    let mut rng = Rng::new(25);
    let mut worst: f64 = 0.0;
    for _ in 0..500 {
        let e = random_euler::<f64>(&mut rng);
        let c = random_euler::<f64>(&mut rng);
        let origin = Vec3::new(
            rng.range(-50.0, 50.0),
            rng.range(-50.0, 50.0),
            rng.range(-50.0, 50.0),
        );
        let eye = Vec3::new(
            rng.range(-50.0, 50.0),
            rng.range(-50.0, 50.0),
            rng.range(-50.0, 50.0),
        );
        let pose = Pose::new(origin, e);
        let m64 = Camera::from_angles(eye, c).object_to_view(&pose);
        let pose_fx = Pose::new(
            origin.cast::<I16F16>(),
            Euler::new(
                I16F16::from_f64(e.roll),
                I16F16::from_f64(e.pitch),
                I16F16::from_f64(e.yaw),
            ),
        );
        let cam_fx = Camera::from_angles(
            eye.cast::<I16F16>(),
            Euler::new(
                I16F16::from_f64(c.roll),
                I16F16::from_f64(c.pitch),
                I16F16::from_f64(c.yaw),
            ),
        );
        let mfx = cam_fx.object_to_view(&pose_fx);
        for _ in 0..10 {
            let p = Vec3::new(
                rng.range(-100.0, 100.0),
                rng.range(-100.0, 100.0),
                rng.range(-100.0, 100.0),
            );
            let exact = m64.transform_point3(p);
            let got = mfx.transform_point3(p.cast::<I16F16>()).cast::<f64>();
            worst = worst.max((got - exact).max_abs());
        }
    }
    std::println!("I16F16 object→view max error within ±100 units: {worst:.2e}");
    assert!(worst <= 2e-2, "I16F16 object→view error {worst}");
}

/// Regression: I16F16 perspective projection of far points whose
/// `x·focus` exceeds ±32768 although the pixel is on screen. It used to
/// saturate the product and return a pixel up to ~110 px off with no
/// error; now it divides first and lands within 0.01 px of f64.
#[test]
fn fixed_projection_survives_x_times_focus_overflow() {
    let p16 = Projection::<I16F16>::perspective(I16F16::from_f64(120.0), 240, 240);
    let p64 = Projection::<f64>::perspective(120.0, 240, 240);
    for (x, y, z) in [
        (2000.0, 1500.0, 3000.0),
        (20000.0, -9000.0, 30000.0),
        (-30000.0, 250.0, 32000.0),
    ] {
        let (want, _) = p64.project(Vec3::new(x, y, z)).unwrap();
        let (got, _) = p16.project(v3(x, y, z)).unwrap();
        let e = (got.x.to_f64() - want.x).hypot(got.y.to_f64() - want.y);
        assert!(e < 0.01, "({x}, {y}, {z}): {e} px");
    }
    // Parallel projection whose result is out of range reports it.
    let par = Projection::<I16F16>::parallel(I16F16::from_f64(100.0), 240, 240);
    assert_eq!(par.project(v3(400.0, 0.0, 1.0)), None);
}

/// I16F16 perspective projection with one division per point (`r = f/z`,
/// then `x·r`, `y·r`) stays within 10⁻³ px of f64 for view coordinates
/// up to ±128 and depths 0.5–100, the bound its comment derives.
#[test]
fn fixed_projection_one_division_is_within_a_thousandth_pixel() {
    let p16 = Projection::<I16F16>::perspective(I16F16::from_f64(200.0), 320, 240);
    let mut worst = 0.0f64;
    let mut seed: u64 = 0x5851_f42d_4c95_7f2d;
    let mut next = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    for _ in 0..20_000 {
        let z = 0.5 + 99.5 * next();
        let lim = (0.9 * z).min(128.0);
        let (x, y) = (lim * (2.0 * next() - 1.0), lim * (2.0 * next() - 1.0));
        // The reference projects the point as I16F16 holds it.
        let p = v3(x, y, z);
        let exact = Projection::<f64>::perspective(200.0, 320, 240)
            .project(p.cast::<f64>())
            .unwrap()
            .0;
        let got = p16.project(p).unwrap().0;
        worst = worst.max((got.x.to_f64() - exact.x).hypot(got.y.to_f64() - exact.y));
    }
    std::println!("I16F16 one-division projection: worst {worst:.2e} px");
    assert!(worst < 1e-3, "{worst} px");
}

/// A camera rebuilt from its world→view transform is the same camera,
/// bit for bit; a non-finite entry is refused.
fn from_world_to_view_is_exact<T: Scalar>() {
    let eye = v3::<T>(3.0, 2.5, 5.0);
    let cam = Camera::look_at(eye, v3(0.0, 0.0, 0.0), v3(0.0, 1.0, 0.0)).unwrap();
    let again = Camera::from_world_to_view(cam.position(), *cam.world_to_view()).unwrap();
    assert!(again == cam, "{}", T::NAME);
    let angles = Camera::from_angles(eye, Euler::new(T::ZERO, T::HALF, T::ONE));
    let again = Camera::from_world_to_view(angles.position(), *angles.world_to_view()).unwrap();
    assert!(again == angles, "{}", T::NAME);
}

#[test]
fn from_world_to_view_every_scalar() {
    from_world_to_view_is_exact::<f32>();
    from_world_to_view_is_exact::<f64>();
    from_world_to_view_is_exact::<I16F16>();
}

#[test]
fn from_world_to_view_refuses_non_finite() {
    let cam = Camera::look_at(v3::<f32>(3.0, 2.5, 5.0), Vec3::ZERO, v3(0.0, 1.0, 0.0)).unwrap();
    let mut m = *cam.world_to_view();
    m.matrix.m[1][2] = f32::NAN;
    assert_eq!(
        Camera::from_world_to_view(cam.position(), m),
        Err(CameraError::NonFinite)
    );
    let mut t = *cam.world_to_view();
    t.translation.z = f32::INFINITY;
    assert_eq!(
        Camera::from_world_to_view(cam.position(), t),
        Err(CameraError::NonFinite)
    );
    assert_eq!(
        Camera::from_world_to_view(Vec3::new(f32::NAN, 0.0, 0.0), *cam.world_to_view()),
        Err(CameraError::NonFinite)
    );
}
