//! Stability suite, part 3: extreme geometry. Each case states its expected
//! outcome (a result within a stated bound, or a specific error) and
//! prints what it measured, so the figures can be quoted.
//!
//! `cargo test --workspace --test stability_geometry -- --nocapture`
//!
//! Part 1 (`stability_solver.rs`) has the stiff linear systems, the
//! fixed-point overflow systems and the 1000-step rotation drift with and
//! without re-orthonormalization; part 2 (`stability_camera.rs`) the camera
//! recovery with and without normalized data.
//!
//! Coverage oracle used below: a pixel is *unambiguous* when its center
//! and four points 0.15 px around it are all inside, or all outside, the
//! polygon as cast in f64 (ray from the eye through the point, hit on the
//! polygon's plane at z ≥ near). Unambiguous pixels must be drawn exactly
//! when inside; pixels within 0.15 px of an edge may go either way
//! (vertices snap to 1/16 px).

use sightline::camera::{Camera, CameraError, Projection};
use sightline::math::{Affine3, Mat3, Vec3};
use sightline::pipeline::{
    DrawError, DrawOutcome, Pipeline, PipelineError, Uv, UvPerspective, Vertex,
};
use sightline::raster::{
    AffineTexture, COORD_LIMIT, FillOutcome, Flat, NoDepth, PerspectiveTexture, ScreenVertex,
    fill_polygon,
};
use sightline::ray::{Plane, Polygon, Ray, Roots, Sphere};
use sightline::scalar::{I16F16, Scalar};
use sightline::target::Framebuffer;
use sightline::texture::{RepeatPow2, Texture};

const W: u16 = 64;
const FOCUS: f64 = 32.0;

fn v<S: Scalar>(x: f64, y: f64, z: f64) -> Vec3<S> {
    Vec3::new(S::from_f64(x), S::from_f64(y), S::from_f64(z))
}

/// A pipeline that clips at `far` too (these cases test the whole clip
/// volume).
fn pipeline<S: Scalar>(near: f64, far: f64) -> Result<Pipeline<S>, PipelineError> {
    Pipeline::new(
        Projection::perspective(S::from_f64(FOCUS), W, W),
        W,
        W,
        S::from_f64(near),
        S::from_f64(far),
        S::from_i32(8),
    )
    .map(|p| p.with_far_clip(true))
}

/// Draws a flat polygon into a fresh W×W frame; returns the outcome and
/// which pixels were written.
fn draw<S: Scalar>(
    pipe: &Pipeline<S>,
    poly: &[Vec3<f64>],
) -> (Result<DrawOutcome, DrawError>, Vec<bool>) {
    let mut buf = vec![0u8; usize::from(W) * usize::from(W)];
    let mut fb = Framebuffer::new(&mut buf, W, W, usize::from(W)).unwrap();
    let vs: Vec<Vertex<S, ()>> = poly
        .iter()
        .map(|p| Vertex::new(v::<S>(p.x, p.y, p.z), ()))
        .collect();
    let r = pipe.draw_polygon(&mut fb, &mut NoDepth, &Flat(1u8), &vs);
    (r, buf.iter().map(|&c| c == 1).collect())
}

/// Whether the view ray through screen point (x, y) meets the convex
/// polygon at z ≥ near (f64).
fn ray_hits(poly: &[Vec3<f64>], near: f64, x: f64, y: f64) -> bool {
    let c = f64::from(W) / 2.0;
    let d = Vec3::new((x - c) / FOCUS, (y - c) / FOCUS, 1.0);
    let n = (poly[1] - poly[0]).cross(poly[2] - poly[0]);
    let den = n.dot(d);
    if den == 0.0 {
        return false;
    }
    let t = n.dot(poly[0]) / den;
    if t.is_nan() || t < near {
        return false;
    }
    let p = d * t;
    // Inside a convex polygon: same side of every edge.
    let mut sign = 0.0f64;
    for i in 0..poly.len() {
        let a = poly[i];
        let b = poly[(i + 1) % poly.len()];
        let s = (b - a).cross(p - a).dot(n);
        if s == 0.0 {
            return false;
        }
        if sign == 0.0 {
            sign = s.signum();
        } else if s.signum() != sign {
            return false;
        }
    }
    true
}

