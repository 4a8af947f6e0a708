//! Perspective-correct texture mapping, pixel by pixel, against an f64
//! reference; and the texel error of the subdivided and affine modes.
//!
//! Scene: one tilted triangle receding from z = 3 to z = 40 in view space,
//! so that depth varies along rows as well as down the screen (on a level
//! floor every row has one depth and linear runs would be exact),
//! 160×120, focus 100 px, drawn
//! through the f64 pipeline into a `Framebuffer<u32>` whose texture holds
//! each texel's own coordinates (`u | v << 8`), so every written pixel
//! says which texel the shader read.
//!
//! Reference: the exact perspective mapping of the triangle *as the
//! rasterizer sees it*: its vertices rounded to 28.4 sub-pixel positions,
//! `u/z`, `v/z` and `1/z` interpolated linearly in screen space at the
//! pixel center and divided, all in f64. (Measuring against the unrounded
//! triangle would charge the 28.4 vertex rounding, which moves coverage
//! too, to the shader.) A pixel's error is the distance, in texels, from
//! the reference (u, v) to the texel the shader read (0 when the
//! reference lies inside it).
//!
//! Run with `--nocapture` to see the table.

use sightline::camera::Projection;
use sightline::math::Vec3;
use sightline::pipeline::{Pipeline, Uv, UvPerspective, Vertex};
use sightline::raster::{
    AffineTexture, NoDepth, PERSPECTIVE_Q_BITS, PerspectiveTexture, SUBPIXEL_BITS, SpanShader,
};
use sightline::scalar::Scalar;
use sightline::target::Framebuffer;
use sightline::texture::{RepeatPow2, Texture};

const W: u16 = 160;
const H: u16 = 120;
const FOCUS: f64 = 100.0;
const NEAR: f64 = 0.5;
const EMPTY: u32 = u32::MAX;

/// View-space vertices and their texel coordinates.
const TRI: [([f64; 3], [f64; 2]); 3] = [
    ([-2.2, 1.6, 3.0], [0.0, 0.0]),
    ([4.5, 3.0, 8.0], [200.0, 0.0]),
    ([-0.5, 1.5, 40.0], [0.0, 200.0]),
];

fn texels() -> Vec<u32> {
    (0..256u32 * 256)
        .map(|k| (k % 256) | (k / 256) << 8)
        .collect()
}

fn pipeline() -> Pipeline<f64> {
    Pipeline::new(
        Projection::perspective(FOCUS, W, H),
        W,
        H,
        NEAR,
        100.0,
        16.0,
    )
    .unwrap()
}

fn draw<A, Sh: SpanShader<K, Color = u32>, const K: usize>(
    shader: &Sh,
    attr: impl Fn([f64; 2]) -> A,
) -> Vec<u32>
where
    A: Copy + sightline::pipeline::Varyings<f64, K>,
{
    let mut buf = vec![EMPTY; W as usize * H as usize];
    let mut fb = Framebuffer::new(&mut buf, W, H, W as usize).unwrap();
    let verts = TRI.map(|(p, uv)| Vertex::new(Vec3::new(p[0], p[1], p[2]), attr(uv)));
    pipeline()
        .draw_polygon(&mut fb, &mut NoDepth, shader, &verts)
        .unwrap();
    buf
}

/// The reference (u, v) and depth z at every pixel center, over the
/// 28.4-rounded screen vertices.
fn reference() -> impl Fn(u16, u16) -> (f64, f64, f64) {
    let proj = Projection::perspective(FOCUS, W, H);
    let mut p = [(0.0, 0.0); 3];
    let mut a = [[0.0; 3]; 3];
    for (c, (v, uv)) in TRI.iter().enumerate() {
        let (s, _) = proj.project(Vec3::new(v[0], v[1], v[2])).unwrap();
        let r = |x: f64| x.to_subpixel(SUBPIXEL_BITS).unwrap() as f64 / 16.0;
        p[c] = (r(s.x), r(s.y));
        let q = 1.0 / v[2];
        a[c] = [uv[0] * q, uv[1] * q, q];
    }
    let (e1, e2) = (
        (p[1].0 - p[0].0, p[1].1 - p[0].1),
        (p[2].0 - p[0].0, p[2].1 - p[0].1),
    );
    let area = e1.0 * e2.1 - e1.1 * e2.0;
    move |x, y| {
        let c = (x as f64 + 0.5 - p[0].0, y as f64 + 0.5 - p[0].1);
        let b1 = (c.0 * e2.1 - c.1 * e2.0) / area;
        let b2 = (e1.0 * c.1 - e1.1 * c.0) / area;
        let at = |k: usize| a[0][k] + b1 * (a[1][k] - a[0][k]) + b2 * (a[2][k] - a[0][k]);
        (at(0) / at(2), at(1) / at(2), 1.0 / at(2))
    }
}

