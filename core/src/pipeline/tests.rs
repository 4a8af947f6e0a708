use super::*;
use crate::camera::Projection;
#[cfg(feature = "depth")]
use crate::raster::DepthBuffer;
#[cfg(feature = "gouraud")]
use crate::raster::Gouraud;
use crate::raster::{Flat, NoDepth};
use crate::scalar::{I16F16, Scalar};
use crate::test_util::MockTarget;
use proptest::prelude::*;
use std::vec::Vec;

fn v3<S: Scalar>(x: f64, y: f64, z: f64) -> Vec3<S> {
    Vec3::new(S::from_f64(x), S::from_f64(y), S::from_f64(z))
}

fn vi<S: Scalar>(x: f64, y: f64, z: f64, i: f64) -> VertexXyzI<S> {
    Vertex::new(v3(x, y, z), Intensity(S::from_f64(i)))
}

/// 12×8 viewport, focus 8 px, near 1, far 100, guard 4 px.
fn pipe<S: Scalar>() -> Pipeline<S> {
    Pipeline::new(
        Projection::perspective(S::from_i32(8), 12, 8),
        12,
        8,
        S::ONE,
        S::from_i32(100),
        S::from_i32(4),
    )
    .unwrap()
}

fn near_only<S: Scalar>(near: f64) -> Frustum<S> {
    Frustum::from_planes(&[Plane::new(v3(0.0, 0.0, 1.0), S::from_f64(-near))])
}

#[cfg(feature = "gouraud")]
fn digits() -> [char; 256] {
    core::array::from_fn(|i| char::from(b'0' + (i * 10 / 256) as u8))
}

/// Tolerance for comparisons in the scalar type: 256 ε times a magnitude.
fn tol<S: Scalar>(mag: f64) -> f64 {
    S::EPSILON.to_f64() * 256.0 * mag.max(1.0)
}

fn near_clip_interpolates<S: Scalar>() {
    // Edge z = 0 → 2 with intensity 0 → 1 crosses z = 1 at intensity ½.
    let tri = [
        vi::<S>(0.0, 0.0, 0.0, 0.0),
        vi(0.0, 0.0, 2.0, 1.0),
        vi(1.0, 0.0, 2.0, 1.0),
    ];
    let out = near_only::<S>(1.0).clip(&tri).unwrap();
    assert_eq!(out.len(), 4);
    for v in &out {
        assert!(v.pos.z.to_f64() >= 1.0 - tol::<S>(2.0));
    }
    let mid = out
        .iter()
        .find(|v| v.pos.x.to_f64().abs() < tol::<S>(1.0))
        .unwrap();
    assert!((mid.pos.z.to_f64() - 1.0).abs() <= tol::<S>(2.0));
    assert!((mid.attr.0.to_f64() - 0.5).abs() <= tol::<S>(1.0));
}

fn vertex_on_plane_is_kept_once<S: Scalar>() {
    let f = near_only::<S>(1.0);
    // One vertex on the plane, the rest inside: unchanged.
    let tri = [
        vi::<S>(0.0, 0.0, 1.0, 0.2),
        vi(1.0, 0.0, 2.0, 0.4),
        vi(0.0, 1.0, 3.0, 0.6),
    ];
    let out = f.clip(&tri).unwrap();
    assert_eq!(&out[..], &tri[..]);
    // One on the plane, one on each side: the on-plane vertex appears once,
    // plus one intersection.
    let tri = [
        vi::<S>(0.0, 0.0, 1.0, 0.0),
        vi(1.0, 0.0, 0.0, 0.0),
        vi(0.0, 1.0, 3.0, 1.0),
    ];
    let out = f.clip(&tri).unwrap();
    assert_eq!(out.len(), 3);
    assert_eq!(out.iter().filter(|v| **v == tri[0]).count(), 1);
    // Only touching the plane from outside: nothing remains.
    let tri = [
        vi::<S>(0.0, 0.0, 1.0, 0.0),
        vi(1.0, 0.0, 0.0, 0.0),
        vi(0.0, 1.0, 0.5, 1.0),
    ];
    assert!(f.clip(&tri).unwrap().is_empty());
}

fn polygon_in_plane_is_kept<S: Scalar>() {
    let quad = [
        vi::<S>(-1.0, -1.0, 1.0, 0.0),
        vi(1.0, -1.0, 1.0, 0.0),
        vi(1.0, 1.0, 1.0, 1.0),
        vi(-1.0, 1.0, 1.0, 1.0),
    ];
    assert_eq!(&near_only::<S>(1.0).clip(&quad).unwrap()[..], &quad[..]);
    // Wholly behind: empty.
    let behind: Vec<_> = quad
        .iter()
        .map(|v| Vertex::new(v3::<S>(0.0, 0.0, -1.0) + v.pos, v.attr))
        .collect();
    assert!(near_only::<S>(1.0).clip(&behind).unwrap().is_empty());
}

fn shared_edges_clip_identically<S: Scalar>() {
    // Two triangles share the edge P–Q, which crosses the near plane and
    // the left side plane; they traverse it in opposite directions.
    let p = pipe::<S>();
    let (pp, q) = (vi::<S>(-9.0, -0.5, 0.25, 0.0), vi::<S>(0.7, 0.9, 6.0, 1.0));
    let a = [pp, q, vi(-2.0, 3.0, 3.0, 0.5)];
    let b = [q, pp, vi(1.0, -2.0, 2.0, 0.5)];
    let ca = p.frustum().clip(&a).unwrap();
    let cb = p.frustum().clip(&b).unwrap();
    // Vertices of `ca` on the line P–Q must appear bit-identically in `cb`.
    let on_pq = |v: &VertexXyzI<S>| {
        let d = q.pos - pp.pos;
        let e = v.pos - pp.pos;
        let c = d.cross(e);
        let (x, y, z) = (c.x.to_f64(), c.y.to_f64(), c.z.to_f64());
        (x * x + y * y + z * z).sqrt() <= tol::<S>(100.0)
    };
    let shared: Vec<_> = ca.iter().filter(|v| on_pq(v)).collect();
    assert_eq!(shared.len(), 2, "{ca:?}");
    for v in shared {
        assert!(cb.iter().any(|w| w.pos == v.pos), "{v:?} not in {cb:?}");
    }
    // And the scan converter draws them without overlap.
    let mut t = MockTarget::new(12, 8);
    p.draw_polygon(&mut t, &mut NoDepth, &Flat('a'), &a)
        .unwrap();
    p.draw_polygon(&mut t, &mut NoDepth, &Flat('b'), &b)
        .unwrap();
}