/// Checks coverage against the ray-cast oracle; returns (covered,
/// unambiguous mismatches, ambiguous pixels).
fn check_coverage(poly: &[Vec3<f64>], near: f64, covered: &[bool]) -> (usize, usize, usize) {
    let (mut n, mut bad, mut amb) = (0, 0, 0);
    for j in 0..usize::from(W) {
        for i in 0..usize::from(W) {
            let (x, y) = (i as f64 + 0.5, j as f64 + 0.5);
            let probes = [
                (0.0, 0.0),
                (0.15, 0.0),
                (-0.15, 0.0),
                (0.0, 0.15),
                (0.0, -0.15),
            ];
            let hits: Vec<bool> = probes
                .iter()
                .map(|(dx, dy)| ray_hits(poly, near, x + dx, y + dy))
                .collect();
            let c = covered[j * usize::from(W) + i];
            n += usize::from(c);
            if hits.iter().all(|&h| h == hits[0]) {
                if c != hits[0] {
                    bad += 1;
                }
            } else {
                amb += 1;
            }
        }
    }
    (n, bad, amb)
}

// ------------------------------------------------- range limits (f32, I16F16)

/// f32 projection is scale invariant: scaling a view-space point by s
/// leaves its pixel unchanged, to a few ulps, from s = 1e-30 to 1e36.
/// Expected: within 1e-4 px of f64 at every scale, including s = 1e36
/// where x·focus overflows f32 (the projection then divides first).
/// Infinite or NaN input gives `None`.
#[test]
fn f32_projection_across_the_exponent_range() {
    let proj = Projection::<f32>::perspective(120.0, 240, 240);
    let reference = Projection::<f64>::perspective(120.0, 240, 240);
    let p = Vec3::new(37.25f64, -12.5, 80.0);
    let (want, _) = reference.project(p).unwrap();
    for s in [1e-30, 1e-10, 1.0, 1e10, 1e30, 1e36] {
        let q = Vec3::new(p.x * s, p.y * s, p.z * s).cast::<f32>();
        let (got, _) = proj.project(q).expect("representable");
        let err = (got.cast::<f64>() - want).length();
        println!("f32 scale {s:e}: pixel error {err:.2e} px");
        assert!(err < 1e-4, "scale {s:e}: {err}");
    }
    for q in [
        Vec3::new(f32::INFINITY, 1.0, 80.0),
        Vec3::new(1.0, f32::NAN, 80.0),
        Vec3::new(1.0, 1.0, f32::INFINITY),
    ] {
        assert_eq!(proj.project(q), None, "{q:?}");
    }
}

/// I16F16 projection of points whose x·focus exceeds the format's range
/// (±32768) although the pixel (focus·x/z) is on screen. Expected: the
/// correct pixel within 0.01 px, never a wrong pixel. (This case found a
/// bug: the product used to saturate and the pixel came out up to 111 px
/// off with no error; fixed in `Projection::project`, with a regression
/// test in core's camera tests.)
#[test]
fn i16f16_projection_where_x_times_focus_overflows() {
    let proj = Projection::<I16F16>::perspective(I16F16::from_f64(120.0), 240, 240);
    let reference = Projection::<f64>::perspective(120.0, 240, 240);
    let mut worst = 0.0f64;
    let mut none = 0;
    for &(x, y, z) in &[
        (300.0, -200.0, 400.0),
        (2000.0, 1500.0, 3000.0),
        (20000.0, -9000.0, 30000.0),
        (-30000.0, 250.0, 32000.0),
        (273.0, 0.0, 300.0),
    ] {
        let p = Vec3::new(x, y, z);
        let (want, _) = reference.project(p).unwrap();
        match proj.project(p.cast()) {
            Some((got, _)) => {
                let e = (got.cast::<f64>() - want).length();
                println!("I16F16 ({x}, {y}, {z}): pixel error {e:.2e} px");
                worst = worst.max(e);
            }
            None => {
                println!("I16F16 ({x}, {y}, {z}): None");
                none += 1;
            }
        }
    }
    assert!(worst < 0.01, "wrong pixel: {worst} px");
    assert_eq!(none, 0, "points with on-screen pixels must project");
}

/// I16F16 arithmetic saturates at the top of its range instead of
/// wrapping. Expected: a translation of 30000 plus a coordinate of 5000
/// gives exactly `I16F16::MAX` (not a negative wrapped value), and a
/// polygon made of such vertices draws or is rejected without panicking.
#[test]
fn i16f16_transform_saturates_at_the_range_limit() {
    let m = Affine3::new(
        Mat3::<I16F16>::IDENTITY,
        v::<I16F16>(30000.0, -30000.0, 30000.0),
    );
    let r = m.transform_point3(v::<I16F16>(5000.0, -5000.0, 100.0));
    println!("I16F16 30000 + 5000 = {}, −30000 − 5000 = {}", r.x, r.y);
    assert_eq!(r.x, I16F16::MAX);
    assert_eq!(r.y, I16F16::MIN);
    assert!((r.z.to_f64() - 30100.0).abs() < 1e-9);

    let pipe = pipeline::<I16F16>(0.5, 32000.0).unwrap();
    let huge = [
        Vec3::new(-32767.0, -32767.0, 32767.0),
        Vec3::new(32767.0, -32767.0, 32767.0),
        Vec3::new(0.0, 32767.0, 32767.0),
    ];
    let (out, covered) = draw::<I16F16>(&pipe, &huge);
    let n = covered.iter().filter(|&&c| c).count();
    println!("I16F16 triangle at the range limit: {out:?}, {n} pixels");
    // Beyond the far plane (32000): clipped away entirely.
    assert!(
        matches!(out, Ok(DrawOutcome::Filled(FillOutcome::Empty))),
        "{out:?}"
    );
    assert_eq!(n, 0);
}

