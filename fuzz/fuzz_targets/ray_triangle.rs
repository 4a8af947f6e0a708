//! `ray_triangle`: the watertight ray/triangle test (`Triangle::intersect`,
//! `Mesh::intersect`) in f32, f64 and I16F16, on integer-grid vertices
//! scaled by a power of two (so every input is exact in every type).
//!
//! Oracle (exact, i128): with `V_A = det(B−Q, C−Q, d)` (and cyclically),
//! the exact barycentric weights are `V_A/ΣV`, ... and the exact
//! `t = n·(A−Q)/n·d`. With S the largest sheared coordinate (≈ the
//! largest |vertex − Q| in the ray's frame), Δ = |ΣV/d_k| the exact
//! sheared determinant and Z the largest sheared depth, each weight is
//! within `w_tol = 16·S·δ/Δ` of the exact one, `δ = 8ε·R + f·(2 + Z_r)`
//! the error of one sheared coordinate (R the largest |vertex − Q|
//! component, Z_r the largest along the ray's axis; ε = `T::EPSILON`, f
//! one absolute rounding: the fixed-point step, or the smallest
//! subnormal), and t within
//! `3·w_tol·Z + 8ε|t| + 4|t|·f·|d_k| + f`. So:
//! - a hit must have finite t > t_min, weights summing to 1 and each
//!   weight and t within those bounds of the exact ones;
//! - a point whose smallest weight exceeds `w_tol` (and whose t exceeds
//!   t_min by the t bound) must be hit, one whose smallest weight is below
//!   `−w_tol` must be missed (fixed point: unless a sheared coordinate or
//!   `1/d_k` leaves the range, a documented miss).
//!
//! A ray parallel to the plane and off it must miss, and so must a
//! triangle with a repeated vertex; a ray inside the plane may report a
//! grazing hit (finite t), and so may (as documented in `ray::triangle`)
//! a collinear triangle whose line the ray meets.
//!
//! Watertightness: two triangles ABC and CBD share the edge BC, with A and
//! D strictly on opposite sides of the plane through the ray and the edge.
//! A ray through a point strictly inside BC, farther than the weight
//! tolerance from the outer edges, must hit at least one of them
//! (both, per the module docs, is allowed), and the two-triangle `Mesh`
//! must report exactly one hit, with the lower index on equal t.
#![no_main]

mod common;

use arbitrary::Arbitrary;
use common::{Kind, eps, floor, icross, idot, isub3};
use libfuzzer_sys::fuzz_target;
use sightline::math::Vec3;
use sightline::ray::{Mesh, Ray, Triangle};
use sightline::scalar::{I16F16, Scalar};

#[derive(Arbitrary, Debug)]
struct Input {
    kind: Kind,
    shared: bool,
    scale: u8,
    a: [i8; 3],
    b: [i8; 3],
    c: [i8; 3],
    d: [i8; 3],
    q: [i8; 3],
    dir: [i8; 3],
    k: u8,
    t_min: i8,
}

fn det(a: [i128; 3], b: [i128; 3], c: [i128; 3]) -> i128 {
    idot(a, icross(b, c))
}

struct Exact {
    /// Weights of A, B, C.
    w: [f64; 3],
    t: f64,
    w_tol: f64,
    t_tol: f64,
    overflow: bool,
}

