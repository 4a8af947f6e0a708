//! `clip`: Sutherland–Hodgman clipping (`pipeline::Frustum::clip`) in f32,
//! f64 and I16F16, against arbitrary plane sets and a real pipeline
//! frustum, with an intensity attribute.
//!
//! Input polygons are convex (a planar convex hull, for which the
//! documented capacity holds) or arbitrary vertex lists. Attributes are
//! either an affine function of position or arbitrary.
//!
//! Oracle:
//! - more than `MAX_INPUT_VERTICES` → `TooManyVertices`; a NaN or ±∞
//!   coordinate or attribute → `NonFinite`; convex input never fails;
//! - the output is empty or has 3..=`MAX_CLIPPED_VERTICES` finite
//!   vertices;
//! - every output vertex is inside every plane within
//!   `tol_i = 16·(ε + f)·(Σ_k |n_ik|·(2M + 1) + |d_i| + 1)` (M the largest
//!   input coordinate, ε = `T::EPSILON`, f the fixed-point step or 0),
//!   and one that is not an input vertex lies on some plane within the
//!   same `tol_i` (it is an intersection point);
//! - every output vertex lies inside the bounding box of the input
//!   vertices, and its attribute within the range of the input attributes,
//!   both within `16(ε + f)·(M + 1)`; for affine attributes
//!   `I = g·p + c`, the output satisfies the same relation within
//!   `16(ε + f)·(Σ|g_k|·(2M + 1) + |c| + 1)`.
#![no_main]

mod common;

use arbitrary::Arbitrary;
use common::{Kind, Num, convex_hull, eps};
use libfuzzer_sys::fuzz_target;
use sightline::camera::Projection;
use sightline::math::Vec3;
use sightline::pipeline::{
    ClipError, Frustum, Intensity, MAX_CLIPPED_VERTICES, MAX_INPUT_VERTICES, Pipeline, Plane,
    Vertex,
};
use sightline::scalar::{I16F16, Scalar};

#[derive(Arbitrary, Debug)]
enum Planes {
    Free(Vec<([i8; 3], i8)>),
    /// Any f64 values (floats only).
    Wild(Vec<([Num; 3], Num)>),
    Pipeline {
        focus: u8,
        w: u8,
        h: u8,
        near: u8,
        far: u8,
        guard: u8,
        parallel: bool,
    },
}

#[derive(Arbitrary, Debug)]
enum Poly {
    /// Convex hull of (u, v) points in the plane O + u·U + v·V.
    Convex {
        o: [i8; 3],
        u: [i8; 3],
        v: [i8; 3],
        pts: Vec<(i8, i8)>,
    },
    Free(Vec<[i8; 3]>),
    /// Any f64 values (floats only).
    Wild(Vec<[Num; 3]>),
}

#[derive(Arbitrary, Debug)]
struct Input {
    kind: Kind,
    planes: Planes,
    poly: Poly,
    affine: Option<([i8; 3], i8)>,
    attrs: Vec<i8>,
    scale: u8,
}