// ------------------------------------------------------ far and near objects

/// A triangle very far away (z = 10⁴ in f32, 2·10⁴ in I16F16, 1650 and
/// 3300 units across, about 5 px) and one reaching from behind the eye to in front
/// of it (clipped at near = 0.01). Expected: coverage equals the f64
/// ray-cast oracle on every unambiguous pixel.
#[test]
fn objects_very_far_and_very_near() {
    fn case<S: Scalar>(name: &str, far_z: f64) {
        let pipe = pipeline::<S>(0.01, 30000.0).unwrap();
        // About 5 px across at either depth (x·focus reaches 57600 at
        // 2·10⁴, beyond I16F16's range: the projection divides first).
        let k = far_z / 1e4 * 1.5;
        let far = [
            Vec3::new(-500.0 * k, -300.0 * k, far_z),
            Vec3::new(600.0 * k, -200.0 * k, far_z),
            Vec3::new(0.0, 700.0 * k, far_z),
        ];
        let near = [
            Vec3::new(-3.0, 2.0, -1.0),
            Vec3::new(3.0, 1.0, 0.02),
            Vec3::new(0.5, -2.0, 4.0),
        ];
        for (what, poly) in [("far", &far[..]), ("near", &near[..])] {
            let (out, covered) = draw::<S>(&pipe, poly);
            let (n, bad, amb) = check_coverage(poly, 0.01, &covered);
            println!("{name} {what}: {out:?}, {n} px, {bad} wrong, {amb} ambiguous");
            assert!(out.is_ok(), "{name} {what}: {out:?}");
            assert!(n > 0, "{name} {what}: nothing drawn");
            assert_eq!(bad, 0, "{name} {what}: unambiguous pixels wrong");
        }
    }
    case::<f32>("f32", 1e4);
    case::<I16F16>("I16F16", 2e4);
}

/// The near plane at tiny distances. Expected: f32 builds a pipeline with
/// near = 1e-6 and draws a floor exactly as the oracle says; I16F16
/// rejects near values that round to 0 (`BadDepthRange`) or whose 1/near
/// overflows (2⁻¹⁶: `NonFinite`), and works from 2⁻¹⁴ on.
#[test]
fn near_plane_at_tiny_distances() {
    let floor = [
        Vec3::new(-4.0, 1.0, 0.5),
        Vec3::new(4.0, 1.0, 0.5),
        Vec3::new(4.0, 1.0, 40.0),
        Vec3::new(-4.0, 1.0, 40.0),
    ];
    let p = pipeline::<f32>(1e-6, 100.0).unwrap();
    let (out, covered) = draw::<f32>(&p, &floor);
    let (n, bad, amb) = check_coverage(&floor, 1e-6, &covered);
    println!("f32 near 1e-6: {out:?}, {n} px, {bad} wrong, {amb} ambiguous");
    assert_eq!(bad, 0);
    assert!(n > 0);

    let e1 = pipeline::<I16F16>(1e-6, 100.0).unwrap_err();
    let e2 = pipeline::<I16F16>(1.0 / 65536.0, 100.0).unwrap_err();
    println!("I16F16 near 1e-6: {e1:?}; near 2^-16: {e2:?}");
    assert_eq!(e1, PipelineError::BadDepthRange);
    assert_eq!(e2, PipelineError::NonFinite);
    let p = pipeline::<I16F16>(1.0 / 16384.0, 100.0).unwrap();
    let (out, covered) = draw::<I16F16>(&p, &floor);
    let (n, bad, amb) = check_coverage(&floor, 1.0 / 16384.0, &covered);
    println!("I16F16 near 2^-14: {out:?}, {n} px, {bad} wrong, {amb} ambiguous");
    assert_eq!(bad, 0);
}