#[cfg(feature = "gouraud")]
fn square_pattern<S: Scalar>() {
    // x, y ∈ [−1, 1] at z = 2 projects to x_s ∈ [2, 10], y_s ∈ [0, 8].
    let p = pipe::<S>();
    let sq = [
        vi::<S>(-1.0, -1.0, 2.0, 0.0),
        vi(1.0, -1.0, 2.0, 1.0),
        vi(1.0, 1.0, 2.0, 1.0),
        vi(-1.0, 1.0, 2.0, 0.0),
    ];
    let mut t = MockTarget::new(12, 8);
    p.draw_polygon(&mut t, &mut NoDepth, &Gouraud::new(&digits()), &sq)
        .unwrap();
    // Intensity at center x_s = c is 255·(c − 2)/8, shown as i·10/256.
    t.assert_pattern(&[
        "..01345689..", //
        "..01345689..", //
        "..01345689..", //
        "..01345689..", //
        "..01345689..", //
        "..01345689..", //
        "..01345689..", //
        "..01345689..", //
    ]);
}

fn near_clipped_floor_pattern<S: Scalar>() {
    // A floor y = 1 from z = 0 (behind the near plane) to z = 4: clipped at
    // z = 1 (y_s = 12, below the screen), far edge at y_s = 6, x_s ∈ [4, 8].
    // Row 6's center line meets the sides at 3.5 and 8.5, row 7's at 2.5
    // and 9.5.
    let p = pipe::<S>();
    let floor = [
        vi::<S>(-1.0, 1.0, 0.0, 0.0),
        vi(1.0, 1.0, 0.0, 0.0),
        vi(1.0, 1.0, 4.0, 0.0),
        vi(-1.0, 1.0, 4.0, 0.0),
    ];
    let mut t = MockTarget::new(12, 8);
    p.draw_polygon(&mut t, &mut NoDepth, &Flat('#'), &floor)
        .unwrap();
    t.assert_pattern(&[
        "............", //
        "............", //
        "............", //
        "............", //
        "............", //
        "............", //
        "...#####....", //
        "..#######...", //
    ]);
}

#[cfg(feature = "depth")]
fn depth_through_pipeline<S: Scalar>() {
    // A near square (z = 2) and a larger far one (z = 4) overlapping it:
    // drawn far first or near first, the near one wins where they overlap.
    let p = pipe::<S>();
    let sq = |h: f64, z: f64| {
        [
            Vertex::new(v3::<S>(-h, -h, z), ()),
            Vertex::new(v3(h, -h, z), ()),
            Vertex::new(v3(h, h, z), ()),
            Vertex::new(v3(-h, h, z), ()),
        ]
    };
    let near = sq(0.5, 2.0);
    let far = sq(2.0, 4.0);
    let expected = [
        "..ffffffff..", //
        "..ffffffff..", //
        "..ffnnnnff..", //
        "..ffnnnnff..", //
        "..ffnnnnff..", //
        "..ffnnnnff..", //
        "..ffffffff..", //
        "..ffffffff..", //
    ];
    for near_first in [false, true] {
        let mut zb = [u16::MAX; 96];
        let mut depth = DepthBuffer::new(&mut zb, 12, 8, 12, 0).unwrap();
        let mut t = MockTarget::new(12, 8);
        t.allow_overdraw = !near_first;
        let order = if near_first {
            [(near, 'n'), (far, 'f')]
        } else {
            [(far, 'f'), (near, 'n')]
        };
        for (poly, c) in order {
            p.draw_polygon(&mut t, &mut depth, &Flat(c), &poly).unwrap();
        }
        t.assert_pattern(&expected);
    }
}

#[cfg(all(feature = "gouraud", feature = "depth"))]
fn bad_input<S: Scalar>() {
    let p = pipe::<S>();
    let mut t = MockTarget::new(12, 8);
    t.allow_overdraw = true;
    let mut zb = [u16::MAX; 96];
    let mut depth = DepthBuffer::new(&mut zb, 12, 8, 12, 0).unwrap();
    // `from_f64` maps NaN to 0 and saturates, so build the specials by
    // arithmetic: 0/0 and ±1/0 are NaN and ±∞ for floats (0 and
    // saturated for fixed point).
    let sp = |k: usize| -> S {
        match k {
            0 => S::ZERO / S::from_i32(0),
            1 => S::ONE / S::ZERO,
            2 => -S::ONE / S::ZERO,
            k => S::from_f64([1e30, -1e30, 0.0, 1e-30, 3e4, -3e4, 0.5][k - 3]),
        }
    };
    for a in 0..10 {
        for b in 0..10 {
            let (x, y) = (sp(a), sp(b));
            let tri = [
                Vertex::new(Vec3::new(x, S::HALF, S::TWO), Intensity(y)),
                Vertex::new(Vec3::new(S::ONE, y, x), Intensity(S::HALF)),
                Vertex::new(Vec3::new(-S::ONE, S::ONE, y), Intensity(x)),
            ];
            let r = p.draw_polygon(&mut t, &mut depth, &Gouraud::new(&digits()), &tri);
            if S::IS_FLOAT && (a < 3 || b < 3) {
                assert_eq!(r, Err(DrawError::Clip(ClipError::NonFinite)));
            }
        }
    }
    // Fixed-point extremes.
    let (mx, mn) = (S::MAX.to_f64(), S::MIN.to_f64());
    let tri = [
        vi::<S>(mx, mn, mx, mx),
        vi(mn, mx, S::EPSILON.to_f64(), mn),
        vi(0.0, 0.0, mx, 0.5),
    ];
    let _ = p.draw_polygon(&mut t, &mut depth, &Gouraud::new(&digits()), &tri);
    // Too many vertices.
    let many = [vi::<S>(0.0, 0.0, 2.0, 0.0); MAX_INPUT_VERTICES + 1];
    assert_eq!(
        p.draw_polygon(&mut t, &mut NoDepth, &Flat('x'), &many),
        Err(DrawError::Clip(ClipError::TooManyVertices))
    );
    // Degenerate pipelines are refused.
    let proj = Projection::perspective(S::from_i32(8), 12, 8);
    assert_eq!(
        Pipeline::new(proj, 12, 8, S::ONE, S::ONE, S::ZERO),
        Err(PipelineError::BadDepthRange)
    );
    assert_eq!(
        Pipeline::new(proj, 12, 8, S::ZERO, S::ONE, S::ZERO),
        Err(PipelineError::BadDepthRange)
    );
}