/// Exact reference for triangle (a, b, c) and the ray q + t·d, in integer
/// units; `scale` converts to the caller's units (a power of two).
fn exact<T: Scalar>(v: [[i128; 3]; 3], q: [i128; 3], d: [i128; 3], scale: f64) -> Option<Exact> {
    let r = v.map(|p| isub3(p, q));
    let va = det(r[1], r[2], d);
    let vb = det(r[2], r[0], d);
    let vc = det(r[0], r[1], d);
    let sum = va + vb + vc;
    let n = icross(isub3(v[1], v[0]), isub3(v[2], v[0]));
    let nd = idot(n, d);
    if sum == 0 || nd == 0 {
        return None;
    }
    let t = idot(n, r[0]) as f64 / nd as f64;
    let w = [
        va as f64 / sum as f64,
        vb as f64 / sum as f64,
        vc as f64 / sum as f64,
    ];
    // The ray's dominant axis k and the sheared frame.
    let mut k = 0;
    for j in 1..3 {
        if d[j].abs() > d[k].abs() {
            k = j;
        }
    }
    let dk = d[k] as f64;
    let sheared_det = (sum as f64 / dk).abs() * scale * scale;
    let mut s_max = 0.0f64;
    let mut z_max = 0.0f64;
    for p in &r {
        for j in 0..3 {
            if j != k {
                let x = p[j] as f64 - d[j] as f64 / dk * p[k] as f64;
                s_max = s_max.max(x.abs() * scale);
            }
        }
        z_max = z_max.max((p[k] as f64 / dk).abs());
    }
    let (e, f) = (eps::<T>(), floor::<T>());
    let za = r
        .iter()
        .fold(0.0f64, |m, p| m.max((p[k] as f64).abs() * scale));
    // One sheared coordinate x = r_j − (d_j/d_k)·r_k: its rounding errors
    // scale with the inputs |r_j| + |r_k| ≤ 2R, not with |x| (which may
    // cancel).
    let r_all = r.iter().fold(0.0f64, |m, p| {
        m.max(
            p.iter()
                .fold(0.0f64, |m, &c| m.max((c as f64).abs() * scale)),
        )
    });
    let delta = 8.0 * e * r_all + f * (2.0 + za);
    let w_tol = 16.0 * s_max * delta / sheared_det;
    let dk_user = dk.abs() * scale;
    let t_tol = 3.0 * w_tol * z_max + 8.0 * e * t.abs() + 4.0 * t.abs() * f * dk_user + f;
    let max = T::MAX.to_f64() * 0.5;
    let overflow = !T::IS_FLOAT
        && (s_max >= max || za >= max || z_max >= max || 1.0 / dk_user >= max || t.abs() >= max);
    Some(Exact {
        w,
        t,
        w_tol,
        t_tol,
        overflow,
    })
}

fn conv<T: Scalar>(p: [i128; 3], scale: f64) -> Vec3<T> {
    Vec3::new(
        T::from_f64(p[0] as f64 * scale),
        T::from_f64(p[1] as f64 * scale),
        T::from_f64(p[2] as f64 * scale),
    )
}

/// Checks one triangle against the exact reference; returns whether it
/// was hit.
fn check_one<T: Scalar>(
    v: [[i128; 3]; 3],
    q: [i128; 3],
    d: [i128; 3],
    scale: f64,
    t_min: f64,
) -> bool {
    let tri = Triangle::new(conv::<T>(v[0], scale), conv(v[1], scale), conv(v[2], scale));
    let ray =
        Ray::new(conv::<T>(q, scale), conv::<T>(d, scale)).expect("non-zero integer direction");
    let tm = T::from_f64(t_min);
    let hit = tri.intersect(&ray, tm);
    let ex = exact::<T>(v, q, d, scale);
    if let Some(h) = hit {
        let t = h.t.to_f64();
        assert!(h.t.is_finite() && h.t > tm, "{}: t = {t}", T::NAME);
        let w = [h.u.to_f64(), h.v.to_f64(), h.w.to_f64()];
        let Some(ex) = &ex else {
            // Degenerate triangle, or a ray parallel to its plane: only a
            // ray lying in the plane of a proper triangle may report a
            // (grazing) hit, where rounding makes the sheared determinant
            // non-zero.
            let n = icross(isub3(v[1], v[0]), isub3(v[2], v[0]));
            let in_plane = n != [0; 3] && idot(n, d) == 0 && idot(n, isub3(v[0], q)) == 0;
            // Documented: three distinct collinear vertices and a ray
            // coplanar with their line (every V is 0).
            let r = v.map(|p| isub3(p, q));
            let sliver = n == [0; 3]
                && v[0] != v[1]
                && v[1] != v[2]
                && v[2] != v[0]
                && det(r[1], r[2], d) == 0
                && det(r[2], r[0], d) == 0
                && det(r[0], r[1], d) == 0;
            assert!(
                in_plane || sliver,
                "{}: hit (t {t}, w {w:?}) on a degenerate triangle or a parallel ray",
                T::NAME
            );
            return true;
        };
        for i in 0..3 {
            assert!(
                (w[i] - ex.w[i]).abs() <= ex.w_tol + 4.0 * floor::<T>(),
                "{}: weights {w:?}, exact {:?}, tolerance {}",
                T::NAME,
                ex.w,
                ex.w_tol
            );
        }
        assert!(
            (t - ex.t).abs() <= ex.t_tol,
            "{}: t = {t}, exact {}, tolerance {}",
            T::NAME,
            ex.t,
            ex.t_tol
        );
    } else if let Some(ex) = &ex {
        let min_w = ex.w.iter().fold(f64::INFINITY, |m, &x| m.min(x));
        assert!(
            !(min_w > ex.w_tol && ex.t > t_min + ex.t_tol) || ex.overflow,
            "{}: missed, exact weights {:?} (tolerance {}), t {} (t_min {t_min})",
            T::NAME,
            ex.w,
            ex.w_tol,
            ex.t
        );
    }
    if let (Some(_), Some(ex)) = (hit, &ex) {
        let min_w = ex.w.iter().fold(f64::INFINITY, |m, &x| m.min(x));
        assert!(
            min_w >= -ex.w_tol,
            "{}: hit, but exact weights {:?} (tolerance {})",
            T::NAME,
            ex.w,
            ex.w_tol
        );
    }
    hit.is_some()
}

