//! The stable ray/sphere quadratic against an `f64` reference (computed on
//! the same, already-rounded inputs), plus analytic cases for `f64` itself.

use super::{Rng, is_f64, per_scalar, v3};
use crate::math::Vec3;
use crate::ray::{Ray, Roots, Sphere, SphereError};
use crate::scalar::Scalar;

extern crate std;
use std::println;

type V = [f64; 3];

fn f(v: Vec3<impl Scalar>) -> V {
    [v.x.to_f64(), v.y.to_f64(), v.z.to_f64()]
}
fn dot(a: V, b: V) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// f64 reference: RTG ch. 7 in plain form. Returns the roots and the
/// conditioning factor `r / √(r² − |l|²)` (large near tangency).
fn reference(q: V, d: V, c: V, r: f64) -> (Option<(f64, f64)>, f64) {
    let fv = [q[0] - c[0], q[1] - c[1], q[2] - c[2]];
    let a = dot(d, d);
    let b = dot(fv, d);
    let l = [
        fv[0] - b / a * d[0],
        fv[1] - b / a * d[1],
        fv[2] - b / a * d[2],
    ];
    let ll = dot(l, l).sqrt();
    let disc = a * (r - ll) * (r + ll);
    let cond = r / ((r - ll).abs() * (r + ll)).sqrt().max(1e-300);
    if disc < 0.0 {
        return (None, cond);
    }
    let cc = (dot(fv, fv).sqrt() - r) * (dot(fv, fv).sqrt() + r);
    let qq = -(b + b.signum() * disc.sqrt());
    let (t0, t1) = (cc / qq, qq / a);
    (Some((t0.min(t1), t0.max(t1))), cond)
}

fn as_pair<S: Scalar>(r: Roots<S>) -> Option<(f64, f64)> {
    match r {
        Roots::None => None,
        Roots::One(t) => Some((t.to_f64(), t.to_f64())),
        Roots::Two(a, b) => Some((a.to_f64(), b.to_f64())),
    }
}

/// Checks one case; returns the error in units of `eps·scale`.
fn check<S: Scalar>(q: Vec3<S>, d: Vec3<S>, c: Vec3<S>, r: S, what: &str) -> f64 {
    let sphere = Sphere::new(c, r).unwrap();
    let ray = Ray::new(q, d).unwrap();
    let got = as_pair(sphere.roots(&ray));
    let (want, cond) = reference(f(q), f(d), f(c), r.to_f64());
    let fv = f(q - c);
    let scale = (dot(fv, fv).sqrt() + r.to_f64()) / dot(f(d), f(d)).sqrt();
    let eps = S::EPSILON.to_f64();
    let k = if S::IS_FLOAT { 64.0 } else { 256.0 };
    let allowed = k * eps * scale * (1.0 + cond.min(1.0 / eps.sqrt()));
    match (got, want) {
        (Some(g), Some(w)) => {
            let e = (g.0 - w.0).abs().max((g.1 - w.1).abs());
            assert!(
                e <= allowed,
                "{} {what}: got {g:?} want {w:?}, error {e:e} > {allowed:e}",
                S::NAME
            );
            e / (eps * scale)
        }
        (None, None) => 0.0,
        _ => {
            // A miss/hit disagreement is only acceptable within rounding of
            // tangency.
            assert!(
                cond * cond * eps * 256.0 >= 1.0 || !S::IS_FLOAT,
                "{} {what}: got {got:?} want {want:?} (cond {cond:e})",
                S::NAME
            );
            0.0
        }
    }
}

fn random_against_reference<S: Scalar>() {
    let mut rng = Rng::new(11);
    let span = if S::IS_FLOAT { 100.0 } else { 20.0 };
    let mut worst: f64 = 0.0;
    for _ in 0..3000 {
        let c = v3::<S>(
            rng.range(-span, span),
            rng.range(-span, span),
            rng.range(-span, span),
        );
        let r = S::from_f64(rng.range(0.1, span / 2.0));
        let q = v3::<S>(
            rng.range(-span, span),
            rng.range(-span, span),
            rng.range(-span, span),
        );
        // Aim near the sphere so most rays hit.
        let target = c + v3(
            rng.range(-1.2, 1.2) * r.to_f64(),
            rng.range(-1.2, 1.2) * r.to_f64(),
            rng.range(-1.2, 1.2) * r.to_f64(),
        );
        let Some(d) = crate::ray::checked::sub3(target, q) else {
            continue;
        };
        if d.max_abs() == S::ZERO {
            continue;
        }
        worst = worst.max(check(q, d, c, r, "random"));
    }
    println!(
        "{}: sphere random worst error {worst:.1} eps·scale",
        S::NAME
    );
}

fn grazing_rays<S: Scalar>() {
    let r = if S::IS_FLOAT { 3.0 } else { 2.0 };
    for k in 1..12 {
        let delta = 10f64.powi(-k);
        let h = r * (1.0 - delta);
        for dir in [
            v3::<S>(1.0, 0.0, 0.0),
            v3(1.0, 1e-3, 0.0),
            v3(0.7, 0.1, -0.2),
        ] {
            let q = v3::<S>(-10.0, h, 0.25);
            check(q, dir, v3(0.0, 0.0, 0.25), S::from_f64(r), "grazing");
        }
    }
}