fn parallel_projection_square<S: Scalar>() {
    // Scale 2 px per unit about (6, 4): x, y ∈ [−2, 2] → [2, 10] × [0, 8].
    let p = Pipeline::new(
        Projection::parallel(S::TWO, 12, 8),
        12,
        8,
        S::ONE,
        S::from_i32(10),
        S::ZERO,
    )
    .unwrap();
    let sq = [
        Vertex::new(v3::<S>(-2.0, -3.0, 5.0), ()),
        Vertex::new(v3(2.0, -3.0, 5.0), ()),
        Vertex::new(v3(2.0, 1.0, 5.0), ()),
        Vertex::new(v3(-2.0, 1.0, 5.0), ()),
    ];
    let mut t = MockTarget::new(12, 8);
    p.draw_polygon(&mut t, &mut NoDepth, &Flat('#'), &sq)
        .unwrap();
    // y ∈ [−3, 1] → y_s ∈ [−2, 6]; the top is clipped by the side plane
    // at the screen edge (guard 0).
    t.assert_pattern(&[
        "..########..", //
        "..########..", //
        "..########..", //
        "..########..", //
        "..########..", //
        "..########..", //
        "............", //
        "............", //
    ]);
}

/// Clipped vertices lie inside every plane (within tolerance) and their
/// intensities within the input's range. Random points with more than
/// three vertices are usually non-convex, and may then exceed the
/// capacity derived for convex input: that must be reported as
/// `TooManyVertices`, never truncated; a triangle always fits.
#[cfg(feature = "gouraud")]
fn clip_stays_in_volume<S: Scalar>(pts: &[(f64, f64, f64, f64)]) {
    let p = pipe::<S>();
    let tri: Vec<VertexXyzI<S>> = pts.iter().map(|&(x, y, z, i)| vi(x, y, z, i)).collect();
    let (lo, hi) = tri.iter().fold((f64::MAX, f64::MIN), |(lo, hi), v| {
        (lo.min(v.attr.0.to_f64()), hi.max(v.attr.0.to_f64()))
    });
    let out = match p.frustum().clip(&tri) {
        Ok(out) => out,
        Err(ClipError::TooManyVertices) if tri.len() > 3 => return,
        Err(e) => panic!("{e:?} for {tri:?}"),
    };
    assert!(out.len() <= MAX_CLIPPED_VERTICES);
    for v in &out {
        for pl in p.frustum().planes() {
            let d = pl.distance(v.pos).to_f64();
            assert!(d >= -tol::<S>(200.0), "{v:?} outside {pl:?} by {d}");
        }
        let i = v.attr.0.to_f64();
        assert!(
            i >= lo - tol::<S>(1.0) && i <= hi + tol::<S>(1.0),
            "{i} not in [{lo}, {hi}]"
        );
    }
    // And drawing never escapes the target.
    let mut t = MockTarget::new(12, 8);
    let _ = p.draw_polygon(&mut t, &mut NoDepth, &Gouraud::new(&digits()), &tri);
}

/// A small scene (two interpenetrating Gouraud quads, one crossing the
/// near plane) rendered to a 24×20 frame in one go and in bands of
/// `rows`: the results must be bit-identical.
#[cfg(all(feature = "gouraud", feature = "depth"))]
fn bands_match_full_frame<S: Scalar>() {
    use crate::target::{Band, Framebuffer};
    let p = Pipeline::new(
        Projection::perspective(S::from_i32(16), 24, 20),
        24,
        20,
        S::HALF,
        S::from_i32(50),
        S::from_i32(8),
    )
    .unwrap();
    let scene = [
        [
            vi::<S>(-3.0, -2.0, 4.0, 0.0),
            vi(2.0, -2.5, 6.0, 0.3),
            vi(2.5, 2.0, 3.0, 1.0),
            vi(-2.0, 2.5, 2.0, 0.6),
        ],
        [
            vi::<S>(-1.0, 1.0, 0.1, 1.0),
            vi(1.5, 1.0, 0.1, 0.8),
            vi(1.5, -1.0, 9.0, 0.2),
            vi(-1.0, -1.0, 9.0, 0.0),
        ],
    ];
    let ramp: [u8; 256] = core::array::from_fn(|i| i as u8);
    let sh = Gouraud::new(&ramp);
    let mut full = [0u8; 24 * 20];
    let mut zfull = [u16::MAX; 24 * 20];
    {
        let mut fb = Framebuffer::new(&mut full, 24, 20, 24).unwrap();
        let mut depth = DepthBuffer::new(&mut zfull, 24, 20, 24, 0).unwrap();
        for q in &scene {
            p.draw_polygon(&mut fb, &mut depth, &sh, q).unwrap();
        }
    }
    assert!(full.iter().filter(|&&c| c != 0).count() > 100);
    for rows in [1u16, 4, 6] {
        let mut out = Vec::new();
        let mut buf = [0u8; 24 * 6];
        let mut zb = [0u16; 24 * 6];
        let mut y0 = 0;
        while y0 < 20 {
            let n = rows.min(20 - y0 as u16);
            let mut band = Band::new(&mut buf, 24, n, 24, y0).unwrap();
            let mut depth = DepthBuffer::new(&mut zb, 24, n, 24, y0).unwrap();
            band.clear(0);
            depth.clear();
            for q in &scene {
                p.draw_polygon(&mut band, &mut depth, &sh, q).unwrap();
            }
            out.extend_from_slice(&band.as_slice()[..24 * n as usize]);
            y0 += n as i32;
        }
        assert_eq!(&out[..], &full[..], "bands of {rows}");
    }
    // Projected once, filled per band: the same pixels.
    let projected: Vec<_> = scene
        .iter()
        .map(|q| p.project_polygon::<_, 1>(q).unwrap().unwrap())
        .collect();
    let mut out = Vec::new();
    let mut buf = [0u8; 24 * 5];
    let mut zb = [0u16; 24 * 5];
    for y0 in (0..20).step_by(5) {
        let mut band = Band::new(&mut buf, 24, 5, 24, y0).unwrap();
        let mut depth = DepthBuffer::new(&mut zb, 24, 5, 24, y0).unwrap();
        band.clear(0);
        depth.clear();
        for s in &projected {
            crate::raster::fill_polygon(&mut band, &mut depth, &sh, s);
        }
        out.extend_from_slice(band.as_slice());
    }
    assert_eq!(&out[..], &full[..], "projected once");
}

/// A floor `y = 1`, `x ∈ [−2, 2]`, `z ∈ [¼, 8]` (crossing the near plane
/// at ½) textured with u = 2x + 4, v = 2z, through a 32×24 perspective
/// pipeline (focus 12). `make` builds the vertex attributes from (u, v).
#[cfg(feature = "perspective")]
fn render_floor<S: Scalar, A, Sh, const VARYINGS: usize>(
    sh: &Sh,
    make: impl Fn(S, S) -> A,
) -> [u16; 32 * 24]
where
    A: Varyings<S, VARYINGS>,
    Sh: crate::raster::SpanShader<VARYINGS, Color = u16>,
{
    use crate::target::Framebuffer;
    let p = Pipeline::new(
        Projection::perspective(S::from_i32(12), 32, 24),
        32,
        24,
        S::HALF,
        S::from_i32(64),
        S::from_i32(4),
    )
    .unwrap();
    let mut buf = [u16::MAX; 32 * 24];
    let mut fb = Framebuffer::new(&mut buf, 32, 24, 32).unwrap();
    let q: Vec<_> = [(-2.0, 0.25), (2.0, 0.25), (2.0, 8.0), (-2.0, 8.0)]
        .iter()
        .map(|&(x, z)| {
            Vertex::new(
                v3::<S>(x, 1.0, z),
                make(S::from_f64(2.0 * x + 4.0), S::from_f64(2.0 * z)),
            )
        })
        .collect();
    p.draw_polygon(&mut fb, &mut NoDepth, sh, &q).unwrap();
    buf
}

