//! Watertightness: rays from inside closed meshes aimed exactly at edges
//! and vertices must hit. The plane + dominant-axis polygon method is
//! measured on the same rays (its leak rate is asserted within a stated window).

use super::{Rng, per_scalar, v3};
use crate::math::Vec3;
use crate::ray::{InclusionTest, Mesh, Polygon, Ray, Triangle};
use crate::scalar::Scalar;
use crate::transform::{Euler, Pose};

extern crate std;
use std::println;
use std::vec::Vec;

const OCTAHEDRON: [[u32; 3]; 8] = [
    [0, 2, 4],
    [2, 1, 4],
    [1, 3, 4],
    [3, 0, 4],
    [2, 0, 5],
    [1, 2, 5],
    [3, 1, 5],
    [0, 3, 5],
];

/// Cube corners: bit 0 → x, bit 1 → y, bit 2 → z. Two triangles a face,
/// outward winding.
const CUBE: [[u32; 3]; 12] = [
    [0, 2, 3],
    [0, 3, 1],
    [4, 5, 7],
    [4, 7, 6],
    [0, 1, 5],
    [0, 5, 4],
    [2, 6, 7],
    [2, 7, 3],
    [0, 4, 6],
    [0, 6, 2],
    [1, 3, 7],
    [1, 7, 5],
];

struct Leaks {
    rays: usize,
    watertight: usize,
    polygon: usize,
    polygon_at_vertices: usize,
    random_rays: usize,
    random_polygon: usize,
    /// Leaks of the polygon method with the half-plane and the fan
    /// inclusion test (`polygon` is the crossing test).
    by_test: [usize; 2],
}

/// `exact`: no rotation, integer scale and offset, so the edge targets are
/// exactly on the edges and edge functions are exactly zero (the
/// higher-precision fallback runs); otherwise a random pose.
fn run_mesh<S: Scalar>(
    rng: &mut Rng,
    local: &[[f64; 3]],
    tris: &[[u32; 3]],
    exact: bool,
    out: &mut Leaks,
) {
    let scale = if exact {
        4.0
    } else if S::IS_FLOAT {
        1.7
    } else {
        6.0
    };
    for _ in 0..12 {
        let pose = if exact {
            Pose::new(
                v3::<S>(
                    rng.int(-3, 3) as f64,
                    rng.int(-3, 3) as f64,
                    rng.int(-3, 3) as f64,
                ),
                Euler::ZERO,
            )
        } else {
            Pose::new(
                v3::<S>(
                    rng.range(-3.0, 3.0),
                    rng.range(-3.0, 3.0),
                    rng.range(-3.0, 3.0),
                ),
                Euler::new(
                    S::from_f64(rng.range(-3.0, 3.0)),
                    S::from_f64(rng.range(-1.5, 1.5)),
                    S::from_f64(rng.range(-3.0, 3.0)),
                ),
            )
        };
        let m = pose.object_to_world();
        let verts: Vec<Vec3<S>> = local
            .iter()
            .map(|p| m.transform_point3(v3(p[0] * scale, p[1] * scale, p[2] * scale)))
            .collect();
        let mesh = Mesh::new(&verts, tris).unwrap();
        let polys: Vec<Polygon<S, 3>> = tris
            .iter()
            .map(|t| {
                Polygon::new(&[
                    verts[t[0] as usize],
                    verts[t[1] as usize],
                    verts[t[2] as usize],
                ])
                .unwrap()
            })
            .collect();
        // Every edge once per triangle that has it; targets exactly on the
        // edge (the vertices included), k/16 of the way in S arithmetic.
        let mut targets = Vec::new();
        for t in tris {
            for e in 0..3 {
                let (a, b) = (verts[t[e] as usize], verts[t[(e + 1) % 3] as usize]);
                for k in 0..=16 {
                    targets.push((a + (b - a) * S::from_f64(k as f64 / 16.0), k % 16 == 0));
                }
            }
        }
        let center = m.transform_point3(Vec3::ZERO);
        // Sanity: aimed at face interiors, both methods always hit.
        for t in tris {
            let g = (verts[t[0] as usize] + verts[t[1] as usize] + verts[t[2] as usize])
                * S::from_f64(1.0 / 3.0);
            let ray = Ray::through(center, g).unwrap();
            assert!(mesh.intersect(&ray, S::ZERO).is_some());
            assert!(polys.iter().any(|p| p.intersect(&ray, S::ZERO).is_some()));
            for test in [InclusionTest::HalfPlane, InclusionTest::Fan] {
                assert!(
                    polys.iter().any(|p| p
                        .clone()
                        .with_test(test)
                        .intersect(&ray, S::ZERO)
                        .is_some())
                );
            }
        }
        // Control: random directions from inside, not aimed at edges.
        for _ in 0..400 {
            let o = 0.3 * scale;
            let origin =
                m.transform_point3(v3(rng.range(-o, o), rng.range(-o, o), rng.range(-o, o)));
            let d = v3::<S>(
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
            );
            let Ok(ray) = Ray::new(origin, d) else {
                continue;
            };
            out.random_rays += 1;
            assert!(mesh.intersect(&ray, S::ZERO).is_some());
            if !polys.iter().any(|p| p.intersect(&ray, S::ZERO).is_some()) {
                out.random_polygon += 1;
            }
        }
        for (i, &(target, at_vertex)) in targets.iter().enumerate() {
            let origin = if i % 4 == 0 {
                center
            } else {
                let o = 0.3 * scale;
                m.transform_point3(v3(rng.range(-o, o), rng.range(-o, o), rng.range(-o, o)))
            };
            let Ok(ray) = Ray::through(origin, target) else {
                continue;
            };
            out.rays += 1;
            if mesh.intersect(&ray, S::ZERO).is_none() {
                out.watertight += 1;
            }
            if !polys.iter().any(|p| p.intersect(&ray, S::ZERO).is_some()) {
                out.polygon += 1;
                out.polygon_at_vertices += at_vertex as usize;
            }
            for (k, test) in [InclusionTest::HalfPlane, InclusionTest::Fan]
                .into_iter()
                .enumerate()
            {
                if !polys
                    .iter()
                    .any(|p| p.clone().with_test(test).intersect(&ray, S::ZERO).is_some())
                {
                    out.by_test[k] += 1;
                }
            }
        }
    }
}