fn distant_small_and_huge<S: Scalar>() {
    // Distant small sphere straight ahead: t = D − r.
    let (dist, r) = if S::IS_FLOAT {
        (1.0e4, 1.0e-2)
    } else {
        (1000.0, 0.5)
    };
    let c = v3::<S>(dist, 1.0, -2.0);
    let q = v3::<S>(0.0, 1.0, -2.0);
    let e = check(q, v3(1.0, 0.0, 0.0), c, S::from_f64(r), "distant small");
    let s = Sphere::new(c, S::from_f64(r)).unwrap();
    let t = s
        .intersect(&Ray::new(q, v3(1.0, 0.0, 0.0)).unwrap(), S::ZERO)
        .unwrap();
    let allowed = 64.0 * S::EPSILON.to_f64() * dist;
    assert!(
        (t.to_f64() - (dist - r)).abs() <= allowed,
        "{} {t:?}",
        S::NAME
    );
    // The same through a pixel-sized direction (not unit), slightly off axis.
    check(
        q,
        v3(200.0, 0.01, 0.0),
        c,
        S::from_f64(r),
        "distant small, long d",
    );
    println!("{}: distant small sphere error {e:.1} eps·scale", S::NAME);

    // Huge sphere: naive b² − 4ac would overflow f32 (r² = 10⁶⁰).
    let big = if is_f64::<S>() {
        1e150
    } else if S::IS_FLOAT {
        1e30
    } else {
        10000.0
    };
    let c = v3::<S>(0.0, 0.0, 2.0 * big);
    let s = Sphere::new(c, S::from_f64(big)).unwrap();
    let ray = Ray::new(Vec3::ZERO, v3(0.0, 0.0, 1.0)).unwrap();
    let t = s.intersect(&ray, S::ZERO).expect("hits a huge sphere");
    assert!(
        (t.to_f64() - big).abs() <= 4.0 * S::EPSILON.to_f64() * big,
        "{} huge: {t:?}",
        S::NAME
    );
    check(Vec3::ZERO, v3(0.3, 0.1, 1.0), c, S::from_f64(big), "huge");
    // Fixed point: the far root (30000) is in range, a bigger one saturates.
    if !S::IS_FLOAT {
        let s = Sphere::new(v3::<S>(0.0, 0.0, 20000.0), S::from_f64(19990.0)).unwrap();
        match s.roots(&ray) {
            Roots::Two(a, b) => {
                assert!((a.to_f64() - 10.0).abs() < 0.5, "{a:?}");
                assert_eq!(b, S::MAX);
            }
            other => panic!("{other:?}"),
        }
    }
}

fn origins_near_surface_and_inside<S: Scalar>() {
    let r = 2.0;
    let c = v3::<S>(1.0, -1.0, 0.5);
    let sphere = Sphere::new(c, S::from_f64(r)).unwrap();
    let n = [0.6, 0.0, 0.8];
    for k in [1.0, 4.0, 64.0, 1024.0] {
        for sign in [-1.0, 1.0] {
            let off = r + sign * k * S::EPSILON.to_f64();
            let q = c + v3(n[0] * off, n[1] * off, n[2] * off);
            for d in [
                v3::<S>(-0.6, 0.0, -0.8),
                v3(0.6, 0.0, 0.8),
                v3(-0.6, 0.3, 0.1),
            ] {
                check(q, d, c, S::from_f64(r), "near surface");
            }
        }
    }
    // Inside: one root behind, one ahead; intersect gives the one ahead.
    let ray = Ray::new(c, v3(0.0, 0.0, 1.0)).unwrap();
    match sphere.roots(&ray) {
        Roots::Two(a, b) => {
            assert!((a.to_f64() + r).abs() <= 8.0 * S::EPSILON.to_f64() * r);
            assert!((b.to_f64() - r).abs() <= 8.0 * S::EPSILON.to_f64() * r);
        }
        other => panic!("{other:?}"),
    }
    let t = sphere.intersect(&ray, S::ZERO).unwrap();
    assert!(t > S::ZERO);
}

fn tangent_miss_and_bad_input<S: Scalar>() {
    let s = Sphere::new(Vec3::<S>::ZERO, S::ONE).unwrap();
    let tangent = Ray::new(v3(-5.0, 1.0, 0.0), Vec3::X).unwrap();
    assert_eq!(s.roots(&tangent), Roots::One(S::from_f64(5.0)));
    let miss = Ray::new(v3(-5.0, 1.5, 0.0), Vec3::X).unwrap();
    assert_eq!(s.roots(&miss), Roots::None);
    let behind = Ray::new(v3(5.0, 0.0, 0.0), Vec3::X).unwrap();
    assert_eq!(s.intersect(&behind, S::ZERO), None);
    assert_eq!(
        Sphere::new(Vec3::<S>::ZERO, S::ZERO).err(),
        Some(SphereError::NonPositiveRadius)
    );
    assert_eq!(
        Sphere::new(Vec3::<S>::ZERO, -S::ONE).err(),
        Some(SphereError::NonPositiveRadius)
    );
    if S::IS_FLOAT {
        let nan = S::from_f64(0.0) / S::from_f64(0.0);
        assert!(Sphere::new(Vec3::<S>::ZERO, nan).is_err());
    }
    // Extreme fixed-point inputs: no panic, a documented answer.
    let far = Sphere::new(Vec3::new(S::MAX, S::MAX, S::MAX), S::MAX).unwrap();
    let ray = Ray::new(Vec3::new(S::MIN, S::MIN, S::MIN), Vec3::X).unwrap();
    let _ = far.roots(&ray);
    let _ = far.intersect(&ray, S::ZERO);
}