/// Pixels whose texel differs from the exact one found by casting a ray
/// in f64 through the pixel center, ignoring pixels within `margin`
/// texels of a texel boundary: (mismatches, drawn).
#[cfg(feature = "perspective")]
fn floor_mismatches(buf: &[u16; 32 * 24], margin: f64) -> (usize, usize) {
    let (cx, cy, f) = (16.0, 12.0, 12.0);
    let (mut bad, mut drawn) = (0, 0);
    for j in 0..24 {
        for i in 0..32 {
            let got = buf[j * 32 + i];
            if got == u16::MAX {
                continue;
            }
            drawn += 1;
            let (px, py) = (i as f64 + 0.5, j as f64 + 0.5);
            let z = f / (py - cy);
            let x = z * (px - cx) / f;
            let (u, v) = (2.0 * x + 4.0, 2.0 * z);
            let near_edge = |t: f64| (t - t.round()).abs() < margin;
            if near_edge(u) || near_edge(v) {
                continue;
            }
            let want =
                ((v.floor() as i64).rem_euclid(16) * 8 + (u.floor() as i64).rem_euclid(8)) as u16;
            if got != want {
                bad += 1;
            }
        }
    }
    (bad, drawn)
}

#[cfg(feature = "perspective")]
fn perspective_texture_matches_ray_cast<S: Scalar>() {
    use crate::raster::{AffineTexture, PerspectiveTexture};
    use crate::texture::{RepeatPow2, Texture};
    // Texel (i, j) of the 8×16 texture holds j·8 + i.
    let data: [u16; 128] = core::array::from_fn(|k| k as u16);
    let tex = Texture::new(&data, 8, 16, 8).unwrap();
    // The margin covers the rounding of 28.4 vertices and of q; it is
    // wider for I16F16, whose 1/z has only 16 fractional bits.
    let margin = if S::IS_FLOAT { 0.02 } else { 0.1 };
    let persp = |u, v| UvPerspective { u, v };
    let exact = PerspectiveTexture::<u16, RepeatPow2, 1>::new(tex).unwrap();
    let (bad, drawn) = floor_mismatches(&render_floor::<S, _, _, 3>(&exact, persp), margin);
    assert!(drawn > 150, "{drawn}");
    assert_eq!(bad, 0, "exact perspective: {bad} of {drawn}");
    // Subdivided runs: exact at run ends, affine between; the error stays
    // small on this floor.
    let sub8 = PerspectiveTexture::<u16, RepeatPow2, 8>::new(tex).unwrap();
    let sub16 = PerspectiveTexture::<u16, RepeatPow2, 16>::new(tex).unwrap();
    let sub32 = PerspectiveTexture::<u16, RepeatPow2, 32>::new(tex).unwrap();
    for buf in [
        render_floor::<S, _, _, 3>(&sub8, persp),
        render_floor::<S, _, _, 3>(&sub16, persp),
        render_floor::<S, _, _, 3>(&sub32, persp),
    ] {
        let (bad, drawn) = floor_mismatches(&buf, margin);
        assert!(bad * 20 <= drawn, "subdivided: {bad} of {drawn}");
    }
    // Affine mapping is visibly wrong on a floor seen in perspective.
    let affine = AffineTexture::<u16, RepeatPow2>::new(tex).unwrap();
    let (bad, drawn) = floor_mismatches(
        &render_floor::<S, _, _, 2>(&affine, |u, v| Uv { u, v }),
        margin,
    );
    assert!(bad * 4 > drawn, "affine should swim: {bad} of {drawn}");
}

/// A jittered grid mesh on the plane z = z0 + ax·x + by·y, crossing the
/// near plane and the side planes, drawn triangle by triangle into a
/// target that panics on overdraw and out-of-bounds writes: shared edges
/// must clip and project identically for the top-left rule to partition
/// them. The plane's visible part projects without folding, but snapping
/// to 28.4 can flip the orientation of slivers seen nearly edge-on, or
/// bend a clipped sliver quad into a non-convex one (a proptest case: a
/// quad of 0.15 px² cut by the guard band whose snapped corners turn both
/// ways, which the scan converter, exact only for convex input, fills over
/// its neighbour's pixel); such meshes genuinely overlap and are skipped
/// (returns `false`). The limitation is documented at
/// `Pipeline::project_polygon`.
fn clipped_mesh_has_no_overdraw<S: Scalar>(
    z0: f64,
    ax: f64,
    by: f64,
    cell: f64,
    jitter: &[(f64, f64)],
) -> bool {
    let p = Pipeline::new(
        Projection::perspective(S::from_i32(10), 24, 18),
        24,
        18,
        S::from_f64(0.3),
        S::from_i32(40),
        S::from_i32(2),
    )
    .unwrap();
    let n = 8usize;
    let vert = |i: usize, j: usize| {
        let (jx, jy) = jitter[(j * (n + 1) + i) % jitter.len()];
        let x = (i as f64 - n as f64 / 2.0 + jx * 0.25) * cell;
        let y = (j as f64 - n as f64 / 2.0 + jy * 0.25) * cell;
        Vertex::new(v3::<S>(x, y, z0 + ax * x + by * y), ())
    };
    let mut tris = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (
                vert(i, j),
                vert(i + 1, j),
                vert(i + 1, j + 1),
                vert(i, j + 1),
            );
            if (i + j) % 2 == 0 {
                tris.extend([[a, b, c], [a, c, d]]);
            } else {
                tris.extend([[a, b, d], [b, c, d]]);
            }
        }
    }
    // Orientation of each clipped, snapped polygon, and whether it stayed
    // convex (every turn between consecutive non-degenerate edges one way).
    let (mut pos, mut neg) = (false, false);
    for tri in &tris {
        let cl = p.frustum().clip(tri).unwrap();
        let sv: Vec<_> = cl.iter().filter_map(|v| p.project::<(), 0>(v)).collect();
        let mut area = 0i64;
        for k in 0..sv.len() {
            let (a, b) = (sv[k], sv[(k + 1) % sv.len()]);
            area += a.x as i64 * b.y as i64 - a.y as i64 * b.x as i64;
        }
        pos |= area > 0;
        neg |= area < 0;
        let edges: Vec<(i64, i64)> = (0..sv.len())
            .map(|k| {
                let (a, b) = (sv[k], sv[(k + 1) % sv.len()]);
                ((b.x - a.x) as i64, (b.y - a.y) as i64)
            })
            .filter(|&e| e != (0, 0))
            .collect();
        let (mut left, mut right) = (false, false);
        for k in 0..edges.len() {
            let (e, f) = (edges[k], edges[(k + 1) % edges.len()]);
            let turn = e.0 * f.1 - e.1 * f.0;
            left |= turn > 0;
            right |= turn < 0;
        }
        if left && right {
            return false;
        }
    }
    if pos && neg {
        return false;
    }
    let mut t = MockTarget::new(24, 18);
    for tri in &tris {
        p.draw_polygon(&mut t, &mut NoDepth, &Flat('#'), tri)
            .unwrap();
    }
    true
}