/// A field of view approaching 180°: focus = (w/2)/tan(fov/2) → 0.
/// Expected: `perspective_fov` matches f64 to a relative error of at most
/// 4·ε/δ (δ = π − fov: cos(fov/2) = sin(δ/2) has absolute error ~ε) or
/// returns `None`; exactly π gives `None`. A pipeline with the smallest
/// f32 focus draws without panicking.
#[test]
fn field_of_view_approaching_180_degrees() {
    fn case<S: Scalar>() {
        for delta_deg in [10.0, 1.0, 0.01, 1e-4] {
            let delta = f64::to_radians(delta_deg);
            let fov = core::f64::consts::PI - delta;
            let want = match Projection::<f64>::perspective_fov(fov, 240, 240)
                .unwrap()
                .kind
            {
                sightline::camera::ProjectionKind::Perspective { focus } => focus,
                _ => unreachable!(),
            };
            match Projection::<S>::perspective_fov(S::from_f64(fov), 240, 240) {
                Some(p) => {
                    let sightline::camera::ProjectionKind::Perspective { focus } = p.kind else {
                        unreachable!()
                    };
                    let rel = (focus.to_f64() - want).abs() / want;
                    let bound = 4.0 * S::EPSILON.to_f64() / delta;
                    println!(
                        "{}: fov 180° − {delta_deg}°: focus {:.4e} (f64 {want:.4e}), rel. error {rel:.2e}, bound {bound:.2e}",
                        S::NAME,
                        focus.to_f64()
                    );
                    assert!(rel <= bound, "{} δ={delta_deg}°", S::NAME);
                }
                None => println!("{}: fov 180° − {delta_deg}°: None", S::NAME),
            }
        }
        assert!(Projection::<S>::perspective_fov(S::PI, 240, 240).is_none());
    }
    case::<f32>();
    case::<I16F16>();
    let p = Projection::<f32>::perspective_fov((180.0f32 - 1e-4).to_radians(), W, W).unwrap();
    let pipe = Pipeline::new(p, W, W, 0.1, 100.0, 8.0);
    println!(
        "f32 pipeline at fov 180° − 1e-4°: {:?}",
        pipe.as_ref().map(|_| ())
    );
    if let Ok(pipe) = pipe {
        let (out, _) = draw::<f32>(
            &pipe,
            &[
                Vec3::new(-1.0, -1.0, 2.0),
                Vec3::new(1.0, -1.0, 2.0),
                Vec3::new(0.0, 1.0, 2.0),
            ],
        );
        println!("  draws: {out:?}");
        assert!(out.is_ok());
    }
}

// ------------------------------------------------ nearly parallel vectors

/// Camera vectors nearly parallel. `look_at` with `up` at angle α from
/// the view direction: expected an orthonormal camera (|RRᵀ − I| ≤ 8ε)
/// down to α = 1e-3 (f32) / 0.05 (I16F16) and `UpParallelToView` at
/// α = 0. `from_vectors` with u, v at angle δ: expected a camera whose
/// matrix inverts [u v w] to a residual ≤ 8ε/δ, or `Degenerate` once the
/// condition estimate passes √ε; δ = 0 is always `Degenerate`.
#[test]
fn nearly_parallel_camera_vectors() {
    fn case<S: Scalar>(alphas: &[f64]) {
        let eps = S::EPSILON.to_f64();
        let eye = v::<S>(1.0, 2.0, 3.0);
        let target = v::<S>(1.0, 2.0, -7.0);
        for &a in alphas {
            let up = v::<S>(a.sin(), 0.0, -a.cos());
            match Camera::look_at(eye, target, up) {
                Ok(c) => {
                    let r = c.world_to_view().matrix.cast::<f64>();
                    let rrt = r.mul_mat3(&r.transpose());
                    let dev = (0..3)
                        .map(|i| (rrt.row(i) - Mat3::<f64>::IDENTITY.row(i)).max_abs())
                        .fold(0.0, f64::max);
                    println!("{} look_at α = {a:e}: |RRᵀ − I| = {dev:.2e}", S::NAME);
                    assert!(dev <= 8.0 * eps, "{} α = {a}", S::NAME);
                }
                Err(e) => {
                    println!("{} look_at α = {a:e}: {e:?}", S::NAME);
                    assert!(a < 64.0 * eps, "{} α = {a}: {e:?}", S::NAME);
                    assert_eq!(e, CameraError::UpParallelToView);
                }
            }
        }
        for delta in [0.3, 1e-2, 1e-3, 1e-5, 0.0] {
            let u = Vec3::new(1.0, 0.0, 0.0);
            let vv = Vec3::new(delta.cos(), delta.sin(), 0.0);
            let w = Vec3::new(0.2, 0.1, 1.0);
            match Camera::from_vectors(v::<S>(0.0, 0.0, 0.0), u.cast(), vv.cast(), w.cast()) {
                Ok((c, d)) => {
                    let m = c.world_to_view().matrix.cast::<f64>();
                    let a = Mat3::from_cols(u, vv, w).cast::<S>().cast::<f64>();
                    let prod = m.mul_mat3(&a);
                    let res = (0..3)
                        .map(|i| (prod.row(i) - Mat3::<f64>::IDENTITY.row(i)).max_abs())
                        .fold(0.0, f64::max);
                    println!(
                        "{} from_vectors δ = {delta:e}: rcond {:.2e}, |M·A − I| = {res:.2e}",
                        S::NAME,
                        d.rcond.to_f64()
                    );
                    assert!(delta > 0.0);
                    assert!(res <= 8.0 * eps / delta.sin(), "{} δ = {delta}", S::NAME);
                }
                Err(e) => {
                    println!("{} from_vectors δ = {delta:e}: {e:?}", S::NAME);
                    assert!(matches!(e, CameraError::Degenerate(_)), "{e:?}");
                    assert!(delta < 0.05, "{} rejected a usable δ = {delta}", S::NAME);
                }
            }
        }
    }
    case::<f32>(&[0.5, 1e-3, 1e-5, 0.0]);
    case::<f64>(&[0.5, 1e-3, 1e-8, 0.0]);
    case::<I16F16>(&[0.5, 0.05, 1e-4, 0.0]);
}