/// Fuzz regression (`ray_sphere`): a huge sphere around an origin, hit
/// along a long direction. The far root is `t = 2050` (32 800 / 16), but
/// `t·s` (s = the radius, 32 768) overflows I16F16 before the division by
/// |d|; it was reported saturated as `S::MAX`.
fn long_direction_does_not_saturate_a_representable_root<S: Scalar>() {
    let r = if S::IS_FLOAT {
        32768.0
    } else {
        S::MAX.to_f64()
    };
    let s = Sphere::new(v3::<S>(32.0, 0.5, 0.0), S::from_f64(r)).unwrap();
    let ray = Ray::new(v3(0.0, 0.0, -8.0), v3(16.0, 0.0, 0.0)).unwrap();
    let Roots::Two(t0, t1) = s.roots(&ray) else {
        panic!("the origin is inside: two roots");
    };
    // Reference: the line y = 0, z = −8 meets the sphere at
    // x = 32 ± √(r² − 0.25 − 64).
    let h = (r * r - 0.25 - 64.0).sqrt();
    let want = [(32.0 - h) / 16.0, (32.0 + h) / 16.0];
    for (got, want) in [t0, t1].into_iter().zip(want) {
        let got = got.to_f64();
        assert!(
            (got - want).abs() < 0.05,
            "{}: root {got}, want {want}",
            S::NAME
        );
    }
    // The second fuzz input: |d| ≈ r ≈ 32 768 and a root near 1, where
    // dividing by |d| before multiplying by s lost all but two raw bits
    // in fixed point (root 1 instead of 1.0029).
    let s = Sphere::new(v3::<S>(58.0, 0.25, 0.0), S::from_f64(r)).unwrap();
    let ray = Ray::new(v3(-38.0, 29.0, 59.5), v3(r, -48.0, 0.0)).unwrap();
    let (q, d) = ([-38.0, 29.0, 59.5], [r, -48.0, 0.0]);
    let fv = [q[0] - 58.0, q[1] - 0.25, q[2]];
    let a = d[0] * d[0] + d[1] * d[1];
    let b = fv[0] * d[0] + fv[1] * d[1];
    let c = fv[0] * fv[0] + fv[1] * fv[1] + fv[2] * fv[2] - r * r;
    let far = (-b + (b * b - a * c).sqrt()) / a;
    let t = s.intersect(&ray, S::ZERO).unwrap().to_f64();
    assert!((t - far).abs() < 2e-4, "{}: root {t}, want {far}", S::NAME);
}

/// Fuzz regression (`grid`): a direction of 3.3·10⁻³¹² puts both roots
/// beyond f64's range; `roots` saturates them to MAX, and `intersect`
/// reported a hit at t = MAX that the grid could not reproduce. Now no
/// hit; a root in range is still found.
fn roots_beyond_the_range_are_not_hits<S: Scalar>() {
    let s = Sphere::new(v3::<S>(0.0, 0.0, -0.03125), S::from_f64(0.0234375)).unwrap();
    let tiny = if S::IS_FLOAT {
        S::from_f64(f64::from_bits(674_309_905_821))
    } else {
        S::EPSILON
    };
    let tiny = if S::EPSILON.to_f64() > 1e-10 && S::IS_FLOAT {
        S::from_f64(1e-44)
    } else {
        tiny
    };
    let ray = Ray::new(
        Vec3::new(S::ZERO, S::ZERO, tiny),
        Vec3::new(S::ZERO, S::ZERO, -tiny),
    )
    .unwrap();
    if let Roots::Two(_, t1) = s.roots(&ray) {
        if t1 == S::MAX {
            assert_eq!(s.intersect(&ray, S::ZERO), None, "{}", S::NAME);
        }
    }
    let unit = Ray::new(v3(0.0, 0.0, 1.0), v3(0.0, 0.0, -1.0)).unwrap();
    let t = s.intersect(&unit, S::ZERO).unwrap().to_f64();
    assert!((t - (1.0 + 0.03125 - 0.0234375)).abs() < 1e-3, "{t}");
}

per_scalar!(
    roots_beyond_the_range_are_not_hits,
    long_direction_does_not_saturate_a_representable_root,
    random_against_reference,
    grazing_rays,
    distant_small_and_huge,
    origins_near_surface_and_inside,
    tangent_miss_and_bad_input,
);