#[cfg(feature = "gouraud")]
fn slivers_clip_inside<S: Scalar>() {
    // Needle-thin triangles crossing the near plane and a side plane, one
    // with two vertices a grid step apart: clipping keeps them inside the
    // volume and drawing them neither panics nor escapes the target.
    let p = pipe::<S>();
    let e = S::EPSILON.to_f64();
    let slivers = [
        [
            vi::<S>(-30.0, 0.0, -1.0, 0.0),
            vi(30.0, 0.0, 9.0, 1.0),
            vi(30.0, e, 9.0, 1.0),
        ],
        [
            vi::<S>(0.0, 0.0, 0.5, 0.0),
            vi(0.0, 0.0, 0.5 + e, 1.0),
            vi(20.0, 3.0, 3.0, 0.5),
        ],
        [
            vi::<S>(-5.0, -5.0, 1.0, 0.2),
            vi(5.0, 5.0, 1.0, 0.8),
            vi(5.0, 5.0 + e, 1.0, 0.8),
        ],
    ];
    let mut t = MockTarget::new(12, 8);
    t.allow_overdraw = true;
    for tri in &slivers {
        let out = p.frustum().clip(tri).unwrap();
        for v in &out {
            for pl in p.frustum().planes() {
                assert!(pl.distance(v.pos).to_f64() >= -tol::<S>(100.0), "{v:?}");
            }
            let i = v.attr.0.to_f64();
            assert!((-tol::<S>(1.0)..=1.0 + tol::<S>(1.0)).contains(&i));
        }
        let _ = p.draw_polygon(&mut t, &mut NoDepth, &Gouraud::new(&digits()), tri);
    }
}

fn culling<S: Scalar>() {
    // Seen from the eye (looking along +z, y down), a→b→c runs
    // counter-clockwise: down the left side, then right along the bottom.
    // With y down that is a negative screen area: front-facing.
    let front = [
        Vertex::new(v3::<S>(-0.5, -0.5, 2.0), ()),
        Vertex::new(v3(-0.5, 0.5, 2.0), ()),
        Vertex::new(v3(0.5, 0.5, 2.0), ()),
    ];
    let back = [front[0], front[2], front[1]];
    let p = pipe::<S>();
    for (cull, f, b) in [
        (Cull::None, true, true),
        (Cull::Back, true, false),
        (Cull::Front, false, true),
    ] {
        let q = p.with_cull(cull);
        let mut t = MockTarget::new(12, 8);
        t.allow_overdraw = true;
        let rf = q
            .draw_polygon(&mut t, &mut NoDepth, &Flat('#'), &front)
            .unwrap();
        let rb = q
            .draw_polygon(&mut t, &mut NoDepth, &Flat('#'), &back)
            .unwrap();
        assert_eq!(rf.is_drawn(), f, "{cull:?}");
        assert_eq!(rb.is_drawn(), b, "{cull:?}");
        assert_eq!(rf == DrawOutcome::Culled, !f);
        assert_eq!(rb == DrawOutcome::Culled, !b);
    }
}

/// The pixels (12×8 viewport) that `poly` covers, and which shade.
fn covered<const VARYINGS: usize>(poly: &[ScreenVertex<VARYINGS>]) -> Vec<u32> {
    let mut px = std::vec![0u32; 12 * 8];
    let mut fb = crate::target::Framebuffer::new(&mut px, 12, 8, 12).unwrap();
    crate::raster::fill_polygon(&mut fb, &mut NoDepth, &Flat(1u32), poly);
    px
}

/// The smallest distance in pixels from (px, py) to the line of an edge
/// of the triangle `p` as `pipe` projects it (focus 8, center (6, 4)),
/// in f64; infinite if a vertex is not in front of the eye (its edges do
/// not project to lines through both ends).
fn edge_distance(p: &[(f64, f64, f64, f64); 3], px: f64, py: f64) -> f64 {
    if p.iter().any(|v| v.2 <= 0.0) {
        return f64::INFINITY;
    }
    let s = p.map(|(x, y, z, _)| (8.0 * x / z + 6.0, 8.0 * y / z + 4.0));
    (0..3)
        .map(|i| {
            let (a, b) = (s[i], s[(i + 1) % 3]);
            let (dx, dy) = (b.0 - a.0, b.1 - a.1);
            let len = dx.hypot(dy);
            if len == 0.0 {
                return f64::INFINITY;
            }
            ((px - a.0) * dy - (py - a.1) * dx).abs() / len
        })
        .fold(f64::INFINITY, f64::min)
}

