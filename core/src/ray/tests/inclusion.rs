//! The four inclusion tests against an exact `i128` oracle, their mutual
//! agreement on random simple and convex polygons, and shared-edge
//! exclusivity.

use super::{Rng, is_f64, per_scalar};
use crate::math::{Vec2, Vec3};
use crate::ray::{InclusionTest, Polygon, SlabError, SlabIndex};
use crate::scalar::Scalar;
extern crate std;
use std::vec;
use std::vec::Vec;

/// Room for 1024 generated vertices plus inserted collinear midpoints.
const CAP: usize = 2100;
type P = (i64, i64);

/// Largest coordinate magnitude for which every edge-function sign is exact
/// in `S` (see the boundary-policy docs): for floats the products of
/// differences must fit the significand; fixed point is exact everywhere,
/// so I16F16 uses half its range (well beyond the ≈181 where E itself
/// would overflow).
fn grid_limit<S: Scalar>() -> i64 {
    if is_f64::<S>() {
        1 << 18
    } else if S::IS_FLOAT {
        1 << 10
    } else {
        1 << 14
    }
}

fn cross(o: P, a: P, b: P) -> i128 {
    let (ax, ay) = ((a.0 - o.0) as i128, (a.1 - o.1) as i128);
    let (bx, by) = ((b.0 - o.0) as i128, (b.1 - o.1) as i128);
    ax * by - ay * bx
}

/// The exact oracle: the boundary policy says p is inside iff
/// p' = p + (δ, δη) is. Scale everything by K and take p' = K·p + (2R+1, 1):
/// with |coordinates| ≤ R this displacement is small enough never to cross
/// a line through two vertices that p is not on, and it breaks every tie
/// the way (δ, δη) does (see the derivation in the test's comments below).
/// p' is then in general position, and the plain winding number decides.
fn oracle(poly: &[P], p: P, r: i64) -> bool {
    // K·E(p) dominates K·(d.x − d.y·a) when K > 2R(1 + a); on a line
    // (E(p) = 0) the sign is that of d.x − d.y·a, i.e. −d.y, or d.x when
    // d.y = 0: exactly the nudged-point rule.
    let a = 2 * r as i128 + 1;
    let k = 2 * r as i128 * (a + 1) + 1;
    let px = k * p.0 as i128 + a;
    let py = k * p.1 as i128 + 1;
    let mut winding = 0i32;
    let n = poly.len();
    for i in 0..n {
        let (ax, ay) = (k * poly[i].0 as i128, k * poly[i].1 as i128);
        let (bx, by) = (
            k * poly[(i + 1) % n].0 as i128,
            k * poly[(i + 1) % n].1 as i128,
        );
        let o = (bx - ax) * (py - ay) - (by - ay) * (px - ax);
        if ay <= py && by > py && o > 0 {
            winding += 1;
        } else if ay > py && by <= py && o < 0 {
            winding -= 1;
        }
    }
    winding != 0
}

fn to_poly<S: Scalar>(pts: &[P], axis: usize) -> Polygon<S, CAP> {
    let v: Vec<Vec3<S>> = pts
        .iter()
        .map(|&(x, y)| {
            let (x, y) = (S::from_i32(x as i32), S::from_i32(y as i32));
            // Embed so that the projection drops `axis` and gives back (x, y).
            match axis {
                0 => Vec3::new(S::ZERO, x, y),
                1 => Vec3::new(y, S::ZERO, x),
                _ => Vec3::new(x, y, S::ZERO),
            }
        })
        .collect();
    let poly = Polygon::new(&v).expect("valid test polygon");
    assert_eq!(poly.dominant_axis(), axis);
    poly
}

fn pt<S: Scalar>(p: P) -> Vec2<S> {
    Vec2::new(S::from_i32(p.0 as i32), S::from_i32(p.1 as i32))
}

/// Random star-shaped simple polygon around the origin, even coordinates,
/// with collinear midpoints inserted. Simple because every consecutive
/// pair turns strictly counter-clockwise about the origin and the angles
/// go round once.
fn star(rng: &mut Rng, n: usize, r: i64) -> Vec<P> {
    loop {
        let mut pts: Vec<P> = (0..n)
            .map(|_| {
                let a = rng.range(0.0, core::f64::consts::TAU);
                let rad = rng.range(0.2, 1.0) * (r - 2) as f64 / 2.0;
                (2 * (rad * a.cos()) as i64, 2 * (rad * a.sin()) as i64)
            })
            .filter(|&p| p != (0, 0))
            .collect();
        pts.sort_by(|&a, &b| {
            let ha = (a.1 < 0 || (a.1 == 0 && a.0 < 0)) as u8;
            let hb = (b.1 < 0 || (b.1 == 0 && b.0 < 0)) as u8;
            ha.cmp(&hb).then_with(|| 0.cmp(&cross((0, 0), a, b)))
        });
        pts.dedup_by(|a, b| cross((0, 0), *a, *b) == 0 && (a.0 * b.0 + a.1 * b.1) > 0);
        let m = pts.len();
        if m < 3 || (0..m).any(|i| cross((0, 0), pts[i], pts[(i + 1) % m]) <= 0) {
            continue;
        }
        return with_midpoints(rng, pts);
    }
}