// ------------------------------------------- grazing rays, vertices, edges

/// Rays grazing the plane y = 1 at angle θ: the hit is at t = 1/sin θ.
/// Expected: relative error of t at most 4·ε/sin θ (the rounding of the
/// direction, amplified by the grazing angle), or `None` when fixed point
/// cannot represent t; θ = 0 (parallel) is `None`.
#[test]
fn grazing_rays_on_a_plane() {
    fn case<S: Scalar>() {
        let plane = Plane::new(v::<S>(0.0, 1.0, 0.0), v::<S>(0.3, 1.0, 0.2)).unwrap();
        let n = Vec3::new(0.3f64, 1.0, 0.2).normalize();
        for theta in [0.5, 1e-2, 1e-3, 1e-4, 0.0] {
            // A direction at angle θ to the plane: in-plane unit vector
            // tilted by θ towards the normal.
            let along = n.cross(Vec3::new(0.0, 0.0, 1.0)).normalize();
            let d = along * f64::cos(theta) + n * f64::sin(theta);
            let origin = Vec3::new(0.0, 0.0, 0.0);
            let exact = Plane::new(Vec3::new(0.0, 1.0, 0.0), n)
                .unwrap()
                .intersect(&Ray::new(origin, d).unwrap(), 0.0);
            let ray = Ray::new(origin.cast::<S>(), d.cast()).unwrap();
            let got = plane.intersect(&ray, S::ZERO);
            match (exact, got) {
                (Some(te), Some(t)) => {
                    let rel = (t.to_f64() - te).abs() / te;
                    let bound = 4.0 * S::EPSILON.to_f64() / theta.sin();
                    println!(
                        "{} θ = {theta:e}: t = {:.6e} (f64 {te:.6e}), rel. error {rel:.2e}, bound {bound:.2e}",
                        S::NAME,
                        t.to_f64()
                    );
                    assert!(rel <= bound, "{} θ = {theta}", S::NAME);
                }
                (_, None) => {
                    println!("{} θ = {theta:e}: None (f64: {exact:?})", S::NAME);
                    assert!(
                        !S::IS_FLOAT || theta == 0.0,
                        "{} θ = {theta}: float must hit",
                        S::NAME
                    );
                }
                (None, Some(t)) => panic!("{} θ = {theta}: hit {t:?} where f64 misses", S::NAME),
            }
        }
    }
    case::<f32>();
    case::<I16F16>();
}

