//! `ray_polygon`: `Polygon::intersect` (all three inclusion tests) and the
//! slab index's ray test, in f32, f64 and I16F16, on convex integer
//! polygons in tilted planes (vertex = O + u·U + v·V with integer O, U, V,
//! (u, v) on a convex hull), hit by integer rays; all scaled by a power of
//! two, so every input is exact in every type.
//!
//! Oracle (exact, i128): t* = n·(O − Q)/n·d with n = U × V, and the hit
//! point X* = Q + t*·d as a rational. A returned t must be finite, > t_min
//! and within the plane bound of the `ray_plane` target,
//!
//! ```text
//! δt = 8ε·(Σ|u_i||r_i| + |t*|·Σ|u_i||d_i|)/|u·d| + 8f·(3 + Σ|r_i| + |t*|(3 + Σ|d_i|))/|u·d| + 2ε|t*| + 2f
//! ```
//!
//! (u = n/|n|, r = vertex₀ − Q). The computed point is then within
//! `δx = δt·‖d‖∞ + 4ε‖X*‖∞ + 2f` of X* in every coordinate, and so is its
//! projection to the polygon's reference plane. If X* is farther than
//! 2δx inside every edge (in that projection), every test must report the
//! hit; if it is farther than 2δx outside some edge (or t* ≤ t_min − δt),
//! none may. In between, only the first property is checked. Fixed point
//! may miss where t* or X* leave the range (documented).
#![no_main]

mod common;

use arbitrary::Arbitrary;
use common::{Kind, convex_hull, eps, floor, icross, idot, isub3};
use libfuzzer_sys::fuzz_target;
use sightline::math::Vec3;
use sightline::ray::{InclusionTest, Intersect, Polygon, Ray, SlabIndex};
use sightline::scalar::{I16F16, Scalar};

#[derive(Arbitrary, Debug)]
struct Input {
    kind: Kind,
    scale: u8,
    reverse: bool,
    o: [i8; 3],
    u: [i8; 3],
    v: [i8; 3],
    pts: Vec<(i8, i8)>,
    q: [i8; 3],
    d: [i8; 3],
    t_min: i8,
}

const CAP: usize = 12;

fn conv<T: Scalar>(p: [i128; 3], scale: f64) -> Vec3<T> {
    Vec3::new(
        T::from_f64(p[0] as f64 * scale),
        T::from_f64(p[1] as f64 * scale),
        T::from_f64(p[2] as f64 * scale),
    )
}