/// The indexed-mesh path gives `project_polygon`'s result for every
/// triangle of a random point cloud (inside, clipped, outside, behind the
/// eye and culled, for every cull mode): the same vertices, or, for a
/// vertex within rounding of a side plane (classified there on its
/// projection, by the clipper on its view-space distance), the same
/// covered pixels.
fn mesh_matches_project_polygon<S: Scalar>(
    pts: &[(f64, f64, f64, f64)],
    tris: &[(usize, usize, usize)],
) {
    let verts: Vec<VertexXyzI<S>> = pts.iter().map(|&(x, y, z, i)| vi(x, y, z, i)).collect();
    for cull in [Cull::None, Cull::Back, Cull::Front] {
        let p = pipe::<S>().with_cull(cull);
        let mut proj = std::vec![MeshVertex::<1>::default(); verts.len()];
        p.project_vertices(&verts, &mut proj);
        for &(a, b, c) in tris {
            let (a, b, c) = (a % verts.len(), b % verts.len(), c % verts.len());
            let t = [a as u32, b as u32, c as u32];
            let mesh = p.mesh_triangle(&verts, &proj, t);
            let poly = p.project_polygon::<_, 1>(&[verts[a], verts[b], verts[c]]);
            match (mesh, poly) {
                (Ok(Some(m)), Ok(Some(q))) if m.as_slice() != q.as_slice() => {
                    let (cm, cq) = (covered(m.as_slice()), covered(&q));
                    for (k, (x, y)) in cm.iter().zip(&cq).enumerate() {
                        if x != y {
                            // The clipper cut at a side plane where the mesh
                            // path kept the vertex (or the reverse): the
                            // clip point is rounded onto the same edge, so
                            // only a pixel whose center lies within rounding
                            // of an edge of the triangle may change. Edges
                            // in f64 from the exact projection.
                            let (px, py) = ((k % 12) as f64 + 0.5, (k / 12) as f64 + 0.5);
                            let d = edge_distance(&[pts[a], pts[b], pts[c]], px, py);
                            assert!(
                                d < 0.125,
                                "{cull:?} {t:?}: pixel {k} differs {d} px from every edge"
                            );
                        }
                    }
                }
                (Ok(Some(_)), Ok(Some(_))) => {}
                // Entirely outside one plane: the clipper returns an empty
                // polygon, the mesh path nothing at all.
                (Ok(None), Ok(Some(q))) => assert!(q.len() < 3, "{cull:?} {t:?}"),
                (Ok(None), Ok(None)) => {}
                (m, q) => panic!("{cull:?} {t:?}: mesh {m:?} vs polygon {q:?}"),
            }
        }
    }
    // An index out of range is an error, not a panic.
    let mut proj = std::vec![MeshVertex::<1>::default(); verts.len()];
    pipe::<S>().project_vertices(&verts, &mut proj);
    assert!(
        pipe::<S>()
            .mesh_triangle(&verts, &proj, [0, 0, u32::MAX])
            .is_err()
    );
}

macro_rules! pipeline_tests {
    ($m:ident, $S:ty) => {
        mod $m {
            use super::*;
            #[test]
            fn near_clip_interpolates() {
                super::near_clip_interpolates::<$S>();
            }
            #[test]
            fn vertex_on_plane_is_kept_once() {
                super::vertex_on_plane_is_kept_once::<$S>();
            }
            #[test]
            fn polygon_in_plane_is_kept() {
                super::polygon_in_plane_is_kept::<$S>();
            }
            #[test]
            fn shared_edges_clip_identically() {
                super::shared_edges_clip_identically::<$S>();
            }
            #[cfg(feature = "gouraud")]
            #[test]
            fn square_pattern() {
                super::square_pattern::<$S>();
            }
            #[test]
            fn near_clipped_floor_pattern() {
                super::near_clipped_floor_pattern::<$S>();
            }
            #[cfg(feature = "depth")]
            #[test]
            fn depth_through_pipeline() {
                super::depth_through_pipeline::<$S>();
            }
            #[cfg(all(feature = "gouraud", feature = "depth"))]
            #[test]
            fn bands_match_full_frame() {
                super::bands_match_full_frame::<$S>();
            }
            #[cfg(feature = "perspective")]
            #[test]
            fn perspective_texture_matches_ray_cast() {
                super::perspective_texture_matches_ray_cast::<$S>();
            }
            #[cfg(feature = "gouraud")]
            #[test]
            fn slivers_clip_inside() {
                super::slivers_clip_inside::<$S>();
            }
            #[test]
            fn culling() {
                super::culling::<$S>();
            }
            #[cfg(all(feature = "gouraud", feature = "depth"))]
            #[test]
            fn bad_input() {
                super::bad_input::<$S>();
            }
            #[test]
            fn parallel_projection_square() {
                super::parallel_projection_square::<$S>();
            }
            proptest! {
                #[test]
                fn clipped_mesh_has_no_overdraw(
                    z0 in -2.0f64..6.0, ax in -1.5f64..1.5, by in -1.5f64..1.5,
                    cell in 0.05f64..3.0,
                    jitter in proptest::collection::vec((-1.0f64..1.0, -1.0f64..1.0), 1..30),
                ) {
                    prop_assume!(super::clipped_mesh_has_no_overdraw::<$S>(z0, ax, by, cell, &jitter));
                }

                #[test]
                fn mesh_matches_project_polygon(
                    pts in proptest::collection::vec(
                        (-3.0f64..3.0, -3.0f64..3.0, -1.0f64..8.0, 0.0f64..1.0), 3..12),
                    tris in proptest::collection::vec((0usize..12, 0usize..12, 0usize..12), 1..20),
                ) {
                    super::mesh_matches_project_polygon::<$S>(&pts, &tris);
                }

                #[cfg(feature = "gouraud")]
                #[test]
                fn clip_stays_in_volume(
                    pts in proptest::collection::vec(
                        (-40.0f64..40.0, -40.0f64..40.0, -5.0f64..150.0, 0.0f64..1.0), 3..8),
                ) {
                    super::clip_stays_in_volume::<$S>(&pts);
                }
            }
        }
    };
}

pipeline_tests!(f32_tests, f32);
pipeline_tests!(i16f16_tests, I16F16);
pipeline_tests!(f64_tests, f64);