/// Random convex polygon: the strict convex hull of points near a circle,
/// even coordinates, then collinear midpoints.
fn convex(rng: &mut Rng, n: usize, r: i64) -> Vec<P> {
    loop {
        let mut pts: Vec<P> = (0..n)
            .map(|_| {
                let a = rng.range(0.0, core::f64::consts::TAU);
                let rad = rng.range(0.9, 1.0) * (r - 2) as f64 / 2.0;
                (2 * (rad * a.cos()) as i64, 2 * (rad * a.sin()) as i64)
            })
            .collect();
        pts.sort();
        pts.dedup();
        let mut hull: Vec<P> = Vec::new();
        for pass in 0..2 {
            let start = hull.len();
            let iter: Vec<P> = if pass == 0 {
                pts.clone()
            } else {
                pts.iter().rev().copied().collect()
            };
            for p in iter {
                while hull.len() >= start + 2
                    && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0
                {
                    hull.pop();
                }
                hull.push(p);
            }
            hull.pop();
        }
        if hull.len() >= 3 {
            return with_midpoints(rng, hull);
        }
    }
}

/// Random convex polygon with up to `n` vertices and no two edges
/// parallel: sum distinct primitive edge vectors (and their negations, so
/// the walk closes) in angular order. This reaches hundreds of vertices on
/// small grids, where hulls of random points stay small.
fn convex_by_edges(rng: &mut Rng, n: usize, r: i64) -> Vec<P> {
    let mut m = 1;
    loop {
        // Largest m whose polygon comfortably fits: extent ≈ count·m/π.
        let count = (m + 1) * (m + 1) * 2;
        if count.min(n) as i64 * (m as i64 + 1) > r / 2 || count >= 2 * n {
            break;
        }
        m += 1;
    }
    let m = m.max(1) as i64;
    let mut dirs: Vec<P> = Vec::new();
    for dx in -m..=m {
        for dy in 0..=m {
            if (dy > 0 || dx > 0) && gcd(dx.abs(), dy) == 1 {
                dirs.push((dx, dy));
            }
        }
    }
    // A random subset of about n/2 directions (at least two, not parallel).
    let keep = (n / 2).clamp(2, dirs.len());
    for i in 0..dirs.len() {
        let j = rng.int(i as i64, dirs.len() as i64 - 1) as usize;
        dirs.swap(i, j);
    }
    dirs.truncate(keep);
    let mut all: Vec<P> = dirs.iter().flat_map(|&(x, y)| [(x, y), (-x, -y)]).collect();
    all.sort_by(|&a, &b| {
        let ha = (a.1 < 0 || (a.1 == 0 && a.0 < 0)) as u8;
        let hb = (b.1 < 0 || (b.1 == 0 && b.0 < 0)) as u8;
        ha.cmp(&hb).then_with(|| 0.cmp(&cross((0, 0), a, b)))
    });
    let mut pts = Vec::with_capacity(all.len());
    let mut p = (0i64, 0i64);
    for d in all {
        pts.push(p);
        p = (p.0 + d.0, p.1 + d.1);
    }
    let (minx, maxx) = (
        pts.iter().map(|p| p.0).min().unwrap(),
        pts.iter().map(|p| p.0).max().unwrap(),
    );
    let (miny, maxy) = (
        pts.iter().map(|p| p.1).min().unwrap(),
        pts.iter().map(|p| p.1).max().unwrap(),
    );
    let (cx, cy) = ((minx + maxx) / 2, (miny + maxy) / 2);
    let pts: Vec<P> = pts
        .iter()
        .map(|&(x, y)| (2 * (x - cx), 2 * (y - cy)))
        .collect();
    assert!(
        pts.iter().all(|p| p.0.abs() <= r && p.1.abs() <= r),
        "generator range"
    );
    with_midpoints(rng, pts)
}

