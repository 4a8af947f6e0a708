//! `inclusion`: the four point-in-polygon tests (crossing, half-plane,
//! binary fan, slabs) on integer-grid polygons, in f32, f64 and I16F16.
//!
//! Polygons are convex hulls, star-shaped polygons (vertices sorted by
//! angle around a center, so always simple) or a convex hull split along a
//! diagonal into two polygons, in the reference plane of any axis and in
//! either orientation. Query points are arbitrary half-integers, vertices
//! and edge midpoints (±½): many lie exactly on the boundary.
//!
//! Oracle (exact, i128): the boundary policy of `ray::polygon` says p is
//! inside exactly when `p + (δ, δη)` is, for infinitesimals `0 < η ≪ δ`.
//! With every coordinate scaled by M and the point moved by (D, 1) for
//! integers `D > max |edge.x|` and `M > max |d.x − D·d.y|`, the moved point
//! is strictly inside or outside and on the same side of every edge as the
//! nudged point; it is classified by its winding number (nonzero = inside),
//! an algorithm independent of all four tests. Every test must agree with
//! the oracle on every point (inside, outside and boundary; the orientation
//! signs are exact in all three types), hulls must be reported
//! convex, and for a split hull the two halves together claim each point
//! exactly as often as the hull does (0 or 1): a point on the shared
//! diagonal belongs to exactly one half.
#![no_main]

mod common;

use arbitrary::Arbitrary;
use common::{Kind, convex_hull, winding};
use libfuzzer_sys::fuzz_target;
use sightline::math::{Vec2, Vec3};
use sightline::ray::{InclusionTest, Polygon, PolygonError, SlabIndex};
use sightline::scalar::{I16F16, Scalar};

#[derive(Arbitrary, Debug)]
enum Query {
    /// (x, y) in half units.
    Free(i16, i16),
    /// Vertex i plus (dx, dy) half units, dx, dy in -2..=2.
    Vertex(u8, i8, i8),
    /// Midpoint of edge i plus (dx, dy) half units.
    Mid(u8, i8, i8),
}

#[derive(Arbitrary, Debug)]
struct Input {
    kind: Kind,
    mode: u8,
    axis: u8,
    reverse: bool,
    zc: i8,
    wide: bool,
    center: (i16, i16),
    diag: (u8, u8),
    verts: Vec<(i16, i16)>,
    queries: Vec<Query>,
}

const CAP: usize = 16;

/// Inside by the exact nudged-point winding oracle; coordinates in half
/// units.
fn oracle(poly: &[[i64; 2]], p: [i64; 2], r: i128) -> bool {
    let d = 2 * r + 1;
    let m = 2 * r * (1 + d) + 1;
    let scaled: Vec<[i128; 2]> = poly
        .iter()
        .map(|v| [v[0] as i128 * m, v[1] as i128 * m])
        .collect();
    let q = [p[0] as i128 * m + d, p[1] as i128 * m + 1];
    winding(&scaled, q) != 0
}

/// (crossing, half-plane, fan, slab).
fn classify<T: Scalar>(
    poly: &Polygon<T, CAP>,
    slab: &SlabIndex<'_, T, CAP>,
    p: [i64; 2],
) -> [bool; 4] {
    let q = Vec2::new(
        T::from_f64(p[0] as f64 / 2.0),
        T::from_f64(p[1] as f64 / 2.0),
    );
    [
        poly.contains(q, InclusionTest::Crossing),
        poly.contains(q, InclusionTest::HalfPlane),
        poly.contains(q, InclusionTest::Fan),
        slab.contains(q),
    ]
}

fn build<T: Scalar>(
    pts: &[[i64; 2]],
    axis: usize,
    zc: i64,
) -> Result<Polygon<T, CAP>, PolygonError> {
    let verts: Vec<Vec3<T>> = pts
        .iter()
        .map(|p| {
            let mut c = [0.0; 3];
            c[axis] = zc as f64;
            c[(axis + 1) % 3] = p[0] as f64 / 2.0;
            c[(axis + 2) % 3] = p[1] as f64 / 2.0;
            Vec3::new(T::from_f64(c[0]), T::from_f64(c[1]), T::from_f64(c[2]))
        })
        .collect();
    Polygon::new(&verts)
}