/// Six triangles fanned around a shared vertex at (0, 0, −10), in integer
/// coordinates (exact in both representations). Expected: a ray through
/// the shared vertex, and rays through points on the shared edges, are
/// claimed by exactly one triangle (the boundary policy of
/// `ray::Polygon`); a ray running along an edge inside the triangles'
/// plane hits none of them (the plane intersection is `None`).
#[test]
fn rays_through_vertices_and_along_edges() {
    fn case<S: Scalar>() {
        let ring: [(f64, f64); 6] = [
            (4.0, 0.0),
            (2.0, 4.0),
            (-2.0, 4.0),
            (-4.0, 0.0),
            (-2.0, -4.0),
            (2.0, -4.0),
        ];
        let z = -10.0;
        let tris: Vec<Polygon<S, 3>> = (0..6)
            .map(|k| {
                let (a, b) = (ring[k], ring[(k + 1) % 6]);
                Polygon::new(&[v::<S>(0.0, 0.0, z), v(a.0, a.1, z), v(b.0, b.1, z)]).unwrap()
            })
            .collect();
        let eye = v::<S>(0.0, 0.0, 0.0);
        let mut targets: Vec<(f64, f64)> = vec![(0.0, 0.0)];
        // Points on the six spokes (shared edges).
        for &(x, y) in &ring {
            targets.push((x / 2.0, y / 2.0));
            targets.push((x / 4.0, y / 4.0));
        }
        for (x, y) in targets {
            let ray = Ray::through(eye, v::<S>(x, y, z)).unwrap();
            let claims = tris
                .iter()
                .filter(|t| t.intersect(&ray, S::ZERO).is_some())
                .count();
            println!(
                "{}: ray through ({x}, {y}, {z}): claimed by {claims}",
                S::NAME
            );
            assert_eq!(claims, 1, "{} ({x}, {y})", S::NAME);
        }
        // Along the edge from the center to ring[0], inside the plane.
        let along = Ray::new(v::<S>(-1.0, 0.0, z), v::<S>(1.0, 0.0, 0.0)).unwrap();
        let hits = tris
            .iter()
            .filter(|t| t.intersect(&along, S::ZERO).is_some())
            .count();
        println!("{}: ray along an edge in the plane: {hits} hits", S::NAME);
        assert_eq!(hits, 0);
    }
    case::<f32>();
    case::<I16F16>();
}

/// Rays tangent to a sphere and grazing it by 10⁻³ of its radius.
/// Expected: never a non-finite root; the tangent ray gives one root (or
/// two within √ε of each other, or none) near the tangent point t = 10;
/// the grazing ray's hit is within 2·√ε·r·(relative) of f64.
#[test]
fn rays_tangent_to_a_sphere() {
    fn case<S: Scalar>() {
        let s = Sphere::new(v::<S>(0.0, 2.0, -10.0), S::from_f64(2.0)).unwrap();
        for off in [0.0, 1e-3] {
            // Tangent at (0, off·2, −10): passes at distance 2 − 2·off from the center.
            let y = 2.0 * off;
            let ray = Ray::new(v::<S>(0.0, y, 0.0), v::<S>(0.0, 0.0, -1.0)).unwrap();
            let roots = s.roots(&ray);
            let tol = 4.0 * S::EPSILON.to_f64().sqrt() * 10.0;
            let check = |t: S| {
                assert!(t.is_finite());
                let half = (4.0f64 - (2.0 - y).powi(2)).max(0.0).sqrt();
                assert!(
                    (t.to_f64() - 10.0).abs() <= half + tol,
                    "{} off {off}: root {t:?}",
                    S::NAME
                );
            };
            match roots {
                Roots::None => {}
                Roots::One(t) => check(t),
                Roots::Two(a, b) => {
                    check(a);
                    check(b);
                }
            }
            println!("{} ray {off:e}·r inside the tangent: {roots:?}", S::NAME);
            if off > 0.0 {
                assert!(
                    !matches!(roots, Roots::None),
                    "{}: grazing ray must hit",
                    S::NAME
                );
            }
        }
    }
    case::<f32>();
    case::<f64>();
    case::<I16F16>();
}

// ------------------------------------------- sliver, needle, zero area