fn run<T: Scalar>(input: &Input) {
    let e = if T::IS_FLOAT {
        (input.scale % 7) as i32 - 3
    } else {
        (input.scale % 4) as i32 - 3
    };
    let scale = 2f64.powi(e);
    let i3 = |p: [i8; 3], m: i128| p.map(|x| x as i128 % m);
    let (o, uu, vv) = (i3(input.o, 128), i3(input.u, 16), i3(input.v, 16));
    let mut hull = convex_hull(
        &input
            .pts
            .iter()
            .take(CAP)
            .map(|&(a, b)| [(a % 16) as i64, (b % 16) as i64])
            .collect::<Vec<_>>(),
    );
    if hull.len() < 3 {
        return;
    }
    if input.reverse {
        hull.reverse();
    }
    let n = icross(uu, vv);
    if n == [0; 3] {
        return;
    }
    let verts: Vec<[i128; 3]> = hull
        .iter()
        .map(|h| [0, 1, 2].map(|i| o[i] + h[0] as i128 * uu[i] + h[1] as i128 * vv[i]))
        .collect();
    let vt: Vec<Vec3<T>> = verts.iter().map(|&p| conv(p, scale)).collect();
    let poly = match Polygon::<T, CAP>::new(&vt) {
        Ok(p) => p,
        Err(err) => panic!(
            "{}: {err:?} for a convex integer polygon {verts:?}",
            T::NAME
        ),
    };
    let (q, d) = (i3(input.q, 128), i3(input.d, 128));
    if d == [0; 3] {
        return;
    }
    let ray = Ray::new(conv::<T>(q, scale), conv::<T>(d, scale)).expect("finite, non-zero");
    let t_min_f = input.t_min as f64 / 16.0;
    let t_min = T::from_f64(t_min_f);
    let tests = [
        InclusionTest::Crossing,
        InclusionTest::HalfPlane,
        InclusionTest::Fan,
    ];
    let mut got: Vec<Option<f64>> = tests
        .iter()
        .map(|&k| {
            poly.clone()
                .with_test(k)
                .intersect(&ray, t_min)
                .map(|t| t.to_f64())
        })
        .collect();
    let m = verts.len();
    let (mut ys, mut st, mut ed) = (vec![T::ZERO; m], vec![0u32; m], vec![0u32; m * (m - 1)]);
    let slab = SlabIndex::build(&poly, &mut ys, &mut st, &mut ed).expect("sized as documented");
    got.push(slab.intersect_ray(&ray, t_min).map(|h| h.t.to_f64()));
    for t in got.iter().flatten() {
        assert!(t.is_finite() && *t > t_min_f, "{}: t = {t}", T::NAME);
    }

    // Exact reference.
    let nd = idot(n, d);
    if nd == 0 {
        // Parallel or in the plane: any reported t was checked finite.
        return;
    }
    let num = idot(n, isub3(verts[0], q));
    let t_ref = num as f64 / nd as f64;
    let (eps_t, f) = (eps::<T>(), floor::<T>());
    let nf = n.map(|c| c as f64);
    let nl = (nf[0] * nf[0] + nf[1] * nf[1] + nf[2] * nf[2]).sqrt();
    let u = nf.map(|c| c / nl);
    let rf = isub3(verts[0], q).map(|c| c as f64 * scale);
    let df = d.map(|c| c as f64 * scale);
    let ur: f64 = (0..3).map(|i| u[i].abs() * rf[i].abs()).sum();
    let ud: f64 = (0..3).map(|i| u[i].abs() * df[i].abs()).sum();
    let r1: f64 = rf.iter().map(|x| x.abs()).sum();
    let d1: f64 = df.iter().map(|x| x.abs()).sum();
    let den = (nd as f64 / nl * scale).abs();
    let dt = (8.0 * eps_t * (ur + t_ref.abs() * ud)
        + 8.0 * f * (3.0 + r1 + t_ref.abs() * (3.0 + d1)))
        / den
        + 2.0 * eps_t * t_ref.abs()
        + 2.0 * f;
    for t in got.iter().flatten() {
        assert!(
            (t - t_ref).abs() <= dt,
            "{}: t = {t}, exact {t_ref}, bound {dt}",
            T::NAME
        );
    }
    // Exact hit point X* = (Q·nd + num·d)/nd, projected along the axis
    // Polygon uses (largest |n_k|, lowest index on a tie).
    let mut k = 0;
    for j in 1..3 {
        if n[j].abs() > n[k].abs() {
            k = j;
        }
    }
    let xs = [0, 1, 2].map(|i| q[i] * nd + num * d[i]); // X*·nd
    let (ia, ib) = ((k + 1) % 3, (k + 2) % 3);
    let xmax = xs
        .iter()
        .fold(0.0f64, |m, &c| m.max((c as f64 / nd as f64).abs() * scale));
    let dmax = df.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let dx = dt * dmax + 4.0 * eps_t * xmax + 2.0 * f;
    // Signed distance of X* inside each edge (positive inside).
    let mut min_inside = f64::INFINITY;
    let pv: Vec<[i128; 2]> = verts.iter().map(|p| [p[ia], p[ib]]).collect();
    let area2: i128 = (0..m)
        .map(|i| pv[i][0] * pv[(i + 1) % m][1] - pv[(i + 1) % m][0] * pv[i][1])
        .sum();
    for i in 0..m {
        let (a, b) = (pv[i], pv[(i + 1) % m]);
        let e = [b[0] - a[0], b[1] - a[1]];
        // E·nd = e.x·(X.y·nd − a.y·nd) − e.y·(X.x·nd − a.x·nd)
        let en = e[0] * (xs[ib] - a[1] * nd) - e[1] * (xs[ia] - a[0] * nd);
        let dist = en as f64 / nd as f64 / ((e[0] * e[0] + e[1] * e[1]) as f64).sqrt()
            * area2.signum() as f64;
        min_inside = min_inside.min(dist * scale);
    }
    let max = T::MAX.to_f64() * 0.99;
    let range = t_ref.abs() + dt < max && xmax + dx < max;
    if min_inside > 2.0 * dx && t_ref > t_min_f + dt && range {
        for (i, g) in got.iter().enumerate() {
            assert!(
                g.is_some(),
                "{}: test {i} missed; exact t {t_ref}, inside by {min_inside} (bound {dx})",
                T::NAME
            );
        }
    }
    if min_inside < -2.0 * dx || t_ref <= t_min_f - dt {
        for (i, g) in got.iter().enumerate() {
            assert!(
                g.is_none(),
                "{}: test {i} hit {g:?}; exact t {t_ref}, outside by {}",
                T::NAME,
                -min_inside
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