/// Fuzz regression (`clip`): huge finite coordinates overflow the plane
/// distance (`n·p + d = −∞`) or the difference of two distances; the
/// intersection parameter then became 0 or NaN and the clipper kept the
/// vertex outside the plane. Every output vertex must be finite and inside
/// (to rounding of the coordinates' magnitude).
fn huge_coordinates_clip_inside<S: Scalar>() {
    let big = S::MAX;
    let planes = [Plane::new(v3::<S>(2.0, 2.0, 2.0), S::from_f64(15.625))];
    let f = Frustum::from_planes(&planes);
    let v = |x: S, y: S, z: S, i: f64| Vertex::new(Vec3::new(x, y, z), Intensity(S::from_f64(i)));
    let s = S::from_f64;
    let cases = [
        // The fuzz input: one vertex at z = −MAX.
        [
            v(s(13.5), s(18.5), s(18.5), 0.0),
            v(s(0.0), s(23.5), -big, 1.0),
            v(s(6.75), s(0.0), s(0.0), 0.5),
        ],
        // Vertices at both ends of the range: b − a overflows in lerp.
        [
            v(-big, s(0.0), s(0.0), 0.0),
            v(big, s(1.0), s(0.0), 1.0),
            v(s(0.0), big, s(0.0), 0.5),
        ],
        [
            v(big, -big, s(1.0), 0.0),
            v(-big, big, s(1.0), 1.0),
            v(-big, -big, s(1.0), 0.5),
        ],
    ];
    for poly in &cases {
        let out = f.clip(poly).unwrap();
        for o in &out {
            let p = [o.pos.x.to_f64(), o.pos.y.to_f64(), o.pos.z.to_f64()];
            assert!(
                p.iter().all(|c| c.is_finite()) && o.attr.0.is_finite(),
                "{o:?}"
            );
            assert!((0.0..=1.0).contains(&o.attr.0.to_f64()), "{o:?}");
            let dist = 2.0 * (p[0] + p[1] + p[2]) + 15.625;
            let tol = 64.0 * S::EPSILON.to_f64() * big.to_f64();
            assert!(dist >= -tol, "{}: {p:?} outside by {}", S::NAME, -dist);
        }
    }
    // The third fuzz input: a + (b − a)·t rounded past MAX to +∞ (then
    // ∞ − ∞ = NaN at the next plane).
    let f = Frustum::from_planes(&[Plane::new(v3::<S>(1.0, 0.0, 0.0), s(11.96875))]);
    let poly = [
        v(
            -s(2.0908917e38) * (big / s(3.4028235e38)),
            s(1.3119319e38) * (big / s(3.4028235e38)),
            s(16.0),
            0.0,
        ),
        v(s(-3.0517676e-5), big, s(41.5), 1.0),
        v(s(0.0), s(0.0), s(41.5), 0.5),
    ];
    for o in &f.clip(&poly).unwrap() {
        assert!(o.pos.is_finite(), "{}: {o:?}", S::NAME);
    }
    // The second fuzz input: a plane coefficient of −MAX made every
    // distance ±∞ and kept a vertex 0.375·MAX outside.
    let f = Frustum::from_planes(&[Plane::new(Vec3::new(S::ZERO, s(41.5), -big), S::ZERO)]);
    let poly = [
        v(s(0.0), s(0.5), s(0.375), 0.0),
        v(s(0.0), s(6.625), s(-9.0625), 1.0),
        v(s(0.0), s(1.3125), s(-11.0), 0.5),
    ];
    let out = f.clip(&poly).unwrap();
    assert_eq!(out.len(), 4, "{}: {out:?}", S::NAME);
    for o in &out {
        let (y, z) = (o.pos.y.to_f64(), o.pos.z.to_f64());
        let dist = 41.5 * y - big.to_f64() * z;
        let tol = 64.0 * S::EPSILON.to_f64() * big.to_f64() * 11.0;
        assert!(dist >= -tol, "{}: ({y}, {z}) outside by {}", S::NAME, -dist);
    }
}

#[test]
fn huge_coordinates_clip_inside_f32() {
    huge_coordinates_clip_inside::<f32>();
}

#[test]
fn huge_coordinates_clip_inside_f64() {
    huge_coordinates_clip_inside::<f64>();
}

#[test]
fn huge_coordinates_clip_inside_i16f16() {
    huge_coordinates_clip_inside::<I16F16>();
}

/// Fuzz regression (`clip`, I16F16): plane distances of ±42 000 and their
/// difference of 80 000 saturated at ±32 768 in fixed point, so the
/// intersection parameter came out wrong and a clipped vertex landed
/// 60 units outside a side plane `x ≤ 168.5 z`. The clipper now halves
/// such a plane (a power of two: same sign everywhere) until no distance
/// or difference can saturate for the polygon at hand. Every output
/// vertex, evaluated in f64 on its stored coordinates, must be inside.
#[test]
fn saturating_distances_clip_inside_i16f16() {
    type S = I16F16;
    let s = S::from_f64;
    let v = |x: f64, y: f64, z: f64, i: f64| Vertex::new(v3::<S>(x, y, z), Intensity(s(i)));
    let cases: [(Plane<S>, [VertexXyzI<S>; 3]); 4] = [
        // Distances ±20 220: their difference saturates.
        (
            Plane::new(v3(-1.0, 0.0, 168.5), S::ZERO),
            [
                v(0.0, 0.0, 120.0, 0.0),
                v(0.0, 0.0, -120.0, 1.0),
                v(0.0, 10.0, 0.0, 0.5),
            ],
        ),
        // The outside distance −42 125 saturates itself.
        (
            Plane::new(v3(-1.0, 0.0, 168.5), S::ZERO),
            [
                v(-10.0, 0.0, 0.0, 0.0),
                v(0.0, 0.0, -250.0, 1.0),
                v(-10.0, 5.0, 0.0, 0.5),
            ],
        ),
        // Unit normal, coordinates near the ends of the range.
        (
            Plane::new(v3(1.0, 0.0, 1.0), S::ZERO),
            [
                v(30000.0, 0.0, 0.0, 0.0),
                v(-30000.0, 0.0, -1000.0, 1.0),
                v(0.0, 20000.0, 5.0, 0.5),
            ],
        ),
        // b − a = 60 000 saturates in the interpolation as well.
        (
            Plane::new(v3(1.0, 0.0, 0.0), s(-1.0)),
            [
                v(-30000.0, 30000.0, -30000.0, 0.0),
                v(30000.0, -30000.0, 30000.0, 1.0),
                v(30000.0, 30000.0, 0.0, 0.5),
            ],
        ),
    ];
    for (plane, poly) in &cases {
        let out = Frustum::from_planes(&[*plane]).clip(poly).unwrap();
        assert!(out.len() >= 3, "{out:?}");
        let n = [plane.n.x, plane.n.y, plane.n.z].map(S::to_f64);
        let m = poly.iter().fold(0.0f64, |m, q| {
            m.max(q.pos.x.to_f64().abs())
                .max(q.pos.y.to_f64().abs())
                .max(q.pos.z.to_f64().abs())
        });
        for o in &out {
            let p = [o.pos.x, o.pos.y, o.pos.z].map(S::to_f64);
            let dist = n[0] * p[0] + n[1] * p[1] + n[2] * p[2] + plane.d.to_f64();
            // A few fixed-point steps of the largest term.
            let tol =
                8.0 * S::EPSILON.to_f64() * (n.iter().map(|c| c.abs()).sum::<f64>() * m + 1.0);
            assert!(
                dist >= -tol,
                "{p:?} outside {plane:?} by {} (tol {tol})",
                -dist
            );
            for k in 0..3 {
                let lo = poly
                    .iter()
                    .map(|q| [q.pos.x, q.pos.y, q.pos.z][k].to_f64())
                    .fold(f64::MAX, f64::min);
                let hi = poly
                    .iter()
                    .map(|q| [q.pos.x, q.pos.y, q.pos.z][k].to_f64())
                    .fold(f64::MIN, f64::max);
                assert!(
                    p[k] >= lo - tol && p[k] <= hi + tol,
                    "{p:?} outside the input box"
                );
            }
            let i = o.attr.0.to_f64();
            assert!((0.0..=1.0).contains(&i), "{o:?}");
            if poly.iter().any(|q| q.pos == o.pos) {
                continue;
            }
            // A new vertex lies on the plane and on an input edge.
            assert!(dist <= tol, "{p:?} off {plane:?} by {dist} (tol {tol})");
            let off_edge = (0..3)
                .map(|k| {
                    let a = [poly[k].pos.x, poly[k].pos.y, poly[k].pos.z].map(S::to_f64);
                    let b = [0, 1, 2].map(|c| {
                        [
                            poly[(k + 1) % 3].pos.x,
                            poly[(k + 1) % 3].pos.y,
                            poly[(k + 1) % 3].pos.z,
                        ][c]
                            .to_f64()
                    });
                    let ab = [0, 1, 2].map(|c| b[c] - a[c]);
                    let ap = [0, 1, 2].map(|c| p[c] - a[c]);
                    let t = (ab.iter().zip(&ap).map(|(x, y)| x * y).sum::<f64>()
                        / ab.iter().map(|x| x * x).sum::<f64>())
                    .clamp(0.0, 1.0);
                    (0..3)
                        .map(|c| (ap[c] - t * ab[c]).powi(2))
                        .sum::<f64>()
                        .sqrt()
                })
                .fold(f64::MAX, f64::min);
            assert!(
                off_edge <= tol,
                "{p:?} is {off_edge} off every input edge (tol {tol})"
            );
        }
    }
}

