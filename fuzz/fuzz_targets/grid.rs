//! `grid`: the uniform grid (`ray::Grid`, 3D DDA with mailboxing and early
//! exit, in caller storage) in f32, f64 and I16F16 on random small scenes
//! of spheres and triangles (grid coordinates, or any values including
//! huge, tiny and flat scenes), with resolutions 1..=8 per axis.
//!
//! Oracle: brute force over the same primitives (each one's own
//! `intersect_ray`, nearest t, lower index on equal t): for every ray the
//! grid returns exactly the same (index, t) — unless the nearest hit lies
//! outside its own primitive's box (widened by the grid's 1/64-cell
//! margin), which rounding can cause and the grid documents as a possible
//! miss; then whatever the grid returns must be a real hit no farther
//! than the nearest in-box hit, and it may return nothing only if no hit
//! is in its box. Fixed-point rays that cross a cell in fewer than 64
//! steps of t (a documented precondition of the grid) and scenes or rays
//! with arbitrary f64 values (huge, tiny: documented precision limit) are
//! only checked not to panic; the oracle covers small scenes on a grid of
//! 1/8 units at scales 2⁻³..2². Storage: `ItemStorage`
//! reports the exact size needed (a second build with that much succeeds);
//! the mailbox may be shorter than the primitive count (documented: those
//! primitives are simply tested once per cell).
#![no_main]

mod common;

use arbitrary::Arbitrary;
use common::{Kind, Num};
use libfuzzer_sys::fuzz_target;
use sightline::math::Vec3;
use sightline::ray::{
    Aabb, Grid, GridError, Intersect, Mailbox, Ray, Sphere, SurfaceHit, Triangle,
};
use sightline::scalar::{I16F16, Scalar};

#[derive(Arbitrary, Debug, Clone, Copy)]
enum P3 {
    Grid([i8; 3]),
    Wild([Num; 3]),
}

#[derive(Arbitrary, Debug)]
enum Spec {
    Sphere(P3, u8),
    Triangle(P3, P3, P3),
    /// A copy of an earlier primitive (ties).
    Copy(u8),
}

