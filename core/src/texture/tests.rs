use super::*;
use crate::camera::Projection;
use crate::math::{Vec2, Vec3};
use crate::pipeline::{Pipeline, Uv, UvPerspective, Vertex};
use crate::raster::{AffineTexture, NoDepth, PerspectiveTexture};
use crate::scalar::{I16F16, Scalar};
use crate::solve::SolveError;
use crate::target::Framebuffer;
use crate::test_util::Rng;
use std::vec;
use std::vec::Vec;

fn v3<S: Scalar>(x: f64, y: f64, z: f64) -> Vec3<S> {
    Vec3::new(S::from_f64(x), S::from_f64(y), S::from_f64(z))
}
fn v2<S: Scalar>(x: f64, y: f64) -> Vec2<S> {
    Vec2::new(S::from_f64(x), S::from_f64(y))
}
fn f64v(v: Vec3<impl Scalar>) -> [f64; 3] {
    [v.x.to_f64(), v.y.to_f64(), v.z.to_f64()]
}
fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|k| (a[k] - b[k]).abs()).fold(0.0, f64::max)
}

/// A random plane mapping in f64: origin, U, V (not orthogonal, not unit).
fn random_vectors(rng: &mut Rng) -> ([f64; 3], [f64; 3], [f64; 3]) {
    let p = [
        rng.range(-1.0, 1.0),
        rng.range(-1.0, 1.0),
        rng.range(3.0, 5.0),
    ];
    let u = [
        rng.range(-0.02, 0.02),
        rng.range(-0.02, 0.02),
        rng.range(-0.02, 0.02),
    ];
    let v = [
        rng.range(-0.02, 0.02),
        rng.range(-0.02, 0.02),
        rng.range(-0.02, 0.02),
    ];
    (p, u, v)
}
fn at(m: &([f64; 3], [f64; 3], [f64; 3]), u: f64, v: f64) -> [f64; 3] {
    core::array::from_fn(|k| m.0[k] + u * m.1[k] + v * m.2[k])
}
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn norm(a: [f64; 3]) -> f64 {
    a.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// Tolerance relative to a magnitude for each scalar.
fn tol<S: Scalar>(mag: f64) -> f64 {
    if S::IS_FLOAT {
        S::EPSILON.to_f64() * 1e4 * mag.max(1.0)
    } else {
        // I16F16: one step is 1.5e-5; the solve divides by texel spans.
        5e-3 * mag.max(1.0)
    }
}

fn rectangle_fast_path_matches_solver<S: Scalar>() {
    // A 2×1 rectangle tilted in depth, texels 0..64 × 0..32 from corner a.
    let a = v3::<S>(-1.0, -0.5, 3.0);
    let b = v3::<S>(1.0, -0.5, 4.0);
    let d = v3::<S>(-1.0, 0.5, 3.0);
    let c = b + (d - a);
    let (ta, tb, tc, td) = (
        v2::<S>(0.0, 0.0),
        v2(64.0, 0.0),
        v2(64.0, 32.0),
        v2(0.0, 32.0),
    );
    let fast = TextureVectors::from_axis_edges(a, b, d, ta, tb, td).unwrap();
    let (solved, diag) = TextureVectors::from_polygon(&[a, b, c, d], &[ta, tb, tc, td]).unwrap();
    assert!(diag.rcond.to_f64() > 0.1);
    for (x, y) in [
        (fast.origin, solved.origin),
        (fast.u_axis, solved.u_axis),
        (fast.v_axis, solved.v_axis),
    ] {
        assert!(dist(f64v(x), f64v(y)) <= tol::<S>(1.0), "{x:?} vs {y:?}");
    }
    // The corners come back.
    for (p, t) in [(a, ta), (b, tb), (c, tc), (d, td)] {
        assert!(dist(f64v(fast.point(t.x, t.y)), f64v(p)) <= tol::<S>(4.0));
    }
    // U is the edge over 64 texels.
    assert!(dist(f64v(fast.u_axis), [2.0 / 64.0, 0.0, 1.0 / 64.0]) <= tol::<S>(0.05));
}

fn polygon_recovers_random_mappings<S: Scalar>() {
    let mut rng = Rng::new(0x7e47);
    for case in 0..200 {
        let m = random_vectors(&mut rng);
        // Texture origin far away: the vertices sit near (1000, -700).
        let (u0, v0) = (1000.0, -700.0);
        let n = 3 + case % 4;
        // A convex polygon in (u, v): points on an ellipse.
        let (ru, rv) = (rng.range(8.0, 60.0), rng.range(8.0, 60.0));
        let phase = rng.range(0.0, 1.0);
        let uv: Vec<(f64, f64)> = (0..n)
            .map(|i| {
                let t = (i as f64 + phase) / n as f64 * core::f64::consts::TAU;
                ((u0 + ru * t.cos()).round(), (v0 + rv * t.sin()).round())
            })
            .collect();
        let pos: Vec<Vec3<S>> = uv
            .iter()
            .map(|&(u, v)| {
                let p = at(&m, u, v);
                v3(p[0], p[1], p[2])
            })
            .collect();
        let tex: Vec<Vec2<S>> = uv.iter().map(|&(u, v)| v2(u, v)).collect();
        let scale = norm(cross(m.1, m.2)).sqrt();
        if norm(cross(m.1, m.2)) < 1e-6 {
            continue; // nearly parallel U, V: tested separately
        }
        let got = match TextureVectors::from_polygon(&pos, &tex) {
            Ok((g, _)) => g,
            // Fixed point may reject ill-conditioned layouts; never garbage.
            Err(e) if !S::IS_FLOAT => {
                assert!(matches!(
                    e,
                    MappingError::Solve(_) | MappingError::Inconsistent
                ));
                continue;
            }
            Err(e) => panic!("case {case}: {e}"),
        };
        // Compare the mapping where it matters: at the vertices and the
        // center of the texture region.
        for &(u, v) in uv.iter().chain([(u0, v0)].iter()) {
            let e = dist(
                f64v(got.point(S::from_f64(u), S::from_f64(v))),
                at(&m, u, v),
            );
            assert!(
                e <= tol::<S>(5.0) * 4.0,
                "case {case} n {n}: error {e} (scale {scale})"
            );
        }
    }
}

fn degenerate_input_gives_errors<S: Scalar>() {
    let p = |x, y, z| v3::<S>(x, y, z);
    let t = |u, v| v2::<S>(u, v);
    let quad = [
        p(0.0, 0.0, 2.0),
        p(1.0, 0.0, 2.0),
        p(1.0, 1.0, 2.0),
        p(0.0, 1.0, 2.0),
    ];
    let uv = [t(0.0, 0.0), t(8.0, 0.0), t(8.0, 8.0), t(0.0, 8.0)];
    assert!(TextureVectors::from_polygon(&quad, &uv).is_ok());
    let err = |pos: &[Vec3<S>], uv: &[Vec2<S>]| TextureVectors::from_polygon(pos, uv).unwrap_err();
    assert_eq!(err(&quad[..2], &uv[..2]), MappingError::TooFewVertices);
    assert_eq!(err(&quad, &uv[..3]), MappingError::TooFewVertices);
    // Collinear and repeated positions.
    let line = [p(0.0, 0.0, 2.0), p(1.0, 1.0, 2.0), p(2.0, 2.0, 2.0)];
    assert_eq!(err(&line, &uv[..3]), MappingError::DegeneratePolygon);
    let same = [quad[0], quad[0], quad[0]];
    assert_eq!(err(&same, &uv[..3]), MappingError::DegeneratePolygon);
    // Zero-area texture coordinates: repeated, and collinear.
    assert_eq!(
        err(&quad[..3], &[uv[0], uv[0], uv[0]]),
        MappingError::DegenerateUv
    );
    assert_eq!(
        err(&quad[..3], &[t(0.0, 0.0), t(4.0, 4.0), t(8.0, 8.0)]),
        MappingError::DegenerateUv
    );
    // Non-planar quad, and texture coordinates that are not affine.
    let bent = [quad[0], quad[1], p(1.0, 1.0, 2.5), quad[3]];
    assert_eq!(err(&bent, &uv), MappingError::Inconsistent);
    let warped = [uv[0], uv[1], t(10.0, 8.0), uv[3]];
    assert_eq!(err(&quad, &warped), MappingError::Inconsistent);
    if S::IS_FLOAT {
        // (from_f64 maps NaN to 0, so make one by arithmetic.)
        let nan = [
            Vec3::new(core::hint::black_box(S::ZERO) / S::ZERO, S::ZERO, S::TWO),
            quad[1],
            quad[2],
        ];
        assert_eq!(err(&nan, &uv[..3]), MappingError::NonFinite);
    }
    // The axis-edge fast path.
    let axis = |b: Vec2<S>, c: Vec2<S>| {
        TextureVectors::from_axis_edges(quad[0], quad[1], quad[3], uv[0], b, c).unwrap_err()
    };
    assert_eq!(axis(t(8.0, 1.0), uv[3]), MappingError::NotAxisAligned);
    assert_eq!(axis(uv[1], t(1.0, 8.0)), MappingError::NotAxisAligned);
    assert_eq!(axis(uv[0], uv[3]), MappingError::DegenerateUv);
    assert_eq!(
        TextureVectors::from_axis_edges(quad[0], quad[1], quad[1], uv[0], uv[1], uv[3])
            .unwrap_err(),
        MappingError::DegeneratePolygon
    );
}

#[test]
fn errors_display_and_chain() {
    use core::error::Error;
    use std::string::ToString;
    let e = MappingError::Solve(SolveError::Singular { column: 1 });
    assert!(e.to_string().contains("singular"));
    assert!(e.source().is_some());
    assert!(MappingError::DegenerateUv.source().is_none());
    for e in [
        MappingError::TooFewVertices,
        MappingError::NonFinite,
        MappingError::DegeneratePolygon,
        MappingError::DegenerateUv,
        MappingError::NotAxisAligned,
        MappingError::Inconsistent,
    ] {
        assert!(!e.to_string().is_empty());
    }
}

/// The per-pixel mapping against an f64 reference: the view ray through
/// the pixel center meets the triangle's plane, and barycentric
/// coordinates of that point interpolate (u, v).
fn screen_mapping_matches_reference<S: Scalar>() {
    let mut rng = Rng::new(0x5c4e);
    let (focus, cx, cy) = (200.0, 160.0, 120.0);
    let mut checked = 0;
    for _ in 0..50 {
        let tri: [[f64; 3]; 3] = core::array::from_fn(|_| {
            let z = rng.range(1.5, 6.0);
            [rng.range(-0.6, 0.6) * z, rng.range(-0.5, 0.5) * z, z]
        });
        let uv: [(f64, f64); 3] =
            core::array::from_fn(|_| (rng.range(-50.0, 300.0), rng.range(-50.0, 300.0)));
        let pos = tri.map(|p| v3::<S>(p[0], p[1], p[2]));
        let tex = uv.map(|(u, v)| v2::<S>(u, v));
        let Ok((m, _)) = TextureVectors::from_polygon(&pos, &tex) else {
            continue; // ill-conditioned in this type (rare, fixed point)
        };
        let Some(sm) = m.screen_mapping(S::from_f64(focus), v2(cx, cy)) else {
            continue;
        };
        // f64 reference.
        let e1: [f64; 3] = core::array::from_fn(|k| tri[1][k] - tri[0][k]);
        let e2: [f64; 3] = core::array::from_fn(|k| tri[2][k] - tri[0][k]);
        let n = cross(e1, e2);
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let area = dot(n, n);
        let uv_range = uv
            .iter()
            .fold(1.0f64, |m, t| m.max(t.0.abs()).max(t.1.abs()));
        for _ in 0..40 {
            // A random point of the triangle, then its pixel.
            let (mut a, mut b) = (rng.unit(), rng.unit());
            if a + b > 1.0 {
                (a, b) = (1.0 - a, 1.0 - b);
            }
            let p: [f64; 3] = core::array::from_fn(|k| tri[0][k] + a * e1[k] + b * e2[k]);
            let (xs, ys) = (cx + focus * p[0] / p[2], cy + focus * p[1] / p[2]);
            let (xs, ys) = (xs.floor() + 0.5, ys.floor() + 0.5);
            let d = [(xs - cx) / focus, (ys - cy) / focus, 1.0];
            let t = dot(n, tri[0]) / dot(n, d);
            let x: [f64; 3] = d.map(|c| c * t);
            let r: [f64; 3] = core::array::from_fn(|k| x[k] - tri[0][k]);
            let l1 = dot(cross(r, e2), n) / area;
            let l2 = dot(cross(e1, r), n) / area;
            let l0 = 1.0 - l1 - l2;
            let ur = l0 * uv[0].0 + l1 * uv[1].0 + l2 * uv[2].0;
            let vr = l0 * uv[0].1 + l1 * uv[1].1 + l2 * uv[2].1;
            let (u, v) = sm.uv(S::from_f64(xs), S::from_f64(ys)).unwrap();
            // The problem's own conditioning: errors in the vectors are
            // amplified by 1/cos of the angle between the ray and the
            // plane's normal (grazing views are ill-conditioned).
            let cos = dot(d, n).abs() / (norm(d) * norm(n));
            let per_unit = if S::IS_FLOAT {
                S::EPSILON.to_f64() * 1e3
            } else {
                1e-2
            };
            let tol = per_unit * uv_range / cos;
            if !S::IS_FLOAT && cos < 0.2 {
                // I16F16 stores U and V (≈ 0.01 units per texel) to about
                // 0.15 %: a plane offset that edge-on views amplify to
                // many texels. Not checked there.
                continue;
            }
            assert!(
                (u.to_f64() - ur).abs() <= tol && (v.to_f64() - vr).abs() <= tol,
                "({xs}, {ys}), cos {cos}: ({}, {}) vs ({ur}, {vr})",
                u.to_f64(),
                v.to_f64()
            );
            checked += 1;
        }
    }
    assert!(checked >= 1000, "{checked}");
}

#[test]
fn error_bound_holds_and_is_not_loose() {
    // Dense screen-space sampling of triangles in f64: the affine error
    // never exceeds the bound, and on an edge with depth ratio 2 the bound
    // (0.25·Δu) is within 1.5× of the true maximum (0.1716·Δu).
    let mut rng = Rng::new(0xb0b);
    for _ in 0..500 {
        let z: [f64; 3] = core::array::from_fn(|_| rng.range(0.5, 20.0));
        let uv: [(f64, f64); 3] =
            core::array::from_fn(|_| (rng.range(-100.0, 100.0), rng.range(-100.0, 100.0)));
        let bound = affine_error_bound(z, uv.map(|(u, v)| Vec2::new(u, v))).unwrap();
        let q = z.map(|d| 1.0 / d);
        let mut worst = 0.0f64;
        for i in 0..=40 {
            for j in 0..=(40 - i) {
                let l = [i as f64 / 40.0, j as f64 / 40.0, (40 - i - j) as f64 / 40.0];
                let qb: f64 = (0..3).map(|k| l[k] * q[k]).sum();
                for c in 0..2 {
                    let t = |k: usize| if c == 0 { uv[k].0 } else { uv[k].1 };
                    let exact: f64 = (0..3).map(|k| l[k] * q[k] * t(k)).sum::<f64>() / qb;
                    let affine: f64 = (0..3).map(|k| l[k] * t(k)).sum();
                    worst = worst.max((exact - affine).abs());
                }
            }
        }
        assert!(
            worst <= bound * (1.0 + 1e-12),
            "worst {worst} > bound {bound}"
        );
    }
    let b = affine_error_bound(
        [1.0, 2.0, 2.0],
        [
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(1.0, 0.0),
        ],
    )
    .unwrap();
    assert!((b - 0.25).abs() < 1e-12);
    // Equal depths (parallel projection, or a polygon facing the eye):
    // affine is exact.
    let flat = [
        Vec2::new(0.0, 0.0),
        Vec2::new(64.0, 0.0),
        Vec2::new(0.0, 64.0),
    ];
    assert_eq!(affine_error_bound([3.0, 3.0, 3.0], flat), Some(0.0));
    assert_eq!(choose_mapping([3.0, 3.0, 3.0], flat, 0.0), Mapping::Affine);
    assert_eq!(
        choose_mapping([1.0, 3.0, 3.0], flat, 0.5),
        Mapping::Perspective
    );
    assert_eq!(
        choose_mapping([-1.0, 3.0, 3.0], flat, 1e9),
        Mapping::Perspective
    );
    assert_eq!(affine_error_bound([0.0, 3.0, 3.0], flat), None);
}

/// Renders triangles through the pipeline with the affine shader wherever
/// `choose_mapping` picks it, and with exact perspective, into a texture
/// whose texels encode their own (u, v): the texel indices differ by at
/// most the threshold plus one (nearest sampling can floor two values
/// that differ by less than t to integers up to ⌊t⌋ + 1 apart).
fn affine_where_chosen_stays_within_threshold<S: Scalar>() {
    let (w, h) = (96u16, 72u16);
    let focus = 80.0;
    let pipe = Pipeline::new(
        Projection::perspective(S::from_f64(focus), w, h),
        w,
        h,
        S::from_f64(0.5),
        S::from_f64(50.0),
        S::from_i32(8),
    )
    .unwrap();
    // 256×256 texels; texel (i, j) holds j·256 + i.
    let texels: Vec<u16> = (0..=u16::MAX).collect();
    let tex = Texture::new(&texels, 256, 256, 256).unwrap();
    let affine = AffineTexture::<_, Clamp>::new(tex).unwrap();
    let exact = PerspectiveTexture::<_, Clamp, 1>::new(tex).unwrap();
    let mut rng = Rng::new(0xaff1);
    let (mut chosen, mut rejected) = (0, 0);
    for threshold in [0.5, 1.0, 2.0, 4.0] {
        for _ in 0..60 {
            let z0 = rng.range(2.0, 6.0);
            let tri: [[f64; 3]; 3] = core::array::from_fn(|_| {
                let z = z0 * rng.range(1.0, 1.25);
                [rng.range(-0.5, 0.5) * z, rng.range(-0.4, 0.4) * z, z]
            });
            let uv: [(f64, f64); 3] =
                core::array::from_fn(|_| (rng.range(5.0, 250.0), rng.range(5.0, 250.0)));
            let zs = tri.map(|p| S::from_f64(p[2]));
            let uvs = uv.map(|(u, v)| v2::<S>(u, v));
            let t = S::from_f64(threshold);
            if choose_mapping(zs, uvs, t) == Mapping::Perspective {
                rejected += 1;
                continue;
            }
            chosen += 1;
            let n = w as usize * h as usize;
            let (mut a, mut b) = (vec![u16::MAX; n], vec![u16::MAX; n]);
            {
                let mut fa = Framebuffer::new(&mut a, w, h, w as usize).unwrap();
                let mut fb = Framebuffer::new(&mut b, w, h, w as usize).unwrap();
                let pa: [Vertex<S, Uv<S>>; 3] = core::array::from_fn(|k| {
                    Vertex::new(
                        v3(tri[k][0], tri[k][1], tri[k][2]),
                        Uv {
                            u: uvs[k].x,
                            v: uvs[k].y,
                        },
                    )
                });
                let pb: [Vertex<S, UvPerspective<S>>; 3] = core::array::from_fn(|k| {
                    Vertex::new(
                        pa[k].pos,
                        UvPerspective {
                            u: uvs[k].x,
                            v: uvs[k].y,
                        },
                    )
                });
                pipe.draw_polygon(&mut fa, &mut NoDepth, &affine, &pa)
                    .unwrap();
                pipe.draw_polygon(&mut fb, &mut NoDepth, &exact, &pb)
                    .unwrap();
            }
            let allow = (threshold + 0.01).floor() as i32 + 1;
            for (&p, &q) in a.iter().zip(&b) {
                assert_eq!(p == u16::MAX, q == u16::MAX, "coverage differs");
                if p == u16::MAX {
                    continue;
                }
                let du = (p & 255) as i32 - (q & 255) as i32;
                let dv = (p >> 8) as i32 - (q >> 8) as i32;
                assert!(
                    du.abs() <= allow && dv.abs() <= allow,
                    "threshold {threshold}: texel error ({du}, {dv})"
                );
            }
        }
    }
    assert!(
        chosen > 20 && rejected > 20,
        "chosen {chosen}, rejected {rejected}"
    );
}

macro_rules! texture_tests {
    ($m:ident, $S:ty) => {
        mod $m {
            #[allow(unused_imports)]
            use super::*;
            #[test]
            fn rectangle_fast_path_matches_solver() {
                super::rectangle_fast_path_matches_solver::<$S>();
            }
            #[test]
            fn polygon_recovers_random_mappings() {
                super::polygon_recovers_random_mappings::<$S>();
            }
            #[test]
            fn degenerate_input_gives_errors() {
                super::degenerate_input_gives_errors::<$S>();
            }
            #[test]
            fn screen_mapping_matches_reference() {
                super::screen_mapping_matches_reference::<$S>();
            }
            #[test]
            fn affine_where_chosen_stays_within_threshold() {
                super::affine_where_chosen_stays_within_threshold::<$S>();
            }
        }
    };
}

texture_tests!(f32_tests, f32);
texture_tests!(f64_tests, f64);
texture_tests!(i16f16_tests, I16F16);
