//! Bounding boxes (conservative slab test) and the uniform grid, checked
//! equal to brute force.

use super::{Rng, per_scalar, v3};
use crate::math::Vec3;
use crate::ray::{
    Aabb, AabbError, Bounded, Grid, GridError, Intersect, Mailbox, Ray, Sphere, SurfaceHit,
    Triangle,
};
use crate::scalar::Scalar;

extern crate std;
use std::vec;
use std::vec::Vec;

fn aabb_slab_cases<S: Scalar>() {
    let b = Aabb::new(v3::<S>(-1.0, -1.0, -1.0), v3(1.0, 1.0, 1.0)).unwrap();
    let hit = Ray::new(v3(-5.0, 0.0, 0.0), v3(1.0, 0.0, 0.0)).unwrap();
    let (t0, t1) = b.intersect_range(&hit, S::ZERO, S::MAX).unwrap();
    let e = 64.0 * S::EPSILON.to_f64();
    assert!((t0.to_f64() - 4.0).abs() <= e && (t1.to_f64() - 6.0).abs() <= e);
    // Parallel to a slab, outside it / on its face / inside.
    let out = Ray::new(v3(-5.0, 2.0, 0.0), v3(1.0, 0.0, 0.0)).unwrap();
    assert!(b.intersect_range(&out, S::ZERO, S::MAX).is_none());
    let face = Ray::new(v3(-5.0, 1.0, 1.0), v3(1.0, 0.0, 0.0)).unwrap();
    assert!(b.intersect_range(&face, S::ZERO, S::MAX).is_some());
    // Origin inside; pointing away; t_max before the box.
    let inside = Ray::new(Vec3::ZERO, v3(0.3, -0.2, 1.0)).unwrap();
    let (t0, _) = b.intersect_range(&inside, S::ZERO, S::MAX).unwrap();
    assert_eq!(t0, S::ZERO);
    let away = Ray::new(v3(-5.0, 0.0, 0.0), v3(-1.0, 0.0, 0.0)).unwrap();
    assert!(b.intersect_range(&away, S::ZERO, S::MAX).is_none());
    assert!(b.intersect_range(&hit, S::ZERO, S::TWO).is_none());
    // Errors.
    assert_eq!(
        Aabb::new(v3::<S>(1.0, 0.0, 0.0), Vec3::ZERO).err(),
        Some(AabbError::Empty)
    );
    assert_eq!(Aabb::<S>::from_points(&[]).err(), Some(AabbError::Empty));
    // Extreme values: no panic.
    let huge = Aabb::new(Vec3::splat(S::MIN), Vec3::splat(S::MAX)).unwrap();
    let r = Ray::new(Vec3::splat(S::MAX), Vec3::new(S::EPSILON, -S::ONE, S::ZERO)).unwrap();
    let _ = huge.intersect_range(&r, S::ZERO, S::MAX);
}

/// A box around a shape never loses one of its hits.
fn bounded_equals_unbounded<S: Scalar>() {
    let mut rng = Rng::new(3);
    for _ in 0..2000 {
        let c = v3::<S>(
            rng.range(-5.0, 5.0),
            rng.range(-5.0, 5.0),
            rng.range(-5.0, 5.0),
        );
        let r = S::from_f64(rng.range(0.1, 3.0));
        let s = Sphere::new(c, r).unwrap();
        let b = Bounded::new(Aabb::around_sphere(c, r), s);
        let q = v3::<S>(
            rng.range(-9.0, 9.0),
            rng.range(-9.0, 9.0),
            rng.range(-9.0, 9.0),
        );
        let Ok(ray) = Ray::through(q, c + v3(rng.range(-3.0, 3.0), rng.range(-3.0, 3.0), 0.0))
        else {
            continue;
        };
        assert_eq!(
            b.intersect_ray(&ray, S::ZERO),
            s.intersect_ray(&ray, S::ZERO)
        );
    }
}