fn with_midpoints(rng: &mut Rng, pts: Vec<P>) -> Vec<P> {
    let n = pts.len();
    let mut out = Vec::with_capacity(2 * n);
    for i in 0..n {
        out.push(pts[i]);
        let b = pts[(i + 1) % n];
        if rng.int(0, 3) == 0 {
            out.push(((pts[i].0 + b.0) / 2, (pts[i].1 + b.1) / 2));
        }
    }
    if rng.int(0, 1) == 0 {
        out.reverse();
    }
    assert!(out.len() <= CAP);
    out
}

/// Points on and near the boundary (vertices, lattice points on edges, one
/// step off them) and random points in the bounding box.
fn probe_points(rng: &mut Rng, poly: &[P], r: i64, random: usize) -> Vec<P> {
    let n = poly.len();
    let mut out = Vec::new();
    // Big polygons: probe about 300 edges (from a random start), which
    // keeps the debug-build test time down without losing coverage.
    let stride = n.div_ceil(300);
    let start = rng.int(0, stride as i64 - 1) as usize;
    for i in (start..n).step_by(stride) {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        for (dx, dy) in [(0, 0), (1, 0), (-1, 0), (0, 1), (0, -1), (1, 1), (-1, -1)] {
            out.push((a.0 + dx, a.1 + dy));
        }
        let g = gcd((b.0 - a.0).abs(), (b.1 - a.1).abs()).max(1);
        let (sx, sy) = ((b.0 - a.0) / g, (b.1 - a.1) / g);
        for _ in 0..3 {
            let k = rng.int(0, g);
            out.push((a.0 + k * sx, a.1 + k * sy));
        }
    }
    for _ in 0..random {
        out.push((rng.int(-r, r), rng.int(-r, r)));
    }
    out.retain(|p| p.0.abs() <= r && p.1.abs() <= r);
    out
}

fn gcd(a: i64, b: i64) -> i64 {
    if b == 0 { a } else { gcd(b, a % b) }
}

fn slab_storage<S: Scalar>(poly: &Polygon<S, CAP>) -> (Vec<S>, Vec<u32>, Vec<u32>) {
    let n = poly.edges().len();
    let mut ys = vec![S::ZERO; n];
    let mut starts = vec![0u32; n];
    let mut none: [u32; 0] = [];
    let needed = match SlabIndex::build(poly, &mut ys, &mut starts, &mut none) {
        Err(SlabError::EdgeStorage { needed }) => needed,
        Ok(_) => 0,
        Err(e) => panic!("unexpected {e}"),
    };
    assert!(needed <= n * (n - 1), "documented bound n(n-1)");
    (ys, starts, vec![0u32; needed])
}

fn check_polygon<S: Scalar>(rng: &mut Rng, pts: &[P], r: i64, axis: usize, random: usize) -> usize {
    let poly = to_poly::<S>(pts, axis);
    let (mut ys, mut starts, mut edges) = slab_storage(&poly);
    let slabs = SlabIndex::build(&poly, &mut ys, &mut starts, &mut edges).expect("sized");
    for p in probe_points(rng, pts, r, random) {
        let want = oracle(pts, p, r);
        let q = pt::<S>(p);
        let got = [
            poly.contains(q, InclusionTest::Crossing),
            poly.contains(q, InclusionTest::HalfPlane),
            poly.contains(q, InclusionTest::Fan),
            slabs.contains(q),
        ];
        assert!(
            got.iter().all(|&g| g == want),
            "{}: point {p:?}: oracle {want}, [crossing, half-plane, fan, slab] = {got:?}, convex {}, polygon {pts:?}",
            S::NAME,
            poly.is_convex()
        );
    }
    poly.edges().len()
}

fn sizes(rng: &mut Rng, max: usize) -> usize {
    match rng.int(0, 9) {
        0 => rng.int(3, max as i64) as usize,
        1 => rng.int(3, 60) as usize,
        _ => rng.int(3, 12) as usize,
    }
}

