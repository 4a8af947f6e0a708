//! Rays, planes and the ray-casting camera.

use super::{Rng, per_scalar, v3};
use crate::camera::{Camera, Projection};
use crate::math::Vec3;
use crate::ray::{InclusionTest, Plane, PlaneError, Ray, RayCamera, RayCameraError, RayError};

extern crate std;
use crate::scalar::Scalar;
use crate::transform::Euler;

fn tol<S: Scalar>(k: f64) -> f64 {
    k * S::EPSILON.to_f64()
}

fn ray_rejects_bad_input<S: Scalar>() {
    let z = Vec3::<S>::ZERO;
    assert_eq!(Ray::new(z, z).err(), Some(RayError::ZeroDirection));
    assert_eq!(
        Ray::<S>::through(Vec3::X, Vec3::X).err(),
        Some(RayError::ZeroDirection)
    );
    if S::IS_FLOAT {
        let nan = S::from_f64(0.0) / S::from_f64(0.0);
        let inf = S::ONE / S::ZERO;
        assert_eq!(
            Ray::new(z, Vec3::new(nan, S::ONE, S::ZERO)).err(),
            Some(RayError::NonFinite)
        );
        assert_eq!(
            Ray::new(Vec3::new(inf, S::ZERO, S::ZERO), Vec3::X).err(),
            Some(RayError::NonFinite)
        );
    }
    let r = Ray::new(z, Vec3::<S>::X).unwrap();
    assert_eq!(r.at(S::TWO), Vec3::new(S::TWO, S::ZERO, S::ZERO));
}

fn plane_parallel_and_in_plane_miss<S: Scalar>() {
    let p = Plane::new(Vec3::<S>::ZERO, Vec3::Y).unwrap();
    // Parallel above the plane, and lying in it: no hit, no NaN, no panic.
    let above = Ray::new(v3(0.0, 1.0, 0.0), Vec3::X).unwrap();
    let inside = Ray::new(v3(3.0, 0.0, -2.0), v3(1.0, 0.0, 1.0)).unwrap();
    assert_eq!(p.intersect(&above, S::ZERO), None);
    assert_eq!(p.intersect(&inside, S::ZERO), None);
    // A plain hit, and one behind the origin.
    let down = Ray::new(v3(0.5, 2.0, 0.0), v3(0.0, -1.0, 0.0)).unwrap();
    assert_eq!(p.intersect(&down, S::ZERO), Some(S::TWO));
    let up = Ray::new(v3(0.5, 2.0, 0.0), v3(0.0, 1.0, 0.0)).unwrap();
    assert_eq!(p.intersect(&up, S::ZERO), None);
    // A nearly parallel ray whose hit is beyond the range: no hit.
    let tiny = S::EPSILON;
    let grazing = Ray::new(v3(0.0, 1000.0, 0.0), Vec3::new(S::ONE, -tiny, S::ZERO)).unwrap();
    if let Some(t) = p.intersect(&grazing, S::ZERO) {
        assert!(t.is_finite() && t > S::ZERO);
    }
    // Fixed point: saturated inputs must not wrap into a bogus hit.
    let big = Ray::new(
        Vec3::new(S::MAX, S::MAX, S::MAX),
        Vec3::new(S::MIN, S::MIN, S::MIN),
    )
    .unwrap();
    let _ = p.intersect(&big, S::ZERO);
}

fn plane_from_points<S: Scalar>() {
    let a = v3::<S>(0.0, 0.0, 1.0);
    let b = v3::<S>(1.0, 0.0, 1.0);
    let c = v3::<S>(0.0, 1.0, 1.0);
    let p = Plane::from_points(a, b, c).unwrap();
    assert!((p.normal().z.to_f64() - 1.0).abs() <= tol::<S>(4.0));
    assert_eq!(
        Plane::from_points(a, b, b).err(),
        Some(PlaneError::Collinear)
    );
    assert_eq!(
        Plane::from_points(a, b, v3(2.0, 0.0, 1.0)).err(),
        Some(PlaneError::Collinear)
    );
    assert_eq!(
        Plane::new(a, Vec3::ZERO).err(),
        Some(PlaneError::ZeroNormal)
    );
    let d = p.signed_distance(v3(5.0, -3.0, 3.0)).unwrap();
    assert!((d.to_f64() - 2.0).abs() <= tol::<S>(16.0));
}