#[derive(Clone, Copy, Debug)]
enum Prim<S> {
    Sphere(Sphere<S>),
    Triangle(Triangle<S>),
}

impl<S: Scalar> Intersect<S> for Prim<S> {
    fn intersect_ray(&self, ray: &Ray<S>, t_min: S) -> Option<SurfaceHit<S>> {
        match self {
            Self::Sphere(s) => s.intersect_ray(ray, t_min),
            Self::Triangle(t) => t.intersect_ray(ray, t_min),
        }
    }
}

fn brute<S: Scalar>(ray: &Ray<S>, prims: &[Prim<S>]) -> Option<(usize, S)> {
    let mut best: Option<(usize, S)> = None;
    for (i, p) in prims.iter().enumerate() {
        if let Some(h) = p.intersect_ray(ray, S::ZERO) {
            if best.is_none_or(|(_, t)| h.t < t) {
                best = Some((i, h.t));
            }
        }
    }
    best
}

fn grid_equals_brute_force<S: Scalar>() {
    let mut rng = Rng::new(1987);
    for scene in 0..6 {
        let mut prims = Vec::new();
        let mut boxes = Vec::new();
        let n = 20 + 40 * scene;
        for i in 0..n {
            let c = v3::<S>(
                rng.range(-10.0, 10.0),
                rng.range(-10.0, 10.0),
                rng.range(-10.0, 10.0),
            );
            if i % 7 == 3 {
                // An exact duplicate of the previous primitive: ties.
                prims.push(prims[i - 1]);
                boxes.push(boxes[i - 1]);
            } else if i % 2 == 0 {
                let r = S::from_f64(rng.range(0.2, 2.5));
                prims.push(Prim::Sphere(Sphere::new(c, r).unwrap()));
                boxes.push(Aabb::around_sphere(c, r));
            } else {
                let mut p = [c; 3];
                for v in p.iter_mut().skip(1) {
                    *v = c + v3(
                        rng.range(-4.0, 4.0),
                        rng.range(-4.0, 4.0),
                        rng.range(-4.0, 4.0),
                    );
                }
                prims.push(Prim::Triangle(Triangle::new(p[0], p[1], p[2])));
                boxes.push(Aabb::from_points(&p).unwrap());
            }
        }
        for res in [[1u16, 1, 1], [8, 8, 8], [16, 3, 9], [24, 24, 24]] {
            let cells = res.iter().map(|&r| r as usize).product::<usize>();
            let mut starts = vec![0u32; cells + 1];
            let mut none: [u32; 0] = [];
            let needed = match Grid::build(&boxes, res, &mut starts, &mut none) {
                Err(GridError::ItemStorage { needed }) => needed,
                other => panic!("{other:?}"),
            };
            let mut items = vec![0u32; needed];
            let grid = Grid::build(&boxes, res, &mut starts, &mut items).unwrap();
            let mut stamps = vec![0u32; prims.len()];
            let mut mailbox = Mailbox::new(&mut stamps);
            let mut hits = 0;
            for _ in 0..400 {
                let q = v3::<S>(
                    rng.range(-14.0, 14.0),
                    rng.range(-14.0, 14.0),
                    rng.range(-14.0, 14.0),
                );
                let target = v3::<S>(
                    rng.range(-8.0, 8.0),
                    rng.range(-8.0, 8.0),
                    rng.range(-8.0, 8.0),
                );
                let Ok(ray) = Ray::through(q, target) else {
                    continue;
                };
                let want = brute(&ray, &prims);
                let got = grid
                    .nearest(&ray, S::ZERO, &prims, &mut mailbox)
                    .map(|(i, h)| (i, h.t));
                assert_eq!(got, want, "{} scene {scene} res {res:?}", S::NAME);
                hits += want.is_some() as usize;
            }
            assert!(hits > 50, "the test should mostly hit ({hits})");
        }
    }
}