/// Distance from `x` to the texel interval `[t, t + 1]`.
fn off(x: f64, t: u32) -> f64 {
    let t = t as f64;
    (t - x).max(x - (t + 1.0)).max(0.0)
}

struct Errors {
    pixels: usize,
    max: f64,
    mean: f64,
    wrong: usize,
    /// Worst ratio of the error to the per-pixel bound (exact mode only).
    worst_ratio: f64,
}

fn measure(buf: &[u32], bound: impl Fn(u16, u16) -> f64) -> Errors {
    let reference = reference();
    let mut e = Errors {
        pixels: 0,
        max: 0.0,
        mean: 0.0,
        wrong: 0,
        worst_ratio: 0.0,
    };
    for y in 0..H {
        for x in 0..W {
            let texel = buf[y as usize * W as usize + x as usize];
            if texel == EMPTY {
                continue;
            }
            let (u, v, _) = reference(x, y);
            let d = off(u, texel & 255).max(off(v, texel >> 8));
            e.pixels += 1;
            e.max = e.max.max(d);
            e.mean += d;
            e.wrong += usize::from(d > 0.0);
            e.worst_ratio = e.worst_ratio.max(d / bound(x, y));
        }
    }
    e.mean /= e.pixels.max(1) as f64;
    e
}

fn report(name: &str, e: &Errors) {
    println!(
        "{name:<12} pixels {:>5}  max {:.5}  mean {:.6}  wrong texel {:>5} ({:.2} %)",
        e.pixels,
        e.max,
        e.mean,
        e.wrong,
        100.0 * e.wrong as f64 / e.pixels as f64
    );
}

fn perspective<const N: u32>(tex: Texture<'_, u32>) -> Vec<u32> {
    let shader = PerspectiveTexture::<u32, RepeatPow2, N>::new(tex).unwrap();
    draw(&shader, |uv| UvPerspective { u: uv[0], v: uv[1] })
}

#[test]
fn exact_perspective_matches_f64_reference_per_pixel() {
    let data = texels();
    let tex = Texture::new(&data, 256, 256, 256).unwrap();
    let buf = perspective::<1>(tex);
    // Error bound, derived from the representation: u·q and v·q are
    // 16.16 varyings and q = near/z is 8.24 (PERSPECTIVE_Q_BITS). A span
    // starts within ½ unit of its plane and steps by a value rounded to
    // ½ unit, so after at most W pixels a varying is off by at most
    // (1 + W)/2 units; the gradients' own rounding (8 extra bits) adds
    // under one unit more across the row. Dividing by q turns an error
    // of e units of u·q into e·2⁻¹⁶/q texels, and an error of e units of
    // q changes u (≤ 256 texels) by at most 256·e·2⁻²⁴/q.
    let reference = reference();
    let bound = |x: u16, y: u16| {
        let q = NEAR / reference(x, y).2;
        let e = (1.0 + W as f64) / 2.0 + 1.0;
        e * (-16f64).exp2() / q + 256.0 * e * (-(PERSPECTIVE_Q_BITS as f64)).exp2() / q
    };
    let e = measure(&buf, bound);
    report("exact", &e);
    assert!(e.pixels > 2000, "the triangle covers {} pixels", e.pixels);
    assert!(
        e.worst_ratio <= 1.0,
        "exact mode exceeds its derived bound by {:.2}×",
        e.worst_ratio
    );
    // Almost every pixel reads the reference texel; the rest sit within
    // the bound of a texel boundary.
    assert!(
        e.wrong * 100 < e.pixels,
        "{} of {} pixels read a different texel than the reference",
        e.wrong,
        e.pixels
    );
}

