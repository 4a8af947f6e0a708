//! Bounding spheres: Ritter's construction against an f64 re-implementation
//! and exact containment, the conservative ray test against the exact f64
//! answer, and a sphere-bounded shape returning exactly the unbounded hits.

use super::{Rng, per_scalar, v3};
use crate::math::Vec3;
use crate::ray::{
    Bounded, BoundingSphere, BoundingSphereError, BoundingVolume, Intersect, Ray, Triangle,
};
use crate::scalar::Scalar;

extern crate std;
use std::vec::Vec;

type P = [f64; 3];

fn d2(a: P, b: P) -> f64 {
    (0..3).map(|k| (a[k] - b[k]).powi(2)).sum()
}

/// Ritter's algorithm in f64, written independently of the generic one.
fn ritter_f64(pts: &[P]) -> (P, f64) {
    let far = |from: P| {
        *pts.iter()
            .max_by(|a, b| d2(**a, from).total_cmp(&d2(**b, from)))
            .unwrap()
    };
    let y = far(pts[0]);
    let z = far(y);
    let mut c = [0.0; 3];
    for k in 0..3 {
        c[k] = (y[k] + z[k]) / 2.0;
    }
    let mut r = d2(y, z).sqrt() / 2.0;
    for &p in pts {
        let d = d2(p, c).sqrt();
        if d > r {
            let nr = (r + d) / 2.0;
            for k in 0..3 {
                c[k] += (p[k] - c[k]) * (nr - r) / d;
            }
            r = nr;
        }
    }
    (c, r)
}

fn to_f64<S: Scalar>(v: Vec3<S>) -> P {
    [v.x.to_f64(), v.y.to_f64(), v.z.to_f64()]
}

/// Every point inside (exactly, in f64 on the values held), and the
/// sphere close to the f64 construction on the same points.
fn from_points_contains_and_matches_f64<S: Scalar>() {
    let mut rng = Rng::new(1990);
    let eps = S::EPSILON.to_f64();
    for case in 0..300 {
        let n = 1 + case % 97;
        let spread = [0.01, 1.0, 50.0][case % 3];
        let center = [rng.range(-50.0, 50.0), rng.range(-50.0, 50.0), 0.0];
        let pts: Vec<Vec3<S>> = (0..n)
            .map(|i| {
                if case % 7 == 0 && i % 2 == 1 {
                    // Duplicates and collinear points.
                    v3(center[0] + i as f64 * spread, center[1], center[2])
                } else {
                    v3(
                        center[0] + rng.range(-spread, spread),
                        center[1] + rng.range(-spread, spread),
                        center[2] + rng.range(-spread, spread),
                    )
                }
            })
            .collect();
        let b = BoundingSphere::from_points(&pts).unwrap();
        let (c, r) = (to_f64(b.center()), b.radius().to_f64());
        for p in &pts {
            let d = d2(to_f64(*p), c).sqrt();
            assert!(
                d <= r,
                "{} case {case}: point at {d} outside r = {r}",
                S::NAME
            );
        }
        let held: Vec<P> = pts.iter().map(|&p| to_f64(p)).collect();
        let (c64, r64) = ritter_f64(&held);
        // Same algorithm, so the same sphere up to the scalar's rounding of
        // distances and the center (a few ulps of the coordinates' size).
        let scale = held.iter().flatten().fold(1.0f64, |m, x| m.max(x.abs()));
        let tol = 64.0 * eps * scale * (n as f64).sqrt();
        assert!(
            (r - r64).abs() <= tol,
            "{} case {case}: r {r} vs {r64}",
            S::NAME
        );
        assert!(d2(c, c64).sqrt() <= tol, "{} case {case}: center", S::NAME);
    }
}

fn errors<S: Scalar>() {
    assert_eq!(
        BoundingSphere::<S>::from_points(&[]),
        Err(BoundingSphereError::Empty)
    );
    assert_eq!(
        BoundingSphere::new(Vec3::<S>::ZERO, -S::ONE),
        Err(BoundingSphereError::NonFinite)
    );
    if S::IS_FLOAT {
        let nan = (-S::ONE).sqrt();
        assert_eq!(
            BoundingSphere::from_points(&[Vec3::new(nan, S::ZERO, S::ZERO)]),
            Err(BoundingSphereError::NonFinite)
        );
    } else {
        // Differences beyond the fixed-point range are reported.
        let far = [Vec3::splat(S::MIN), Vec3::splat(S::MAX)];
        assert_eq!(
            BoundingSphere::from_points(&far),
            Err(BoundingSphereError::Overflow)
        );
    }
    // One point: radius of a few ulps, the point inside.
    let p = v3::<S>(1.5, -2.0, 3.25);
    let b = BoundingSphere::from_points(&[p]).unwrap();
    assert_eq!(b.center(), p);
    assert!(b.radius() > S::ZERO && b.radius().to_f64() < 1e-3);
}