fn closed_meshes_do_not_leak<S: Scalar>() {
    let octa = [
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ];
    let cube: Vec<[f64; 3]> = (0..8)
        .map(|i| {
            let c = |b: u32| if i & (1 << b) != 0 { 1.0 } else { -1.0 };
            [c(0), c(1), c(2)]
        })
        .collect();
    let mut rng = Rng::new(2013);
    let mut leaks = Leaks {
        rays: 0,
        watertight: 0,
        polygon: 0,
        polygon_at_vertices: 0,
        random_rays: 0,
        random_polygon: 0,
        by_test: [0; 2],
    };
    for exact in [false, false, false, true] {
        run_mesh::<S>(&mut rng, &octa, &OCTAHEDRON, exact, &mut leaks);
        run_mesh::<S>(&mut rng, &cube, &CUBE, exact, &mut leaks);
    }
    println!(
        "{}: {} rays at edges/vertices from inside: watertight leaks {} ({:.3}%), plane + dominant-axis polygon leaks {} ({:.3}%; {} of them aimed at vertices)",
        S::NAME,
        leaks.rays,
        leaks.watertight,
        100.0 * leaks.watertight as f64 / leaks.rays as f64,
        leaks.polygon,
        100.0 * leaks.polygon as f64 / leaks.rays as f64,
        leaks.polygon_at_vertices,
    );
    println!(
        "{}: same rays, polygon leaks by inclusion test: crossing {} ({:.3}%), half-plane {} ({:.3}%), fan {} ({:.3}%)",
        S::NAME,
        leaks.polygon,
        100.0 * leaks.polygon as f64 / leaks.rays as f64,
        leaks.by_test[0],
        100.0 * leaks.by_test[0] as f64 / leaks.rays as f64,
        leaks.by_test[1],
        100.0 * leaks.by_test[1] as f64 / leaks.rays as f64,
    );
    println!(
        "{}: control, {} random-direction rays from inside: watertight leaks 0, polygon leaks {}",
        S::NAME,
        leaks.random_rays,
        leaks.random_polygon
    );
    assert_eq!(leaks.watertight, 0, "{}: watertight mode leaked", S::NAME);
    // The plane + inclusion method leaks at shared edges by design (the
    // hit point is rounded onto each face's plane, then tested against
    // that face's edges alone). Measured: 18.5 % (f32), 18.5 % (f64),
    // 20.4 % (I16F16) of these rays; the window states that rate. Exact
    // inclusion makes the three tests agree ray for ray, and random rays,
    // which almost never pass within rounding of an edge, never leak.
    let rate = 100.0 * leaks.polygon as f64 / leaks.rays as f64;
    assert!(
        (15.0..=25.0).contains(&rate),
        "{}: plane + inclusion leak rate {rate:.3}% outside 15..25%",
        S::NAME
    );
    assert_eq!(leaks.by_test, [leaks.polygon; 2], "{}", S::NAME);
    assert_eq!(leaks.random_polygon, 0, "{}", S::NAME);
}