fn oracle_small_cases<S: Scalar>() {
    // Hand-made cases with collinear vertices, horizontal edges and a
    // notch, both orientations, all three projection axes.
    let cases: [&[P]; 4] = [
        &[(0, 0), (4, 0), (4, 4), (0, 4)],
        &[
            (0, 0),
            (2, 0),
            (4, 0),
            (4, 2),
            (4, 4),
            (2, 4),
            (0, 4),
            (0, 2),
        ],
        &[(0, 0), (6, 0), (6, 6), (3, 2), (0, 6)],
        &[(0, 0), (3, 3), (6, 0), (6, 6), (0, 6)],
    ];
    let mut rng = Rng::new(1);
    for (ci, c) in cases.iter().enumerate() {
        for rev in [false, true] {
            let mut pts = c.to_vec();
            if rev {
                pts.reverse();
            }
            for axis in 0..3 {
                let poly = to_poly::<S>(&pts, axis);
                assert_eq!(poly.is_convex(), ci < 2);
                check_polygon::<S>(&mut rng, &pts, 8, axis, 0);
                // Every lattice point and half-lattice point of the box.
                for x in -2..=16 {
                    for y in -2..=16 {
                        let p = (x, y);
                        let q: Vec2<S> = Vec2::new(
                            S::from_i32(x as i32) * S::HALF,
                            S::from_i32(y as i32) * S::HALF,
                        );
                        let scaled: Vec<P> = pts.iter().map(|&(a, b)| (2 * a, 2 * b)).collect();
                        let want = oracle(&scaled, p, 16);
                        assert_eq!(
                            poly.contains(q, InclusionTest::Crossing),
                            want,
                            "{p:?}/2 in case {ci} rev {rev}"
                        );
                        assert_eq!(poly.contains(q, InclusionTest::Fan), want);
                        assert_eq!(poly.contains(q, InclusionTest::HalfPlane), want);
                    }
                }
            }
        }
    }
}

fn agreement_random_convex<S: Scalar>() {
    let mut rng = Rng::new(0xC0_4E_E5);
    let r = grid_limit::<S>();
    let cases = if is_f64::<S>() { 80 } else { 50 };
    let mut largest = 0;
    for case in 0..cases {
        let n = if case < 3 {
            1024
        } else {
            sizes(&mut rng, 1024)
        };
        let pts = if case % 2 == 0 {
            convex_by_edges(&mut rng, n, r)
        } else {
            convex(&mut rng, n, r)
        };
        let axis = case % 3;
        let poly = to_poly::<S>(&pts, axis);
        assert!(poly.is_convex(), "{pts:?}");
        largest = largest.max(check_polygon::<S>(&mut rng, &pts, r, axis, 100));
    }
    std::println!("{}: largest convex polygon {largest} vertices", S::NAME);
}

fn agreement_random_simple<S: Scalar>() {
    let mut rng = Rng::new(0x51_3B_1E);
    let r = grid_limit::<S>();
    let cases = if is_f64::<S>() { 80 } else { 50 };
    let mut largest = 0;
    for case in 0..cases {
        let n = if case < 2 {
            1024
        } else {
            sizes(&mut rng, 1024)
        };
        let pts = star(&mut rng, n, r);
        largest = largest.max(check_polygon::<S>(&mut rng, &pts, r, case % 3, 100));
    }
    std::println!("{}: largest simple polygon {largest} vertices", S::NAME);
}

/// A star polygon and the fan of triangles (0, vᵢ, vᵢ₊₁) partition the same
/// region; the origin is a vertex of every triangle. For every probe point
/// the number of triangles claiming it equals the polygon's claim (0 or 1):
/// shared edges and the shared vertex are claimed exactly once.
fn shared_edges_fan_partition<S: Scalar>() {
    let mut rng = Rng::new(77);
    let r = grid_limit::<S>().min(1 << 12);
    for case in 0..30 {
        let n = rng.int(3, 24) as usize;
        let mut pts = star(&mut rng, n, r);
        // Keep counter-clockwise so the triangles (0, a, b) are too.
        if (0..pts.len())
            .map(|i| cross((0, 0), pts[i], pts[(i + 1) % pts.len()]))
            .sum::<i128>()
            < 0
        {
            pts.reverse();
        }
        let axis = case % 3;
        let whole = to_poly::<S>(&pts, axis);
        let m = pts.len();
        let tris: Vec<Vec<P>> = (0..m)
            .map(|i| vec![(0, 0), pts[i], pts[(i + 1) % m]])
            .collect();
        let polys: Vec<Polygon<S, CAP>> = tris.iter().map(|t| to_poly::<S>(t, axis)).collect();
        let mut probes = probe_points(&mut rng, &pts, r, 200);
        for t in &tris {
            probes.extend(probe_points(&mut rng, t, r, 0));
        }
        probes.push((0, 0));
        for p in probes {
            let q = pt::<S>(p);
            for test in [
                InclusionTest::Crossing,
                InclusionTest::HalfPlane,
                InclusionTest::Fan,
            ] {
                let claims = polys.iter().filter(|t| t.contains(q, test)).count();
                let expect = whole.contains(q, InclusionTest::Crossing) as usize;
                assert_eq!(
                    claims,
                    expect,
                    "{}: {p:?} claimed {claims}×, {test:?}",
                    S::NAME
                );
            }
        }
    }
}