fn run<T: Scalar>(input: &Input) {
    let e = (input.scale % 10) as i32 - 6; // 2^-6 ..= 2^3
    let scale = 2f64.powi(e);
    let i3 = |p: [i8; 3], m: i128| p.map(|x| x as i128 * m);
    if !input.shared {
        let v = [i3(input.a, 1), i3(input.b, 1), i3(input.c, 1)];
        let (q, d) = (i3(input.q, 1), i3(input.dir, 1));
        if d == [0; 3] {
            return;
        }
        check_one::<T>(v, q, d, scale, input.t_min as f64 / 4.0);
        return;
    }
    // Shared edge BC: the ray from Q through B + (C − B)·k/4, k = 1..3.
    let (a, b, c, dv, q) = (
        i3(input.a, 4),
        i3(input.b, 4),
        i3(input.c, 4),
        i3(input.d, 4),
        i3(input.q, 4),
    );
    let k = (input.k % 3 + 1) as i128;
    let p = [0, 1, 2].map(|i| b[i] + (c[i] - b[i]) * k / 4);
    let d = isub3(p, q);
    if d == [0; 3] || b == c {
        return;
    }
    // A and D strictly on opposite sides of the plane (Q, B, C).
    let sa = det(isub3(b, q), isub3(c, q), isub3(a, q)).signum();
    let sd = det(isub3(b, q), isub3(c, q), isub3(dv, q)).signum();
    let hit1 = check_one::<T>([a, b, c], q, d, scale, 0.0);
    let hit2 = check_one::<T>([c, b, dv], q, d, scale, 0.0);
    let ex1 = exact::<T>([a, b, c], q, d, scale);
    let ex2 = exact::<T>([c, b, dv], q, d, scale);
    let overflow =
        ex1.as_ref().is_none_or(|e| e.overflow) || ex2.as_ref().is_none_or(|e| e.overflow);
    // The point must also be farther than rounding from the union's outer
    // edges (AB, CA, BD, DC): its exact weights for B and C in both
    // triangles exceed the weight tolerance. Otherwise a sliver (seen
    // along the ray) can be narrower at the point than the rounding of the
    // sheared vertices, and the ray legitimately leaves this open
    // two-triangle mesh across an outer edge.
    let clear = |e: &Option<Exact>, ib: usize, ic: usize| {
        e.as_ref()
            .is_some_and(|e| e.w[ib] > e.w_tol && e.w[ic] > e.w_tol)
    };
    if sa * sd == -1 && !overflow && clear(&ex1, 1, 2) && clear(&ex2, 1, 0) {
        assert!(
            hit1 || hit2,
            "{}: ray through the shared edge missed both triangles",
            T::NAME
        );
    }
    let verts = [a, b, c, dv].map(|p| conv::<T>(p, scale));
    let mesh = Mesh::new(&verts, &[[0, 1, 2], [2, 1, 3]]).expect("finite, in range");
    let ray = Ray::new(conv::<T>(q, scale), conv::<T>(d, scale)).expect("non-zero");
    let m = mesh.intersect(&ray, T::ZERO);
    assert_eq!(
        m.is_some(),
        hit1 || hit2,
        "{}: mesh {m:?} vs triangles {hit1} {hit2}",
        T::NAME
    );
    if let Some((i, _)) = m {
        assert!(
            i == 0 && hit1 || i == 1 && hit2,
            "{}: mesh reports triangle {i}",
            T::NAME
        );
    }
}

fuzz_target!(|input: Input| {
    match input.kind {
        Kind::F32 => run::<f32>(&input),
        Kind::F64 => run::<f64>(&input),
        Kind::Fixed => run::<I16F16>(&input),
    }
});