fn run<T: Scalar>(input: &Input, limit: i64) {
    let c = |x: i16| (x as i64 % limit) * 2; // vertices: integers, in half units
    let raw: Vec<[i64; 2]> = input
        .verts
        .iter()
        .take(CAP)
        .map(|&(x, y)| [c(x), c(y)])
        .collect();
    let mode = input.mode % 3;
    let mut polys: Vec<Vec<[i64; 2]>> = Vec::new();
    let hull = convex_hull(&raw);
    match mode {
        0 | 2 => {
            if hull.len() < 3 {
                return;
            }
            if mode == 0 {
                polys.push(hull.clone());
            } else {
                let n = hull.len();
                if n < 4 {
                    return;
                }
                let i = input.diag.0 as usize % n;
                let j = (i + 2 + input.diag.1 as usize % (n - 3)) % n;
                let mut a = Vec::new();
                let mut k = i;
                loop {
                    a.push(hull[k]);
                    if k == j {
                        break;
                    }
                    k = (k + 1) % n;
                }
                let mut b = Vec::new();
                loop {
                    b.push(hull[k]);
                    if k == i {
                        break;
                    }
                    k = (k + 1) % n;
                }
                polys.push(a);
                polys.push(b);
            }
        }
        _ => {
            let ctr = [c(input.center.0), c(input.center.1)];
            let mut pts: Vec<[i64; 2]> = raw.iter().copied().filter(|&p| p != ctr).collect();
            let half =
                |p: [i64; 2]| (p[1] - ctr[1] < 0 || (p[1] == ctr[1] && p[0] - ctr[0] < 0)) as u8;
            let cross = |a: [i64; 2], b: [i64; 2]| {
                (a[0] - ctr[0]) as i128 * (b[1] - ctr[1]) as i128
                    - (a[1] - ctr[1]) as i128 * (b[0] - ctr[0]) as i128
            };
            pts.sort_by(|&a, &b| half(a).cmp(&half(b)).then_with(|| 0.cmp(&cross(a, b))));
            pts.dedup_by(|a, b| half(*a) == half(*b) && cross(*a, *b) == 0);
            let n = pts.len();
            if n < 3 || (0..n).any(|i| cross(pts[i], pts[(i + 1) % n]) <= 0) {
                return;
            }
            polys.push(pts);
        }
    }
    if input.reverse {
        for p in &mut polys {
            p.reverse();
        }
    }
    let axis = input.axis as usize % 3;
    let built: Vec<Polygon<T, CAP>> = match polys
        .iter()
        .map(|p| build::<T>(p, axis, input.zc as i64))
        .collect()
    {
        Ok(b) => b,
        Err(e) => {
            assert!(
                matches!(
                    e,
                    PolygonError::Overflow | PolygonError::TooManyVertices { .. }
                ),
                "{}: {e:?} for a simple integer polygon {polys:?}",
                T::NAME
            );
            return;
        }
    };
    if mode != 1 {
        for p in &built {
            assert!(
                p.is_convex(),
                "{}: convex polygon reported non-convex: {polys:?}",
                T::NAME
            );
        }
    }
    let all: Vec<[i64; 2]> = polys.concat();
    let mut r: i128 = 1;
    let mut queries: Vec<[i64; 2]> = Vec::new();
    let whole = if mode == 2 {
        hull.clone()
    } else {
        polys[0].clone()
    };
    let nw = whole.len();
    for q in input.queries.iter().take(24) {
        let off = |d: i8| (d % 3) as i64;
        queries.push(match *q {
            Query::Free(x, y) => [x as i64 % (2 * limit + 8), y as i64 % (2 * limit + 8)],
            Query::Vertex(i, dx, dy) => {
                let v = whole[i as usize % nw];
                [v[0] + off(dx), v[1] + off(dy)]
            }
            Query::Mid(i, dx, dy) => {
                let a = whole[i as usize % nw];
                let b = whole[(i as usize + 1) % nw];
                [(a[0] + b[0]) / 2 + off(dx), (a[1] + b[1]) / 2 + off(dy)]
            }
        });
    }
    for p in all.iter().chain(&queries) {
        r = r
            .max(p[0].unsigned_abs() as i128)
            .max(p[1].unsigned_abs() as i128);
    }
    // An edge vector is at most 2r in each coordinate.
    let r = 2 * r;
    // Slab storage as documented: n, n and n·(n − 1) entries.
    let mut storage: Vec<(Vec<T>, Vec<u32>, Vec<u32>)> = built
        .iter()
        .map(|p| {
            let n = p.edges().len();
            (vec![T::ZERO; n], vec![0u32; n], vec![0u32; n * (n - 1)])
        })
        .collect();
    let slabs: Vec<SlabIndex<'_, T, CAP>> = built
        .iter()
        .zip(storage.iter_mut())
        .map(|(p, (ys, st, ed))| {
            SlabIndex::build(p, ys, st, ed).expect("storage sized as documented")
        })
        .collect();
    for &p in &queries {
        let mut claims = 0;
        for ((poly, slab), pts) in built.iter().zip(&slabs).zip(&polys) {
            let want = oracle(pts, p, r);
            let got = classify(poly, slab, p);
            assert!(
                got.iter().all(|&g| g == want),
                "{}: point {p:?} (half units) in {pts:?}: oracle {want}, crossing/half-plane/fan/slab {got:?}",
                T::NAME
            );
            claims += want as i32;
        }
        if mode == 2 {
            let want = oracle(&hull, p, r) as i32;
            assert_eq!(
                claims,
                want,
                "{}: split hull claims {p:?} {claims} times",
                T::NAME
            );
        }
    }
}

fuzz_target!(|input: Input| {
    match input.kind {
        // Orientation signs are exact in every type (Scalar::orient2d), so
        // f32 takes the same range as f64 (half-units stay below 2^24).
        Kind::F32 => run::<f32>(&input, if input.wide { 16000 } else { 64 }),
        Kind::F64 => run::<f64>(&input, if input.wide { 16000 } else { 64 }),
        // I16F16: edge vectors must fit ±32768.
        Kind::Fixed => run::<I16F16>(&input, if input.wide { 16000 } else { 64 }),
    }
});