/// Two polygons sharing an edge, split from a convex polygon along a
/// diagonal: every point strictly inside the shared edge is claimed by
/// exactly one; every point at all by at most one, and by one iff the
/// whole polygon claims it.
fn shared_edge_diagonal_split<S: Scalar>() {
    let mut rng = Rng::new(99);
    let r = grid_limit::<S>().min(1 << 12);
    for case in 0..40 {
        let n = rng.int(4, 40) as usize;
        let pts = convex(&mut rng, n, r);
        let m = pts.len();
        if m < 4 {
            continue;
        }
        let i = rng.int(0, m as i64 - 1) as usize;
        let j = (i + rng.int(2, m as i64 - 2) as usize) % m;
        let (lo, hi) = (i.min(j), i.max(j));
        let p1: Vec<P> = pts[lo..=hi].to_vec();
        let mut p2: Vec<P> = pts[hi..].to_vec();
        p2.extend_from_slice(&pts[..=lo]);
        let area = |q: &[P]| {
            (1..q.len() - 1)
                .map(|k| cross(q[0], q[k], q[k + 1]))
                .sum::<i128>()
        };
        if p1.len() < 3 || p2.len() < 3 || area(&p1) == 0 || area(&p2) == 0 {
            continue;
        }
        let axis = case % 3;
        let (a, b) = (to_poly::<S>(&p1, axis), to_poly::<S>(&p2, axis));
        let whole = to_poly::<S>(&pts, axis);
        let (s, e) = (pts[lo], pts[hi]);
        let g = gcd((e.0 - s.0).abs(), (e.1 - s.1).abs()).max(1);
        let (sx, sy) = ((e.0 - s.0) / g, (e.1 - s.1) / g);
        for k in 0..=g {
            let p = (s.0 + k * sx, s.1 + k * sy);
            let q = pt::<S>(p);
            let claims = a.contains(q, InclusionTest::Fan) as usize
                + b.contains(q, InclusionTest::Fan) as usize;
            if k > 0 && k < g {
                assert_eq!(claims, 1, "{p:?} on the shared edge");
            } else {
                assert!(claims <= 1);
            }
        }
        for p in probe_points(&mut rng, &pts, r, 100) {
            let q = pt::<S>(p);
            let claims = a.contains(q, InclusionTest::HalfPlane) as usize
                + b.contains(q, InclusionTest::HalfPlane) as usize;
            assert_eq!(claims, whole.contains(q, InclusionTest::HalfPlane) as usize);
        }
    }
}

/// A 4×4 grid of unit squares, each cut into two triangles along
/// alternating diagonals: horizontal, vertical and diagonal shared edges.
/// Every lattice and half-lattice point of the interior is claimed once.
fn shared_edges_grid_tiling<S: Scalar>() {
    let mut tiles: Vec<Vec<P>> = Vec::new();
    for x in 0..4i64 {
        for y in 0..4i64 {
            let (a, b, c, d) = (
                (2 * x, 2 * y),
                (2 * x + 2, 2 * y),
                (2 * x + 2, 2 * y + 2),
                (2 * x, 2 * y + 2),
            );
            if (x + y) % 2 == 0 {
                tiles.push(vec![a, b, c]);
                tiles.push(vec![a, c, d]);
            } else {
                tiles.push(vec![a, b, d]);
                tiles.push(vec![b, c, d]);
            }
        }
    }
    let polys: Vec<Polygon<S, CAP>> = tiles.iter().map(|t| to_poly::<S>(t, 2)).collect();
    for x in 0..=16 {
        for y in 0..=16 {
            let q = Vec2::new(S::from_i32(x) * S::HALF, S::from_i32(y) * S::HALF);
            let claims = polys
                .iter()
                .filter(|t| t.contains(q, InclusionTest::Crossing))
                .count();
            // Inside the region [0, 8)²: the right and top sides are open.
            let want = (x < 16 && y < 16) as usize;
            assert_eq!(claims, want, "({x}, {y})/2");
        }
    }
}