fn triangle_basics<S: Scalar>() {
    let tri = Triangle::new(v3::<S>(0.0, 0.0, 2.0), v3(1.0, 0.0, 2.0), v3(0.0, 1.0, 2.0));
    let ray = Ray::new(v3(0.25, 0.25, 0.0), v3(0.0, 0.0, 1.0)).unwrap();
    let h = tri.intersect(&ray, S::ZERO).unwrap();
    let e = 16.0 * S::EPSILON.to_f64();
    assert!((h.t.to_f64() - 2.0).abs() <= e);
    assert!((h.u.to_f64() - 0.5).abs() <= e);
    assert!((h.v.to_f64() - 0.25).abs() <= e);
    assert!((h.w.to_f64() - 0.25).abs() <= e);
    // Backwards along the ray: no hit (t ≤ 0); reversed winding still hits.
    let back = Ray::new(v3(0.25, 0.25, 3.0), v3(0.0, 0.0, 1.0)).unwrap();
    assert!(tri.intersect(&back, S::ZERO).is_none());
    let rev = Triangle::new(tri.v[0], tri.v[2], tri.v[1]);
    assert!(rev.intersect(&ray, S::ZERO).is_some());
    // Exactly on the edge x + y = 1 and on vertex (1, 0): hits.
    for (x, y) in [(0.5, 0.5), (1.0, 0.0), (0.0, 0.0)] {
        let r = Ray::new(v3(x, y, 0.0), v3(0.0, 0.0, 1.0)).unwrap();
        assert!(tri.intersect(&r, S::ZERO).is_some(), "({x}, {y})");
    }
    // Just outside.
    let r = Ray::new(v3(0.75, 0.5, 0.0), v3(0.0, 0.0, 1.0)).unwrap();
    assert!(tri.intersect(&r, S::ZERO).is_none());
    // Degenerate triangle and a ray in the triangle's plane: no hit.
    let flat = Triangle::new(v3::<S>(0.0, 0.0, 2.0), v3(1.0, 0.0, 2.0), v3(2.0, 0.0, 2.0));
    assert!(flat.intersect(&ray, S::ZERO).is_none());
    let inplane = Ray::new(v3(-1.0, 0.2, 2.0), v3(1.0, 0.0, 0.0)).unwrap();
    assert!(tri.intersect(&inplane, S::ZERO).is_none());
    // Extreme values: no panic.
    let big = Triangle::new(
        Vec3::new(S::MAX, S::MIN, S::MAX),
        Vec3::new(S::MIN, S::MAX, S::MIN),
        Vec3::new(S::MAX, S::MAX, S::MIN),
    );
    let _ = big.intersect(&ray, S::ZERO);
    let tiny_dir = Ray::new(Vec3::ZERO, Vec3::new(S::EPSILON, S::ZERO, S::EPSILON)).unwrap();
    let _ = tri.intersect(&tiny_dir, S::ZERO);
}

fn mesh_validation_and_ties<S: Scalar>() {
    use crate::ray::MeshError;
    let verts = [
        v3::<S>(0.0, 0.0, 1.0),
        v3(1.0, 0.0, 1.0),
        v3(0.0, 1.0, 1.0),
        v3(1.0, 1.0, 1.0),
    ];
    assert_eq!(
        Mesh::new(&verts, &[[0, 1, 4]]).err(),
        Some(MeshError::IndexOutOfRange { triangle: 0 })
    );
    // Two triangles sharing the diagonal 1–2: a ray through its midpoint
    // hits both at the same t; the lower index wins.
    let mesh = Mesh::new(&verts, &[[1, 3, 2], [0, 1, 2]]).unwrap();
    let r = Ray::new(v3(0.5, 0.5, 0.0), v3(0.0, 0.0, 1.0)).unwrap();
    let (i, h) = mesh.intersect(&r, S::ZERO).unwrap();
    assert_eq!(i, 0);
    assert_eq!(h.t, S::ONE);
}

per_scalar!(
    degenerate_triangles_hit_only_on_their_segment,
    closed_meshes_do_not_leak,
    triangle_basics,
    mesh_validation_and_ties,
);

/// Fuzz regression (`ray_triangle`): a triangle with three distinct
/// collinear vertices on the line x = y = 51.5, and a ray through a point
/// of that line. It may report a grazing hit (the rounded sheared vertices
/// have a tiny area), but only on the segment; a repeated vertex is never
/// hit.
fn degenerate_triangles_hit_only_on_their_segment<S: Scalar>() {
    let e = 0.125;
    let p = |x: f64, y: f64, z: f64| v3::<S>(x * e, y * e, z * e);
    let (a, b, c) = (
        p(412.0, 412.0, 168.0),
        p(412.0, 412.0, 452.0),
        p(412.0, 412.0, 412.0),
    );
    let q = p(-420.0, -416.0, -416.0);
    let target = p(412.0, 412.0, 422.0);
    let ray = Ray::through(q, target).unwrap();
    if let Some(h) = Triangle::new(a, b, c).intersect(&ray, S::ZERO) {
        let x = ray.at(h.t);
        // On the segment x = y = 51.5, z in [21, 56.5], to rounding.
        let tol = if S::IS_FLOAT { 1e-3 } else { 0.05 };
        assert!((x.x.to_f64() - 51.5).abs() < tol && (x.y.to_f64() - 51.5).abs() < tol);
        assert!(x.z.to_f64() > 21.0 - tol && x.z.to_f64() < 56.5 + tol);
    }
    let d = p(412.0, 412.0, 412.0);
    assert_eq!(Triangle::new(c, b, d).intersect(&ray, S::ZERO), None);
}