/// Degenerate polygons through clip and raster. Expected: zero-area
/// (collinear or repeated vertices) polygons draw nothing and report
/// `Empty`; a needle (0.001 px wide, 60 px long) and a sliver (1° apex
/// angle across the frame) draw exactly what the oracle says on every
/// unambiguous pixel; a screen polygon beyond the scan converter's
/// coordinate limit is `Rejected`. Nothing panics.
#[test]
fn sliver_needle_and_zero_area_polygons() {
    fn case<S: Scalar>() {
        let pipe = pipeline::<S>(0.1, 100.0).unwrap();
        let z = 4.0;
        let px = z / FOCUS; // one pixel in view units at depth z
        let cases: Vec<(&str, Vec<Vec3<f64>>)> = vec![
            (
                "collinear",
                vec![
                    Vec3::new(-1.0, -1.0, z),
                    Vec3::new(0.0, 0.0, z),
                    Vec3::new(1.0, 1.0, z),
                ],
            ),
            (
                "repeated vertex",
                vec![
                    Vec3::new(-1.0, -1.0, z),
                    Vec3::new(-1.0, -1.0, z),
                    Vec3::new(1.0, 0.5, z),
                ],
            ),
            (
                "needle",
                vec![
                    Vec3::new(-30.0 * px, 0.1 * px, z),
                    Vec3::new(30.0 * px, 0.1 * px, z),
                    Vec3::new(30.0 * px, 0.101 * px, z),
                ],
            ),
            (
                "sliver",
                vec![
                    Vec3::new(-31.0 * px, -0.3 * px, z),
                    Vec3::new(31.0 * px, -0.3 * px, z),
                    Vec3::new(31.0 * px, (62.0 * 1f64.to_radians().tan() - 0.3) * px, z),
                ],
            ),
        ];
        for (name, poly) in &cases {
            let (out, covered) = draw::<S>(&pipe, poly);
            let (n, bad, amb) = check_coverage(poly, 0.1, &covered);
            println!(
                "{} {name}: {out:?}, {n} px, {bad} wrong, {amb} ambiguous",
                S::NAME
            );
            assert!(out.is_ok(), "{out:?}");
            assert_eq!(bad, 0, "{} {name}", S::NAME);
            if name.starts_with("collinear") || name.starts_with("repeated") {
                assert_eq!(n, 0);
                assert_eq!(out, Ok(DrawOutcome::Filled(FillOutcome::Empty)));
            }
        }
    }
    case::<f32>();
    case::<I16F16>();

    // Straight to the scan converter: beyond ±COORD_LIMIT, and a zero-area
    // triangle at the limit.
    let mut buf = vec![0u8; 16 * 16];
    let mut fb = Framebuffer::new(&mut buf, 16, 16, 16).unwrap();
    let sv = |x: i32, y: i32| ScreenVertex::<0>::new(x, y, 0, []);
    let out = fill_polygon(
        &mut fb,
        &mut NoDepth,
        &Flat(1u8),
        &[sv(0, 0), sv(COORD_LIMIT + 1, 0), sv(0, 64)],
    );
    assert_eq!(out, FillOutcome::Rejected);
    let l = COORD_LIMIT - 1;
    let out2 = fill_polygon(
        &mut fb,
        &mut NoDepth,
        &Flat(1u8),
        &[sv(-l, -l), sv(0, 0), sv(l, l)],
    );
    assert_eq!(out2, FillOutcome::Empty);
    println!("raster: beyond the limit {out:?}; zero area at the limit {out2:?}");
    assert!(buf.iter().all(|&c| c == 0));
}

/// Polygons lying exactly in a clip plane: the clipper keeps a polygon in
/// a plane whole (documented), so one in the near or the far plane is
/// drawn as the oracle says; one edge-on in a side plane (through the eye)
/// projects to a line and draws nothing.
#[test]
fn polygons_lying_in_a_clip_plane() {
    fn case<S: Scalar>() {
        let (near, far) = (0.25, 64.0);
        let pipe = pipeline::<S>(near, far).unwrap();
        let quad = |z: f64, s: f64| {
            vec![
                Vec3::new(-s, -s, z),
                Vec3::new(s, -s, z),
                Vec3::new(s, s * 0.5, z),
                Vec3::new(-s, s * 0.5, z),
            ]
        };
        for (name, poly, oracle_near) in [
            ("in the near plane", quad(near, 0.15), near * 0.999_999),
            ("in the far plane", quad(far, 40.0), near),
        ] {
            let (out, covered) = draw::<S>(&pipe, &poly);
            let (n, bad, amb) = check_coverage(&poly, oracle_near, &covered);
            println!(
                "{} {name}: {out:?}, {n} px, {bad} wrong, {amb} ambiguous",
                S::NAME
            );
            assert!(out.is_ok());
            assert!(n > 0, "{} {name}: dropped", S::NAME);
            assert_eq!(bad, 0, "{} {name}", S::NAME);
        }
        // The left side plane passes through the eye: x/z = −(cx + guard)/f.
        let k = (f64::from(W) / 2.0 + 8.0) / FOCUS;
        let side = vec![
            Vec3::new(-k * 2.0, -1.0, 2.0),
            Vec3::new(-k * 8.0, -1.0, 8.0),
            Vec3::new(-k * 8.0, 1.0, 8.0),
        ];
        let (out, covered) = draw::<S>(&pipe, &side);
        let n = covered.iter().filter(|&&c| c).count();
        println!("{} in the left side plane: {out:?}, {n} px", S::NAME);
        assert!(out.is_ok());
        assert_eq!(n, 0);
    }
    case::<f32>();
    case::<I16F16>();
}

// ------------------------------------------------ extreme minification