/// The in-volume cull test (`keep_inside`: i32 cross product on small
/// viewports) decides as the general one (`keep`) for every triangle in
/// the guard-band rectangle, for both cull modes, on a viewport that takes
/// the i32 path (990 px wide) and one that does not (4000 px).
#[test]
fn keep_inside_agrees_with_keep() {
    for (w, small) in [(990u16, true), (4000u16, false)] {
        let p = Pipeline::<f32>::new(
            Projection::perspective(400.0, w, 200),
            w,
            200,
            1.0,
            100.0,
            16.0,
        )
        .unwrap();
        assert_eq!(p.guard_small, small, "width {w}");
        let [x0, x1, y0, y1] = p.guard_rect;
        let mut r = 0x1234_5678_u32;
        let mut next = |lo: i32, hi: i32| {
            r ^= r << 13;
            r ^= r >> 17;
            r ^= r << 5;
            lo + (r % (hi - lo + 1) as u32) as i32
        };
        for cull in [Cull::Back, Cull::Front, Cull::None] {
            let p = p.with_cull(cull);
            for i in 0..20_000 {
                // Corners of the rectangle too: the extreme edge vectors.
                let pt = |next: &mut dyn FnMut(i32, i32) -> i32| {
                    if i % 4 == 0 {
                        (
                            if next(0, 1) == 0 { x0 } else { x1 },
                            if next(0, 1) == 0 { y0 } else { y1 },
                        )
                    } else {
                        (next(x0, x1), next(y0, y1))
                    }
                };
                let (a, b, c) = (pt(&mut next), pt(&mut next), pt(&mut next));
                let v = |q: (i32, i32)| ScreenVertex::new(q.0, q.1, 0, []);
                assert_eq!(
                    p.keep_inside(a, b, c),
                    p.keep(&[v(a), v(b), v(c)]),
                    "{cull:?} {a:?} {b:?} {c:?} (width {w})"
                );
            }
        }
    }
}

/// The i64 two-part shoelace sign equals the i128 shoelace sign for
/// polygons with any `i32` coordinates, extremes included.
#[test]
fn shoelace_front_matches_i128() {
    fn oracle(p: &[ScreenVertex<0>]) -> bool {
        let mut area2: i128 = 0;
        let mut prev = p[p.len() - 1];
        for &v in p {
            area2 += prev.x as i128 * v.y as i128 - prev.y as i128 * v.x as i128;
            prev = v;
        }
        area2 < 0
    }
    let mut r = 0x0bad_5eed_u32;
    let mut next = move || {
        r ^= r << 13;
        r ^= r >> 17;
        r ^= r << 5;
        r
    };
    let extremes = [i32::MIN, i32::MIN + 1, -1, 0, 1, i32::MAX - 1, i32::MAX];
    for case in 0..50_000 {
        let n = 3 + (next() % 10) as usize;
        let poly: Vec<ScreenVertex<0>> = (0..n)
            .map(|_| {
                let c = |r: u32| match case % 3 {
                    0 => extremes[(r % 7) as usize],
                    1 => r as i32,
                    _ => (r % 4001) as i32 - 2000,
                };
                ScreenVertex::new(c(next()), c(next()), 0, [])
            })
            .collect();
        let last = poly[n - 1];
        assert_eq!(mesh::shoelace_front(&poly, last), oracle(&poly), "{poly:?}");
    }
}

/// `project_vertex` tests the depth planes by comparing z with near (and
/// far): the outcode bits equal the sign of the planes' dot-product
/// distance, for points on, within rounding of, and far from the planes.
fn depth_outcodes_equal_plane_distances<S: Scalar>() {
    let near = 0.37;
    let far = 91.5;
    let base = Pipeline::<S>::new(
        Projection::perspective(S::from_i32(200), 320, 240),
        320,
        240,
        S::from_f64(near),
        S::from_f64(far),
        S::from_i32(16),
    )
    .unwrap();
    #[cfg(feature = "clip-far")]
    let pipes = [base, base.with_far_clip(true)];
    #[cfg(not(feature = "clip-far"))]
    let pipes = [base];
    let mut rng = crate::test_util::Rng::new(77);
    let eps = S::EPSILON.to_f64();
    let mut checked = [0u32; 2];
    for pipe in &pipes {
        let planes = pipe.frustum().planes();
        let depth_planes = planes.len() - 4;
        for i in 0..4000 {
            let z = match i % 6 {
                0 => near,
                1 => far,
                2 => near + eps * rng.range(-4.0, 4.0).round(),
                3 => far + eps * rng.range(-4.0, 4.0).round(),
                4 => rng.range(-40000.0, 40000.0),
                _ => rng.range(-1.0, 120.0),
            };
            let p = v3::<S>(rng.range(-3e4, 3e4), rng.range(-3e4, 3e4), z);
            let o = pipe.project_vertex::<(), 0>(&Vertex::new(p, ())).outcode;
            for (k, plane) in planes.iter().take(depth_planes).enumerate() {
                let outside = plane.distance(p) < S::ZERO;
                assert_eq!(o & (1 << k) != 0, outside, "{} plane {k} at {p:?}", S::NAME);
                checked[usize::from(outside)] += 1;
            }
        }
    }
    assert!(checked[0] > 500 && checked[1] > 500, "{checked:?}");
}

#[test]
fn depth_outcodes_equal_plane_distances_every_scalar() {
    depth_outcodes_equal_plane_distances::<f32>();
    depth_outcodes_equal_plane_distances::<f64>();
    depth_outcodes_equal_plane_distances::<I16F16>();
}