fn run<T: Scalar>(input: &Input) {
    let fixed = !T::IS_FLOAT;
    let sc = 2f64.powi((input.scale % 5) as i32 - 2);
    let planes: Vec<Plane<T>> = match &input.planes {
        Planes::Free(p) => p
            .iter()
            .take(8)
            .map(|(n, d)| {
                let n = n.map(|x| T::from_f64((x % 9) as f64 / 4.0));
                Plane::new(
                    Vec3::new(n[0], n[1], n[2]),
                    T::from_f64(*d as f64 * sc / 2.0),
                )
            })
            .collect(),
        Planes::Wild(p) => {
            if fixed {
                return;
            }
            p.iter()
                .take(8)
                .map(|(n, d)| Plane::new(common::v3(*n), common::conv(d.value())))
                .collect()
        }
        Planes::Pipeline {
            focus,
            w,
            h,
            near,
            far,
            guard,
            parallel,
        } => {
            let (w, h) = (*w as u16 + 1, *h as u16 + 1);
            let proj = if *parallel {
                Projection::parallel(T::from_f64(*focus as f64 / 8.0 + 0.125), w, h)
            } else {
                Projection::perspective(T::from_f64(*focus as f64 + 1.0), w, h)
            };
            let near = *near as f64 / 16.0 + 0.0625;
            match Pipeline::new(
                proj,
                w,
                h,
                T::from_f64(near),
                T::from_f64(near + *far as f64 / 4.0 + 0.25),
                T::from_f64(*guard as f64),
            ) {
                Ok(p) => p.frustum().planes().to_vec(),
                Err(_) => return,
            }
        }
    };
    let frustum = Frustum::from_planes(&planes);
    let pos: Vec<[f64; 3]> = match &input.poly {
        Poly::Convex { o, u, v, pts } => {
            let h = convex_hull(
                &pts.iter()
                    .take(10)
                    .map(|&(a, b)| [(a % 16) as i64, (b % 16) as i64])
                    .collect::<Vec<_>>(),
            );
            h.iter()
                .map(|p| {
                    [0, 1, 2].map(|i| {
                        (o[i] as f64
                            + p[0] as f64 * (u[i] % 8) as f64
                            + p[1] as f64 * (v[i] % 8) as f64)
                            * sc
                            / 4.0
                    })
                })
                .collect()
        }
        Poly::Free(v) => v
            .iter()
            .take(10)
            .map(|p| p.map(|x| x as f64 * sc / 2.0))
            .collect(),
        Poly::Wild(v) => {
            if fixed {
                return;
            }
            v.iter().take(10).map(|p| p.map(Num::value)).collect()
        }
    };
    let convex = matches!(input.poly, Poly::Convex { .. });
    let attr_of = |i: usize, p: [f64; 3]| match input.affine {
        Some((g, c)) => (0..3).map(|k| g[k] as f64 / 64.0 * p[k]).sum::<f64>() + c as f64 / 64.0,
        None => input.attrs.get(i).copied().unwrap_or(0) as f64 / 64.0,
    };
    let verts: Vec<Vertex<T, Intensity<T>>> = pos
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let pv: Vec3<T> = Vec3::new(common::conv(p[0]), common::conv(p[1]), common::conv(p[2]));
            // The attribute of the stored position.
            Vertex::new(pv, Intensity(common::conv(attr_of(i, common::f3(pv)))))
        })
        .collect();
    // Work with the stored values from here on.
    let pos: Vec<[f64; 3]> = verts.iter().map(|v| common::f3(v.pos)).collect();
    let attrs: Vec<f64> = verts.iter().map(|v| v.attr.0.to_f64()).collect();
    let finite = pos.iter().flatten().chain(&attrs).all(|x| x.is_finite());
    let out = frustum.clip(&verts);
    if verts.len() > MAX_INPUT_VERTICES {
        assert_eq!(out, Err(ClipError::TooManyVertices), "{}", T::NAME);
        return;
    }
    if !finite {
        assert_eq!(out, Err(ClipError::NonFinite), "{}", T::NAME);
        return;
    }
    let out = match out {
        Ok(o) => o,
        Err(ClipError::TooManyVertices) if !convex => return,
        Err(e) => panic!(
            "{}: {e:?} for finite {} input",
            T::NAME,
            if convex { "convex" } else { "" }
        ),
    };
    assert!(
        out.is_empty() || (out.len() >= 3 && out.len() <= MAX_CLIPPED_VERTICES),
        "{}: {} vertices",
        T::NAME,
        out.len()
    );
    let e = eps::<T>() + if fixed { eps::<T>() } else { 0.0 };
    let m = pos.iter().flatten().fold(0.0f64, |a, x| a.max(x.abs()));
    let (amin, amax) = attrs
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    let box_tol = 16.0 * e * (m + 1.0);
    // The affine model holds for the stored inputs unless an attribute
    // saturated on conversion.
    let affine_holds = input.affine.is_some_and(|(g, c)| {
        pos.iter().zip(&attrs).all(|(p, &a)| {
            let want = (0..3).map(|k| g[k] as f64 / 64.0 * p[k]).sum::<f64>() + c as f64 / 64.0;
            (a - want).abs() <= 4.0 * e * (want.abs() + 1.0)
        })
    });
    for v in &out {
        let p = common::f3(v.pos);
        let a = v.attr.0.to_f64();
        assert!(
            p.iter().all(|x| x.is_finite()) && a.is_finite(),
            "{}: non-finite output {v:?}",
            T::NAME
        );
        let mut on_a_plane = false;
        for pl in frustum.planes() {
            let n = common::f3(pl.n);
            let d = pl.d.to_f64();
            let dist = n[0] * p[0] + n[1] * p[1] + n[2] * p[2] + d;
            let tol = 16.0
                * e
                * ((n[0].abs() + n[1].abs() + n[2].abs()) * (2.0 * m + 1.0) + d.abs() + 1.0);
            assert!(
                dist >= -tol || !tol.is_finite(),
                "{}: output {p:?} outside plane {n:?}·p + {d} by {} (tol {tol})",
                T::NAME,
                -dist
            );
            on_a_plane |= dist <= tol || !tol.is_finite();
        }
        // A vertex the clipper made is an intersection with some plane.
        assert!(
            on_a_plane || verts.iter().any(|w| w.pos == v.pos),
            "{}: new output vertex {p:?} lies on no plane",
            T::NAME
        );
        for k in 0..3 {
            let lo = pos.iter().fold(f64::INFINITY, |a, q| a.min(q[k]));
            let hi = pos.iter().fold(f64::NEG_INFINITY, |a, q| a.max(q[k]));
            assert!(
                p[k] >= lo - box_tol && p[k] <= hi + box_tol,
                "{}: output {p:?} outside the input box",
                T::NAME
            );
        }
        let atol = 16.0 * e * (amax.abs().max(amin.abs()) + 1.0);
        assert!(
            a >= amin - atol && a <= amax + atol,
            "{}: attribute {a} outside [{amin}, {amax}]",
            T::NAME
        );
        if let (Some((g, c)), true) = (input.affine, affine_holds) {
            let want = (0..3).map(|k| g[k] as f64 / 64.0 * p[k]).sum::<f64>() + c as f64 / 64.0;
            let gs: f64 = g.iter().map(|x| (*x as f64 / 64.0).abs()).sum();
            // The stored input attributes are rounded once (to the type).
            let tol = 16.0 * e * (gs * (2.0 * m + 1.0) + (c as f64 / 64.0).abs() + 1.0)
                + 4.0 * e * (amax.abs().max(amin.abs()));
            assert!(
                (a - want).abs() <= tol || !tol.is_finite(),
                "{}: affine attribute {a}, want {want} at {p:?} (tol {tol})",
                T::NAME
            );
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