/// A 256×256-texel quad facing the camera, drawn ever smaller (far away):
/// at 32 texels per pixel and at 128. Expected: every drawn pixel samples
/// a texel within one pixel footprint (texels per pixel + 1) of the exact
/// texel under its center, for exact perspective and affine mapping;
/// nothing panics, and texture coordinates of ±10⁶ texels (beyond the
/// 16.16 varying range, which saturates) still sample inside the texture.
#[test]
fn textures_at_extreme_minification() {
    let texels: Vec<u32> = (0..256u32 * 256)
        .map(|i| (i % 256) | ((i / 256) << 16))
        .collect();
    let tex = Texture::new(&texels, 256, 256, 256).unwrap();
    let wrapped = |a: i64, b: i64| ((a - b + 128).rem_euclid(256) - 128).abs();
    fn case<S: Scalar>(
        tex: Texture<'_, u32>,
        wrapped: &dyn Fn(i64, i64) -> i64,
        tpp: f64,
        uv_scale: f64,
    ) -> (usize, i64) {
        let pipe = pipeline::<S>(0.1, 100000.0).unwrap();
        // Quad side: 256 texels over 256/tpp pixels at depth z.
        let z = 50.0;
        let side = 256.0 / tpp * z / FOCUS;
        let corners = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
        let pos = |c: (f64, f64)| Vec3::new(-side / 2.0 + c.0 * side, -side / 2.0 + c.1 * side, z);
        let mut worst = 0i64;
        let mut drawn = 0;
        for persp in [true, false] {
            let mut buf = vec![u32::MAX; usize::from(W) * usize::from(W)];
            let mut fb = Framebuffer::new(&mut buf, W, W, usize::from(W)).unwrap();
            let out = if persp {
                let sh = PerspectiveTexture::<u32, RepeatPow2, 1>::new(tex).unwrap();
                let vs = corners.map(|c| {
                    let p = pos(c);
                    Vertex::new(
                        v::<S>(p.x, p.y, p.z),
                        UvPerspective {
                            u: S::from_f64(c.0 * 256.0 * uv_scale),
                            v: S::from_f64(c.1 * 256.0 * uv_scale),
                        },
                    )
                });
                pipe.draw_polygon(&mut fb, &mut NoDepth, &sh, &vs)
            } else {
                let sh = AffineTexture::<u32, RepeatPow2>::new(tex).unwrap();
                let vs = corners.map(|c| {
                    let p = pos(c);
                    Vertex::new(
                        v::<S>(p.x, p.y, p.z),
                        Uv {
                            u: S::from_f64(c.0 * 256.0 * uv_scale),
                            v: S::from_f64(c.1 * 256.0 * uv_scale),
                        },
                    )
                });
                pipe.draw_polygon(&mut fb, &mut NoDepth, &sh, &vs)
            };
            assert!(out.is_ok(), "{out:?}");
            for (k, &c) in buf.iter().enumerate() {
                if c == u32::MAX {
                    continue;
                }
                drawn += 1;
                assert!(
                    c & 0xffff < 256 && c >> 16 < 256,
                    "sample outside the texture"
                );
                let (x, y) = ((k % 64) as f64 + 0.5, (k / 64) as f64 + 0.5);
                // Exact (u, v) at the pixel center: the quad faces the camera.
                let px = (x - 32.0) * z / FOCUS;
                let py = (y - 32.0) * z / FOCUS;
                let u = (px + side / 2.0) / side * 256.0 * uv_scale;
                let vv = (py + side / 2.0) / side * 256.0 * uv_scale;
                let e = wrapped(i64::from(c & 0xffff), u.floor() as i64)
                    .max(wrapped(i64::from(c >> 16), vv.floor() as i64));
                worst = worst.max(e);
            }
        }
        (drawn, worst)
    }
    for tpp in [32.0, 128.0] {
        for (name, r) in [
            ("f32", case::<f32>(tex, &wrapped, tpp, 1.0)),
            ("I16F16", case::<I16F16>(tex, &wrapped, tpp, 1.0)),
        ] {
            println!(
                "{name}: {tpp} texels/pixel: {} pixels drawn, worst texel error {} (footprint bound {})",
                r.0,
                r.1,
                tpp + 1.0
            );
            assert!(r.0 > 0);
            assert!(r.1 as f64 <= tpp + 1.0, "{name} {tpp}");
        }
    }
    // uv of ±10⁶ texels: beyond the varyings' range; only "inside the
    // texture and no panic" is promised (checked inside `case`).
    let (n, _) = case::<f32>(tex, &wrapped, 32.0, 4000.0);
    println!("f32: uv up to 1e6 texels: {n} pixels drawn, all inside the texture");
}