fn degenerate_polygons_are_errors<S: Scalar>() {
    use crate::ray::PolygonError;
    let z = S::ZERO;
    let o = S::ONE;
    let v = |x: S, y: S| Vec3::new(x, y, z);
    let collinear = [v(z, z), v(o, o), v(o + o, o + o)];
    assert_eq!(
        Polygon::<S, 8>::new(&collinear).err(),
        Some(PolygonError::Degenerate)
    );
    assert_eq!(
        Polygon::<S, 8>::new(&[v(z, z), v(o, z)]).err(),
        Some(PolygonError::Degenerate)
    );
    let dup = [v(z, z), v(z, z), v(o, z), v(o, z), v(z, z)];
    assert_eq!(
        Polygon::<S, 8>::new(&dup).err(),
        Some(PolygonError::Degenerate)
    );
    let sq = [v(z, z), v(o, z), v(o, o), v(z, o)];
    let bent = [v(z, z), v(o, z), Vec3::new(o, o, o), v(z, o)];
    assert_eq!(
        Polygon::<S, 8>::new(&bent).err(),
        Some(PolygonError::NotPlanar)
    );
    assert_eq!(
        Polygon::<S, 3>::new(&sq).err(),
        Some(PolygonError::TooManyVertices { capacity: 3 })
    );
    if S::IS_FLOAT {
        let nan = S::from_f64(0.0) / S::from_f64(0.0);
        assert_eq!(
            Polygon::<S, 8>::new(&[v(z, z), v(o, nan), v(o, o)]).err(),
            Some(PolygonError::NonFinite)
        );
    }
    // Far-away query points (overflowing edge functions in fixed point)
    // are simply outside.
    let poly = Polygon::<S, 8>::new(&sq).unwrap();
    let far = Vec2::new(S::MAX, S::MIN);
    for t in [
        InclusionTest::Crossing,
        InclusionTest::HalfPlane,
        InclusionTest::Fan,
    ] {
        assert!(!poly.contains(far, t));
    }
}

/// `A·x + B·y + C` from `Edge2::coefficients` equals `Edge2::value`
/// (exactly, on the integer grid).
fn edge_equation_coefficients<S: Scalar>() {
    let mut rng = Rng::new(8);
    // Small enough that E itself fits I16F16.
    let r = if S::IS_FLOAT {
        grid_limit::<S>() / 4
    } else {
        22
    };
    for _ in 0..500 {
        let pts = [
            (rng.int(-r, r), rng.int(-r, r)),
            (rng.int(-r, r), rng.int(-r, r)),
            (rng.int(-r, r), rng.int(-r, r)),
        ];
        let Ok(poly) = Polygon::<S, 3>::new(&[
            Vec3::new(pt::<S>(pts[0]).x, pt::<S>(pts[0]).y, S::ZERO),
            Vec3::new(pt::<S>(pts[1]).x, pt::<S>(pts[1]).y, S::ZERO),
            Vec3::new(pt::<S>(pts[2]).x, pt::<S>(pts[2]).y, S::ZERO),
        ]) else {
            continue;
        };
        let p = (rng.int(-r, r), rng.int(-r, r));
        for e in poly.edges() {
            let (a, b, c) = e.coefficients().unwrap();
            let q = pt::<S>(p);
            assert_eq!(a * q.x + b * q.y + c, e.value(q).unwrap());
            let exact = cross(
                (e.a.x.to_f64() as i64, e.a.y.to_f64() as i64),
                (
                    (e.a.x + e.d.x).to_f64() as i64,
                    (e.a.y + e.d.y).to_f64() as i64,
                ),
                p,
            );
            assert_eq!(e.value(q).unwrap().to_f64(), exact as f64);
        }
    }
}

/// Posed (rotated, translated: inexact) planar polygons pass the
/// coplanarity check, and a ray through an interior point hits with every
/// test, at the right distance.
fn posed_polygons_hit<S: Scalar>() {
    use crate::ray::Ray;
    use crate::transform::{Euler, Pose};
    let mut rng = Rng::new(21);
    let scale = if S::IS_FLOAT { 3.0 } else { 8.0 };
    // An L-shaped (concave) hexagon and a convex pentagon, object space.
    let shapes: [&[(f64, f64)]; 2] = [
        &[
            (0.0, 0.0),
            (2.0, 0.0),
            (2.0, 1.0),
            (1.0, 1.0),
            (1.0, 2.0),
            (0.0, 2.0),
        ],
        &[(0.0, 0.0), (2.0, 0.0), (2.5, 1.0), (1.0, 2.0), (-0.5, 1.0)],
    ];
    for _ in 0..100 {
        let pose = Pose::new(
            super::v3::<S>(
                rng.range(-4.0, 4.0),
                rng.range(-4.0, 4.0),
                rng.range(-4.0, 4.0),
            ),
            Euler::new(
                S::from_f64(rng.range(-3.0, 3.0)),
                S::from_f64(rng.range(-1.5, 1.5)),
                S::from_f64(rng.range(-3.0, 3.0)),
            ),
        );
        let m = pose.object_to_world();
        for shape in shapes {
            let verts: Vec<Vec3<S>> = shape
                .iter()
                .map(|&(x, y)| m.transform_point3(super::v3(x * scale, y * scale, 0.0)))
                .collect();
            let poly = Polygon::<S, 8>::new(&verts).expect("planar within tolerance");
            let inside = m.transform_point3(super::v3(0.5 * scale, 0.5 * scale, 0.0));
            let eye = m.transform_point3(super::v3(0.3 * scale, 0.7 * scale, 5.0));
            let ray = Ray::through(eye, inside).unwrap();
            for test in [
                InclusionTest::Crossing,
                InclusionTest::HalfPlane,
                InclusionTest::Fan,
            ] {
                let t = poly.clone().with_test(test).intersect(&ray, S::ZERO);
                let t = t.expect("hit").to_f64();
                assert!(
                    (t - 1.0).abs() < 1e3 * S::EPSILON.to_f64(),
                    "{} t = {t}",
                    S::NAME
                );
            }
            let outside = m.transform_point3(super::v3(1.5 * scale, 1.5 * scale, 0.0));
            let miss = Ray::through(eye, outside).unwrap();
            if shape.len() == 6 {
                assert!(poly.intersect(&miss, S::ZERO).is_none());
            }
        }
    }
}