fn grid_errors<S: Scalar>() {
    let b = [Aabb::around_sphere(Vec3::<S>::ZERO, S::ONE)];
    let mut starts = [0u32; 8];
    let mut items = [0u32; 8];
    assert_eq!(
        Grid::build(&b, [2, 2, 2], &mut starts, &mut items).err(),
        Some(GridError::CellStorage { needed: 9 })
    );
    assert_eq!(
        Grid::<S>::build(&[], [1, 1, 1], &mut starts, &mut items).err(),
        Some(GridError::Empty)
    );
    assert_eq!(
        Grid::build(&b, [0, 1, 1], &mut starts, &mut items).err(),
        Some(GridError::Empty)
    );
    // Mismatched primitive slice: no hit rather than a wrong one.
    let grid = Grid::build(&b, [1, 1, 1], &mut starts, &mut items).unwrap();
    let mut stamps = [0u32; 1];
    let mut mb = Mailbox::new(&mut stamps);
    let ray = Ray::new(v3(0.0, 0.0, -5.0), v3(0.0, 0.0, 1.0)).unwrap();
    let none: [Sphere<S>; 0] = [];
    assert!(grid.nearest(&ray, S::ZERO, &none, &mut mb).is_none());
    let one = [Sphere::new(Vec3::ZERO, S::ONE).unwrap()];
    assert!(grid.nearest(&ray, S::ZERO, &one, &mut mb).is_some());
}

/// Counts calls, to check that mailboxing tests a primitive once per ray
/// although it is listed in many cells.
struct Counting<S> {
    sphere: Sphere<S>,
    calls: core::cell::Cell<usize>,
}

impl<S: Scalar> Intersect<S> for Counting<S> {
    fn intersect_ray(&self, ray: &Ray<S>, t_min: S) -> Option<SurfaceHit<S>> {
        self.calls.set(self.calls.get() + 1);
        self.sphere.intersect_ray(ray, t_min)
    }
}

fn mailbox_tests_each_primitive_once<S: Scalar>() {
    let big = Sphere::new(Vec3::<S>::ZERO, S::from_f64(5.0)).unwrap();
    let small = Sphere::new(v3::<S>(0.0, 0.0, 20.0), S::ONE).unwrap();
    let prims = [
        Counting {
            sphere: big,
            calls: core::cell::Cell::new(0),
        },
        Counting {
            sphere: small,
            calls: core::cell::Cell::new(0),
        },
    ];
    let boxes = [
        Aabb::around_sphere(big.center(), big.radius()),
        Aabb::around_sphere(small.center(), small.radius()),
    ];
    let mut starts = vec![0u32; 16 * 16 * 16 + 1];
    let mut items = vec![0u32; 8192];
    let grid = Grid::build(&boxes, [16, 16, 16], &mut starts, &mut items).unwrap();
    let mut stamps = [0u32; 2];
    let mut mb = Mailbox::new(&mut stamps);
    // Along the axis from inside the big sphere: its far side is hit many
    // cells later; the small sphere beyond must not be reported instead.
    let ray = Ray::new(v3(0.0, 0.0, -0.5), v3(0.0, 0.0, 1.0)).unwrap();
    let (i, h) = grid.nearest(&ray, S::ZERO, &prims, &mut mb).unwrap();
    assert_eq!(i, 0);
    assert!((h.t.to_f64() - 5.5).abs() < 1e3 * S::EPSILON.to_f64());
    assert_eq!(prims[0].calls.get(), 1, "mailbox: one test per ray");
    assert_eq!(
        prims[1].calls.get(),
        0,
        "early exit before the small sphere"
    );
    // A second ray: the mailbox resets per ray.
    let (i, _) = grid
        .nearest(&ray, S::from_f64(6.0), &prims, &mut mb)
        .unwrap();
    assert_eq!(i, 1);
    assert_eq!(prims[0].calls.get(), 2);
}

per_scalar!(
    mailbox_tests_each_primitive_once,
    aabb_slab_cases,
    bounded_equals_unbounded,
    grid_equals_brute_force,
    grid_errors,
);