#[test]
fn subdivided_and_affine_errors_grow_with_run_length() {
    let data = texels();
    let tex = Texture::new(&data, 256, 256, 256).unwrap();
    let exact = measure(&perspective::<1>(tex), |_, _| 1.0);
    let p8 = measure(&perspective::<8>(tex), |_, _| 1.0);
    let p16 = measure(&perspective::<16>(tex), |_, _| 1.0);
    let p32 = measure(&perspective::<32>(tex), |_, _| 1.0);
    let affine_shader = AffineTexture::<u32, RepeatPow2>::new(tex).unwrap();
    let affine = measure(
        &draw(&affine_shader, |uv| Uv { u: uv[0], v: uv[1] }),
        |_, _| 1.0,
    );
    for (name, e) in [
        ("exact", &exact),
        ("persp 8", &p8),
        ("persp 16", &p16),
        ("persp 32", &p32),
        ("affine", &affine),
    ] {
        report(name, e);
    }
    // Same coverage for every mode: the shader does not move edges.
    for e in [&p8, &p16, &p32, &affine] {
        assert_eq!(e.pixels, exact.pixels);
    }
    // Linear runs between exact divisions err more the longer they are,
    // and affine mapping (one run per span) errs most: on this floor
    // (depth ratio 40/6) by many texels.
    assert!(exact.mean < p8.mean && p8.mean < p16.mean && p16.mean < p32.mean);
    assert!(p32.mean < affine.mean);
    assert!(exact.max < p8.max && p8.max < p32.max && p32.max < affine.max);
    assert!(
        affine.max > 4.0,
        "affine max error {:.2} texels",
        affine.max
    );
    // Exact mode stays within 1/16 texel.
    assert!(exact.max < 1.0 / 16.0);
}

/// `a × b`, `a · b`, `a − b` in f64.
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[test]
fn reference_is_close_to_the_unrounded_mapping() {
    // Guards the reference itself: the mapping before any rounding is the
    // pixel-center ray's hit on the triangle, with the hit's barycentric
    // weights applied to the texel coordinates. Rounding the vertices to
    // 1/16 px moves the reference by a fraction of a texel where the
    // triangle is near (z ≤ 15: ≤ ~3 texels per pixel); a wrong plane fit
    // would be off by many texels.
    let reference = reference();
    let [(a, ta), (b, tb), (c, tc)] = TRI;
    let (e1, e2) = (sub(b, a), sub(c, a));
    let n = cross(e1, e2);
    let mut worst: f64 = 0.0;
    let mut count = 0;
    for y in 0..H {
        for x in 0..W {
            let d = [
                (x as f64 + 0.5 - W as f64 / 2.0) / FOCUS,
                (y as f64 + 0.5 - H as f64 / 2.0) / FOCUS,
                1.0,
            ];
            let t = dot(n, a) / dot(n, d);
            let p = d.map(|k| k * t);
            let nn = dot(n, n);
            let w1 = dot(cross(sub(p, a), e2), n) / nn;
            let w2 = dot(cross(e1, sub(p, a)), n) / nn;
            let w0 = 1.0 - w1 - w2;
            if w0.min(w1).min(w2) < 0.05 || p[2] > 15.0 {
                continue;
            }
            let lerp = |k: usize| w0 * ta[k] + w1 * tb[k] + w2 * tc[k];
            let (u, v, _) = reference(x, y);
            worst = worst.max((u - lerp(0)).abs().max((v - lerp(1)).abs()));
            count += 1;
        }
    }
    println!("reference vs unrounded mapping, z <= 15: {count} pixels, max {worst:.4} texels");
    assert!(count > 500, "{count} pixels");
    assert!(
        worst < 0.25,
        "reference is {worst} texels from the analytic mapping"
    );
}