per_scalar!(
    posed_polygons_hit,
    edge_equation_coefficients,
    oracle_small_cases,
    agreement_random_convex,
    agreement_random_simple,
    shared_edges_fan_partition,
    shared_edge_diagonal_split,
    shared_edges_grid_tiling,
    degenerate_polygons_are_errors,
    lattice_exact,
);

/// Adversarial lattice for item 7 of issue 14: coordinates `0.5 + X·h` with
/// `h = 2^-shift` and integer `0 ≤ X < 2^(shift−1)`, so every coordinate
/// lies in [0.5, 1), where it is exactly representable in `S` (`shift` ≤ 24
/// for f32, ≤ 53 for f64, ≤ 16 for I16F16) and `h` is one unit in the last
/// place: the finest grid the type can express there.
struct Lattice {
    shift: u32,
}

impl Lattice {
    fn half(&self) -> i64 {
        1 << (self.shift - 1)
    }
    /// A lattice coordinate at fraction `f` of the range, plus `odd`.
    fn at(&self, f: f64, odd: i64) -> i64 {
        (f * self.half() as f64) as i64 + odd
    }
    fn coord<S: Scalar>(&self, x: i64) -> S {
        // 0.5 + x·2^-shift is exact in f64 (shift ≤ 53, x < 2^(shift−1)),
        // and in [0.5, 1) it is a multiple of S's unit there: exact in S.
        let v = 0.5 + x as f64 * 2f64.powi(-(self.shift as i32));
        let s = S::from_f64(v);
        assert_eq!(s.to_f64(), v, "lattice point not representable");
        s
    }
    fn pt<S: Scalar>(&self, p: P) -> Vec2<S> {
        Vec2::new(self.coord(p.0), self.coord(p.1))
    }
}

/// Exact oracle on lattice integers (i128; |X| < 2⁵², so every product is
/// below 2¹⁰⁶): the crossing rule applied to the nudged point
/// `p' = p + (δ, δη)` symbolically. An edge with one end at `y ≤ p.y` and
/// the other above is counted when `p'` is strictly left of it directed
/// upward: `E(p') = E(p) − d.y·δ + d.x·δη`, whose sign is that of `E(p)`,
/// or of `−d.y` when `E(p) = 0`, so a point on the edge is never strictly
/// left. Returns (inside, on the boundary).
fn lattice_oracle(poly: &[P], p: P) -> (bool, bool) {
    let n = poly.len();
    let mut inside = false;
    let mut on = false;
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        let e = cross(a, b, p);
        let within = p.0 >= a.0.min(b.0)
            && p.0 <= a.0.max(b.0)
            && p.1 >= a.1.min(b.1)
            && p.1 <= a.1.max(b.1);
        on |= e == 0 && within;
        if (a.1 <= p.1) != (b.1 <= p.1) {
            let up = b.1 > a.1;
            if (up && e > 0) || (!up && e < 0) {
                inside = !inside;
            }
        }
    }
    (inside, on)
}