#[derive(Arbitrary, Debug)]
struct Input {
    kind: Kind,
    res: [u8; 3],
    scale: u8,
    mailbox_short: u8,
    prims: Vec<Spec>,
    rays: Vec<(P3, P3)>,
    t_min: i8,
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

fn run<T: Scalar>(input: &Input) {
    let sc = 2f64.powi((input.scale % 6) as i32 - 3);
    let p3 = |p: P3| -> Vec3<T> {
        match p {
            P3::Grid(g) => Vec3::new(
                T::from_f64(g[0] as f64 * sc / 8.0),
                T::from_f64(g[1] as f64 * sc / 8.0),
                T::from_f64(g[2] as f64 * sc / 8.0),
            ),
            // Extreme values only as a no-panic check (see `wild` below).
            P3::Wild(n) => common::v3(n),
        }
    };
    let mut prims: Vec<Prim<T>> = Vec::new();
    let mut boxes: Vec<Aabb<T>> = Vec::new();
    for s in input.prims.iter().take(12) {
        match *s {
            Spec::Sphere(c, r) => {
                let (c, r) = (p3(c), T::from_f64((r as f64 + 1.0) * sc / 32.0));
                if let Ok(sp) = Sphere::new(c, r) {
                    prims.push(Prim::Sphere(sp));
                    boxes.push(Aabb::around_sphere(c, r));
                }
            }
            Spec::Triangle(a, b, c) => {
                let v = [p3(a), p3(b), p3(c)];
                if let Ok(bx) = Aabb::from_points(&v) {
                    prims.push(Prim::Triangle(Triangle::new(v[0], v[1], v[2])));
                    boxes.push(bx);
                }
            }
            Spec::Copy(i) => {
                if !prims.is_empty() {
                    let i = i as usize % prims.len();
                    prims.push(prims[i]);
                    boxes.push(boxes[i]);
                }
            }
        }
    }
    if prims.is_empty() {
        return;
    }
    let res = input.res.map(|r| (r % 8 + 1) as u16);
    let cells = res.iter().map(|&r| r as usize).product::<usize>();
    let mut starts = vec![0u32; cells + 1];
    let needed = match Grid::build(&boxes, res, &mut starts, &mut []) {
        Err(GridError::ItemStorage { needed }) => needed,
        Ok(_) => 0,
        Err(e) => panic!("{}: {e:?}", T::NAME),
    };
    let mut items = vec![0u32; needed];
    let grid =
        Grid::build(&boxes, res, &mut starts, &mut items).expect("storage sized from ItemStorage");
    let short = (input.mailbox_short as usize % 4).min(prims.len());
    let mut stamps = vec![0u32; prims.len() - short];
    let mut mailbox = Mailbox::new(&mut stamps);
    let t_min = T::from_f64(input.t_min as f64 / 16.0);
    let wild_p = |p: &P3| matches!(p, P3::Wild(_));
    let wild_scene = input.prims.iter().take(12).any(|s| match s {
        Spec::Sphere(c, _) => wild_p(c),
        Spec::Triangle(a, b, c) => wild_p(a) || wild_p(b) || wild_p(c),
        Spec::Copy(_) => false,
    });
    for &(q, through) in input.rays.iter().take(8) {
        let wild = wild_scene || wild_p(&q) || wild_p(&through);
        let Ok(ray) = Ray::through(p3(q), p3(through)) else {
            continue;
        };
        // Brute force; each hit flagged whether its point (in f64) lies in
        // the primitive's box widened by the grid's 1/64-cell margin.
        let lo = grid.bounds().min();
        let hi = grid.bounds().max();
        let cell: [f64; 3] = [0, 1, 2].map(|k| {
            let e = common::f3(hi)[k] - common::f3(lo)[k];
            if e > 0.0 { e / res[k] as f64 } else { 1.0 }
        });
        let (q, d) = (common::f3(ray.origin()), common::f3(ray.dir()));
        let mut want: Option<(usize, T)> = None;
        let mut want_in_box: Option<(usize, T)> = None;
        for (i, p) in prims.iter().enumerate() {
            if let Some(h) = p.intersect_ray(&ray, t_min) {
                if want.is_none_or(|(_, t)| h.t < t) {
                    want = Some((i, h.t));
                }
                let t = h.t.to_f64();
                let (bl, bh) = (common::f3(boxes[i].min()), common::f3(boxes[i].max()));
                let in_box = (0..3).all(|k| {
                    let x = q[k] + t * d[k];
                    let m = cell[k] / 64.0;
                    x >= bl[k] - m && x <= bh[k] + m
                });
                if in_box && want_in_box.is_none_or(|(_, t)| h.t < t) {
                    want_in_box = Some((i, h.t));
                }
            }
        }
        let got = grid
            .nearest(&ray, t_min, &prims, &mut mailbox)
            .map(|(i, h)| (i, h.t));
        // Fixed point: the documented precondition of the margins, at
        // least 64 steps of t per cell on every axis with d_k ≠ 0.
        let coarse = !T::IS_FLOAT
            && (0..3).any(|k| d[k] != 0.0 && cell[k] / d[k].abs() < 64.0 * T::EPSILON.to_f64());
        if coarse || wild {
            // Outside the grid's documented precision (fixed point: too few
            // t steps per cell; floats: a scene spanning the whole range,
            // where distinct hits round to equal t): no panic only.
            let _ = grid.nearest(&ray, t_min, &prims, &mut mailbox);
            continue;
        }
        if want == want_in_box {
            assert_eq!(
                got,
                want,
                "{}: grid vs brute force, ray {ray:?}, res {res:?}",
                T::NAME
            );
        } else {
            // The nearest hit lies outside its primitive's box (rounding):
            // the grid may miss it (documented), but anything it returns is
            // a real hit of that primitive, no farther than the nearest
            // in-box hit.
            if let Some((i, t)) = got {
                assert_eq!(
                    prims[i].intersect_ray(&ray, t_min).map(|h| h.t),
                    Some(t),
                    "{}",
                    T::NAME
                );
                if let Some((_, tb)) = want_in_box {
                    assert!(
                        t <= tb,
                        "{}: grid {got:?} beyond the nearest in-box hit {want_in_box:?}",
                        T::NAME
                    );
                }
            } else {
                assert_eq!(want_in_box, None, "{}: grid missed an in-box hit", T::NAME);
            }
        }
    }
}

fuzz_target!(|input: Input| {
    match input.kind {
        Kind::F32 => run::<f32>(&input),
        Kind::F64 => run::<f64>(&input),
        Kind::Fixed => run::<I16F16>(&input),
    }
});