/// The ray for pixel (i, j) passes through every world point the raster
/// path projects to the center of that pixel, for the same camera.
fn camera_rays_match_projection<S: Scalar>() {
    let mut rng = Rng::new(5);
    let (w, h) = (64u16, 48u16);
    let proj = Projection::perspective(S::from_f64(40.0), w, h);
    for _ in 0..20 {
        let cam = Camera::from_angles(
            v3(
                rng.range(-2.0, 2.0),
                rng.range(-2.0, 2.0),
                rng.range(-2.0, 2.0),
            ),
            Euler::new(
                S::from_f64(rng.range(-1.0, 1.0)),
                S::from_f64(rng.range(-1.0, 1.0)),
                S::from_f64(rng.range(-3.0, 3.0)),
            ),
        );
        let rc = RayCamera::from_camera(&cam, &proj, w, h).unwrap();
        for _ in 0..10 {
            let (i, j) = (
                rng.int(0, w as i64 - 1) as u16,
                rng.int(0, h as i64 - 1) as u16,
            );
            let ray = rc.pixel_ray(i, j).unwrap();
            let k = S::from_f64(rng.range(0.05, 0.3));
            let world = ray.at(k);
            let view = cam.world_to_view().transform_point3(world);
            let (s, _) = proj.project(view).unwrap();
            let e = 1e4 * S::EPSILON.to_f64();
            assert!(
                (s.x.to_f64() - (i as f64 + 0.5)).abs() <= e,
                "{} {s:?} vs ({i}, {j})",
                S::NAME
            );
            assert!(
                (s.y.to_f64() - (j as f64 + 0.5)).abs() <= e,
                "{} {s:?} vs ({i}, {j})",
                S::NAME
            );
        }
        // Column rays lie on the horizon row through the projection center.
        for (i, r) in rc.column_rays() {
            let r = r.unwrap();
            let view = cam.world_to_view().transform_point3(r.at(S::from_f64(0.1)));
            let (s, _) = proj.project(view).unwrap();
            let e = 1e4 * S::EPSILON.to_f64();
            assert!((s.x.to_f64() - (i as f64 + 0.5)).abs() <= e);
            assert!((s.y.to_f64() - h as f64 / 2.0).abs() <= e);
        }
    }
}

/// The chapter's form: pixel (i, j) maps to O + (i + ½ − w/2)·u + (j + ½ − h/2)·v.
fn chapter_camera_pixel_centers<S: Scalar>() {
    let o = v3::<S>(0.0, 0.0, 10.0);
    let rc = RayCamera::new(o, Vec3::X, v3(0.0, -1.0, 0.0), Vec3::ZERO, 4, 2).unwrap();
    let r = rc.pixel_ray(0, 0).unwrap();
    assert_eq!(r.origin(), Vec3::ZERO);
    assert_eq!(r.dir(), v3(-1.5, 0.5, 10.0));
    let r = rc.pixel_ray(3, 1).unwrap();
    assert_eq!(r.dir(), v3(1.5, -0.5, 10.0));
    assert_eq!(
        RayCamera::new(o, Vec3::ZERO, Vec3::X, Vec3::ZERO, 4, 2).err(),
        Some(RayCameraError::ZeroVector)
    );
    let par = Projection::parallel(S::ONE, 4, 2);
    let cam = Camera::from_angles(Vec3::ZERO, Euler::ZERO);
    assert_eq!(
        RayCamera::from_camera(&cam, &par, 4, 2).err(),
        Some(RayCameraError::NotPerspective)
    );
}

per_scalar!(
    ray_rejects_bad_input,
    plane_parallel_and_in_plane_miss,
    plane_from_points,
    camera_rays_match_projection,
    chapter_camera_pixel_centers,
    extreme_inputs_never_panic_or_nan,
    plane_exactly_in_plane_rays_miss,
);