/// The lattice polygons: a generic convex quadrilateral, a concave
/// pentagon, a quadrilateral with an edge along (7, 3) (so lattice points
/// lie exactly on it) and a triangle with a horizontal edge.
fn lattice_polygons(l: &Lattice) -> Vec<Vec<P>> {
    let v = |fx: f64, ox: i64, fy: f64, oy: i64| (l.at(fx, ox), l.at(fy, oy));
    let s = l.at(0.8, 0) / 7;
    let base = v(0.1, 0, 0.1, 0);
    vec![
        vec![
            v(0.02, 3, 0.05, 7),
            v(0.97, 1, 0.11, 5),
            v(0.83, 11, 0.96, 1),
            v(0.07, 5, 0.71, 3),
        ],
        vec![
            v(0.02, 3, 0.05, 7),
            v(0.97, 1, 0.11, 5),
            v(0.83, 11, 0.96, 1),
            v(0.45, 9, 0.40, 13),
            v(0.07, 5, 0.71, 3),
        ],
        vec![
            base,
            (base.0 + 7 * s, base.1 + 3 * s),
            v(0.6, 1, 0.9, 3),
            v(0.05, 7, 0.6, 5),
        ],
        vec![v(0.1, 0, 0.2, 0), v(0.9, 0, 0.2, 0), v(0.37, 3, 0.93, 1)],
    ]
}

/// Per method (crossing, half-plane, fan, slab): wrong answers off the
/// boundary, queries off it, wrong answers on it, queries on it, over
/// (2G + 1)² lattice points around every vertex and every edge midpoint
/// of every lattice polygon, in both orientations.
fn lattice_errors<S: Scalar>(l: &Lattice) -> [[usize; 4]; 4] {
    const G: i64 = 16;
    let mut out = [[0usize; 4]; 4];
    for base in lattice_polygons(l) {
        for rev in [false, true] {
            let mut pts = base.clone();
            if rev {
                pts.reverse();
            }
            let verts: Vec<Vec3<S>> = pts
                .iter()
                .map(|&p| {
                    let q = l.pt::<S>(p);
                    Vec3::new(q.x, q.y, S::ZERO)
                })
                .collect();
            let poly = Polygon::<S, 8>::new(&verts).expect("lattice polygon");
            let n = poly.edges().len();
            assert_eq!(n, pts.len());
            let (mut ys, mut starts, mut edges) =
                (vec![S::ZERO; n], vec![0u32; n], vec![0u32; n * (n - 1)]);
            let slabs = SlabIndex::build(&poly, &mut ys, &mut starts, &mut edges).expect("sized");
            let mut centers = pts.clone();
            for i in 0..n {
                let (a, b) = (pts[i], pts[(i + 1) % n]);
                centers.push(((a.0 + b.0) / 2, (a.1 + b.1) / 2));
            }
            for c in centers {
                for dx in -G..=G {
                    for dy in -G..=G {
                        let p = (c.0 + dx, c.1 + dy);
                        let (want, on) = lattice_oracle(&pts, p);
                        let q = l.pt::<S>(p);
                        let got = [
                            poly.contains(q, InclusionTest::Crossing),
                            poly.contains(q, InclusionTest::HalfPlane),
                            poly.contains(q, InclusionTest::Fan),
                            slabs.contains(q),
                        ];
                        for (m, &g) in got.iter().enumerate() {
                            let k = if on { 2 } else { 0 };
                            out[m][k] += (g != want) as usize;
                            out[m][k + 1] += 1;
                        }
                    }
                }
            }
        }
    }
    out
}

/// Item 7 of issue 14: every method is exactly right on the adversarial
/// lattice, off the boundary and (by the ownership rule) on it, at the
/// finest spacing each type has in [0.5, 1) and, for f64, also at 2⁻²⁴.
fn lattice_exact<S: Scalar>() {
    let shifts: &[u32] = if is_f64::<S>() {
        &[24, 53]
    } else if S::IS_FLOAT {
        &[24]
    } else {
        &[16]
    };
    let names = ["crossing", "half-plane", "fan", "slab"];
    let mut bad = false;
    for &shift in shifts {
        let calls = || crate::scalar::predicates::tests::EXACT_CALLS.with(|c| c.get());
        let before = calls();
        let r = lattice_errors::<S>(&Lattice { shift });
        std::println!(
            "{} h=2^-{shift}: exact stage ran {} times for {} queries",
            S::NAME,
            calls() - before,
            r[0][1] + r[0][3]
        );
        for (m, c) in r.iter().enumerate() {
            std::println!(
                "{} h=2^-{shift} {:10}: off boundary {}/{} wrong ({:.2} %), on boundary {}/{} wrong",
                S::NAME,
                names[m],
                c[0],
                c[1],
                100.0 * c[0] as f64 / c[1] as f64,
                c[2],
                c[3]
            );
            assert!(c[3] > 0, "the lattice has boundary points");
            bad |= c[0] != 0 || c[2] != 0;
        }
    }
    assert!(
        !bad,
        "{}: misclassified lattice points (see above)",
        S::NAME
    );
}