/// The ray test never rejects a ray the exact f64 test accepts, and it
/// does reject clear misses (the line further than r + 1e-3·s, or the
/// sphere behind the origin by that margin).
fn ray_test_is_conservative_and_tight<S: Scalar>() {
    let mut rng = Rng::new(2019);
    let (mut hits, mut misses) = (0, 0);
    for case in 0..20000 {
        let r = [0.01, 0.5, 3.0, 40.0][case % 4];
        let c = [
            rng.range(-60.0, 60.0),
            rng.range(-60.0, 60.0),
            rng.range(-60.0, 60.0),
        ];
        let Ok(b) = BoundingSphere::new(v3::<S>(c[0], c[1], c[2]), S::from_f64(r)) else {
            continue;
        };
        // Aim near the sphere: inside, at the edge, or past it.
        let aim = rng.range(0.0, 2.0) * r;
        let q = [
            rng.range(-80.0, 80.0),
            rng.range(-80.0, 80.0),
            rng.range(-80.0, 80.0),
        ];
        let dir = [
            c[0] + rng.range(-aim, aim) - q[0],
            c[1] + rng.range(-aim, aim) - q[1],
            c[2] + rng.range(-aim, aim) - q[2],
        ];
        let dir = if case % 5 == 0 { dir.map(|x| -x) } else { dir };
        let Ok(ray) = Ray::new(v3::<S>(q[0], q[1], q[2]), v3(dir[0], dir[1], dir[2])) else {
            continue;
        };
        // Exact answer on the values actually held.
        let (q, d, c, r) = (
            to_f64(ray.origin()),
            to_f64(ray.dir()),
            to_f64(b.center()),
            b.radius().to_f64(),
        );
        let dl = d2(d, [0.0; 3]).sqrt();
        let u = d.map(|x| x / dl);
        let f = [q[0] - c[0], q[1] - c[1], q[2] - c[2]];
        let bb: f64 = (0..3).map(|k| f[k] * u[k]).sum();
        let line = (d2(f, [0.0; 3]) - bb * bb).max(0.0).sqrt();
        let inside = d2(f, [0.0; 3]).sqrt() <= r;
        let exact = line <= r && (inside || bb <= 0.0);
        let got = b.may_hit(&ray, S::ZERO);
        if exact {
            assert!(got, "{} case {case}: rejected a hit", S::NAME);
            hits += 1;
        }
        let s = d2(f, [0.0; 3]).sqrt().max(r);
        let margin = 1e-3 * s;
        let clear_miss = line > r + margin || (d2(f, [0.0; 3]).sqrt() > r + margin && bb > margin);
        if clear_miss {
            assert!(!got, "{} case {case}: accepted a clear miss", S::NAME);
            misses += 1;
        }
    }
    assert!(hits > 3000 && misses > 3000, "{hits} hits, {misses} misses");
}

/// A triangle behind its Ritter sphere returns exactly its own hits.
fn sphere_bounded_equals_unbounded<S: Scalar>() {
    let mut rng = Rng::new(5);
    for _ in 0..3000 {
        let p = |rng: &mut Rng| {
            v3::<S>(
                rng.range(-4.0, 4.0),
                rng.range(-4.0, 4.0),
                rng.range(-4.0, 4.0),
            )
        };
        let t = Triangle {
            v: [p(&mut rng), p(&mut rng), p(&mut rng)],
        };
        let b = Bounded::new(BoundingSphere::from_points(&t.v).unwrap(), t);
        let Ok(ray) = Ray::through(
            v3(rng.range(-9.0, 9.0), rng.range(-9.0, 9.0), 9.0),
            t.v[rng.int(0, 2) as usize] + v3(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), 0.0),
        ) else {
            continue;
        };
        assert_eq!(
            b.intersect_ray(&ray, S::ZERO),
            t.intersect_ray(&ray, S::ZERO)
        );
    }
}

per_scalar!(
    from_points_contains_and_matches_f64,
    errors,
    ray_test_is_conservative_and_tight,
    sphere_bounded_equals_unbounded,
);