/// Every constructor and intersection on extreme and non-finite inputs:
/// no panic, and any reported `t` is finite and above `t_min`.
fn extreme_inputs_never_panic_or_nan<S: Scalar>() {
    use crate::ray::{Aabb, Mesh, Polygon, Sphere, Triangle};
    let mut vals = std::vec![
        S::ZERO,
        S::EPSILON,
        -S::EPSILON,
        S::ONE,
        -S::ONE,
        S::MAX,
        S::MIN,
        S::from_f64(1e3),
        S::from_f64(-7.25),
    ];
    if S::IS_FLOAT {
        vals.push(S::from_f64(0.0) / S::from_f64(0.0));
        vals.push(S::ONE / S::from_f64(0.0));
        vals.push(S::from_f64(1e-40));
    }
    let mut rng = Rng::new(404);
    let pick = |rng: &mut Rng| vals[rng.int(0, vals.len() as i64 - 1) as usize];
    let ok = |t: Option<S>| {
        if let Some(t) = t {
            assert!(t.is_finite() && t > S::ZERO, "{} bad t {t:?}", S::NAME);
        }
    };
    for _ in 0..20000 {
        let mut v = || Vec3::new(pick(&mut rng), pick(&mut rng), pick(&mut rng));
        let (q, d, a, b, c) = (v(), v(), v(), v(), v());
        let r = pick(&mut rng);
        let Ok(ray) = Ray::new(q, d) else {
            continue;
        };
        if let Ok(p) = Plane::new(a, b) {
            ok(p.intersect(&ray, S::ZERO));
        }
        if let Ok(p) = Plane::from_points(a, b, c) {
            ok(p.intersect(&ray, S::ZERO));
        }
        if let Ok(s) = Sphere::new(a, r) {
            ok(s.intersect(&ray, S::ZERO));
            let _ = s.roots(&ray);
        }
        ok(Triangle::new(a, b, c).intersect(&ray, S::ZERO).map(|h| h.t));
        let verts = [a, b, c];
        if let Ok(m) = Mesh::new(&verts, &[[0, 1, 2]]) {
            ok(m.intersect(&ray, S::ZERO).map(|h| h.1.t));
        }
        if let Ok(p) = Polygon::<S, 4>::new(&[a, b, c, q]) {
            for t in [
                InclusionTest::Crossing,
                InclusionTest::HalfPlane,
                InclusionTest::Fan,
            ] {
                ok(p.clone().with_test(t).intersect(&ray, S::ZERO));
            }
        }
        if let Ok(bx) = Aabb::new(a, b) {
            if let Some((t0, t1)) = bx.intersect_range(&ray, S::ZERO, S::MAX) {
                assert!(t0 <= t1);
            }
        }
        if let Ok(cam) = RayCamera::new(a, b, c, q, 8, 8) {
            let _ = cam.pixel_ray(3, 5);
            let _ = cam.column_ray(7);
        }
    }
}

/// Item 8 of issue 14: rays lying exactly in the plane (and rays exactly
/// parallel to it) never hit. The normal n is an integer vector of
/// generic direction, the direction is d = n × w and the origin
/// P + n × w₂ for integer w, w₂, all exactly representable in every type;
/// n·d = 0 is checked in i128. Normalizing n rounds, so n̂·d is not 0.
fn plane_exactly_in_plane_rays_miss<S: Scalar>() {
    let mut rng = Rng::new(0x1A_B1A7);
    let cross = |a: [i64; 3], b: [i64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let v = |a: [i64; 3]| {
        Vec3::new(
            S::from_i32(a[0] as i32),
            S::from_i32(a[1] as i32),
            S::from_i32(a[2] as i32),
        )
    };
    let mut hits = 0;
    let mut cases = 0;
    for _ in 0..300 {
        let mut r = || rng.int(-40, 40);
        let n = [r(), r(), r()];
        let (w, w2) = ([r(), r(), r()], [r(), r(), r()]);
        let p = [r(), r(), r()];
        let (d, off) = (cross(n, w), cross(n, w2));
        let dot =
            |a: [i64; 3], b: [i64; 3]| (0..3).map(|i| a[i] as i128 * b[i] as i128).sum::<i128>();
        if n == [0, 0, 0] || d == [0, 0, 0] {
            continue;
        }
        assert_eq!(dot(n, d), 0);
        assert_eq!(dot(n, off), 0);
        let plane = Plane::new(v(p), v(n)).unwrap();
        let o = [p[0] + off[0], p[1] + off[1], p[2] + off[2]];
        // In the plane, and parallel at distance |n|² above it.
        for origin in [o, [o[0] + n[0], o[1] + n[1], o[2] + n[2]]] {
            let ray = Ray::new(v(origin), v(d)).unwrap();
            cases += 1;
            if let Some(t) = plane.intersect(&ray, S::from_f64(-1e4)) {
                hits += 1;
                std::println!("{}: n {n:?} d {d:?} origin {origin:?}: t = {t:?}", S::NAME);
            }
        }
    }
    std::println!("{}: {hits} of {cases} in-plane/parallel rays hit", S::NAME);
    assert_eq!(hits, 0, "{}: in-plane or parallel rays hit", S::NAME);
}
