//! Texture-vector recovery and perspective texture mapping.

use super::mcu::{McuCell, NO_KERNEL, lookup_span};
use super::routines_geom::{find, g, max_err, mean_err, ns, per_scalar, rand_vec, scalar_row, v3};
use super::{Pending, Rng, Row, Size, Table, bench, finish};
use sightline::camera::Projection;
use sightline::math::{Vec2, Vec3};
use sightline::pipeline::{Pipeline, Uv, UvPerspective, Vertex};
use sightline::raster::{AffineTexture, NoDepth, PerspectiveTexture};
use sightline::scalar::{I16F16, Scalar};
use sightline::target::Framebuffer;
use sightline::texture::{Mapping, TextureVectors, choose_mapping};
use sightline::texture::{RepeatPow2, Texture};

const FOCUS: f64 = 120.0;
const W: u16 = 240;
const CX: f64 = 120.0;

/// Exact (u, v) of the plane `X = P + u·U + v·V` seen through screen
/// point (x, y): intersect the view ray, then solve the 2×2 normal
/// equations of `X − P = u·U + v·V`. Independent of core's formulas.
fn exact_uv(p: Vec3<f64>, u: Vec3<f64>, v: Vec3<f64>, x: f64, y: f64) -> (f64, f64) {
    let d = Vec3::new((x - CX) / FOCUS, (y - CX) / FOCUS, 1.0);
    let n = u.cross(v);
    let t = n.dot(p) / n.dot(d);
    let r = d * t - p;
    let (uu, uv, vv) = (u.dot(u), u.dot(v), v.dot(v));
    let (ru, rv) = (r.dot(u), r.dot(v));
    let det = uu * vv - uv * uv;
    ((ru * vv - rv * uv) / det, (rv * uu - ru * uv) / det)
}

// ---------------------------------------------------------- texture vectors

struct TvCase {
    positions: [Vec3<f64>; 4],
    uvs: [Vec2<f64>; 4],
    /// (pixel x, pixel y, exact u, exact v) of interior points.
    samples: Vec<(f64, f64, f64, f64)>,
}

fn tv_cases(size: Size) -> Vec<TvCase> {
    let mut rng = Rng::new(21);
    let mut out = Vec::new();
    while out.len() < (size.samples / 16).max(8) {
        // Texture frame: origin P and texel steps U, V (not orthogonal).
        let z = rng.log_range(2.0, 20.0);
        let center = Vec3::new(rng.range(-0.4, 0.4) * z, rng.range(-0.4, 0.4) * z, z);
        let ext = rng.range(1.0, 5.0);
        let e1 = rand_vec(&mut rng, 1.0).normalize();
        let e2 = (rand_vec(&mut rng, 1.0) - e1 * 0.0).normalize();
        let n = e1.cross(e2);
        // Face the camera within ~70°: skip steeper frames.
        if n.length() < 0.3 || (n.normalize().dot(center.normalize())).abs() < 0.35 {
            continue;
        }
        let (u_axis, v_axis) = (e1 * (ext / 64.0), e2 * (ext / 64.0));
        let (u0, v0) = (rng.range(0.0, 192.0), rng.range(0.0, 192.0));
        let p = center - u_axis * (u0 + 32.0) - v_axis * (v0 + 32.0);
        let corner = [(0.0, 0.0), (64.0, 0.0), (64.0, 64.0), (0.0, 64.0)];
        let uvs = corner.map(|(a, b)| Vec2::new(u0 + a, v0 + b));
        let positions = uvs.map(|t| p + u_axis * t.x + v_axis * t.y);
        let samples = (0..16)
            .map(|_| {
                let (u, v) = (u0 + rng.range(0.0, 64.0), v0 + rng.range(0.0, 64.0));
                let x = p + u_axis * u + v_axis * v;
                (CX + FOCUS * x.x / x.z, CX + FOCUS * x.y / x.z, u, v)
            })
            .collect();
        out.push(TvCase {
            positions,
            uvs,
            samples,
        });
    }
    out
}

fn tv_row<S: Scalar>(size: Size, cases: &[TvCase]) -> Pending<'static> {
    let focus = S::from_f64(FOCUS);
    let center = Vec2::new(S::from_f64(CX), S::from_f64(CX));
    type In<S> = ([Vec3<S>; 4], [Vec2<S>; 4]);
    let inputs: Vec<In<S>> = cases
        .iter()
        .map(|c| (c.positions.map(v3), c.uvs.map(|t| t.cast())))
        .collect();
    let setup = move |(pos, uv): &In<S>| {
        TextureVectors::from_polygon(pos, uv)
            .ok()
            .and_then(|(m, _)| m.screen_mapping(focus, center))
    };
    let mut errs = Vec::new();
    let mut rejected = 0;
    for (c, inp) in cases.iter().zip(&inputs) {
        let Some(sm) = setup(inp) else {
            rejected += 1;
            continue;
        };
        for &(x, y, u, v) in &c.samples {
            match sm.uv(S::from_f64(x), S::from_f64(y)) {
                Some((su, sv)) => {
                    errs.push((su.to_f64() - u).abs().max((sv.to_f64() - v).abs()));
                }
                None => errs.push(f64::INFINITY),
            }
        }
    }
    scalar_row::<S>(&errs, NO_KERNEL, rejected, cases.len(), "rejected").timed(size, inputs, setup)
}

/// Texture-mapping vectors from a polygon, then (u, v) per pixel.
pub fn texture_vectors(size: Size) -> Table {
    let cases = tv_cases(size);
    let rows = finish(size, per_scalar!(tv_row(size, &cases)));
    let recommendation = format!(
        "The recovered mapping, evaluated per pixel, is within {} texels of the exact (u, v) \
         in f32 and {} texels in I16F16 (I20F12: {}). Half a texel is where nearest sampling \
         starts picking a neighboring texel, so {} for 64-texel quads of 1–5 units \
         at 2–20 units; the setup itself costs {} ns (f32) / {} ns (I16F16) per polygon, once \
         per polygon and frame.",
        g(max_err(&rows, "f32")),
        g(max_err(&rows, "I16F16")),
        g(max_err(&rows, "I20F12")),
        rows.iter()
            .filter(|r| r.repr != "f64")
            .map(|r| {
                let ok = r.err.is_some_and(|e| e.max < 0.5);
                format!(
                    "{} is {}",
                    r.repr,
                    if ok {
                        "adequate"
                    } else {
                        "not always adequate"
                    }
                )
            })
            .collect::<Vec<_>>()
            .join(", "),
        g(ns(&rows, "f32")),
        g(ns(&rows, "I16F16")),
    );
    Table {
        id: "texture_vectors",
        title: "Texture-vector recovery (polygon → U, V, P → per-pixel u, v)",
        op: "one polygon setup: `TextureVectors::from_polygon` + `screen_mapping`",
        unit: "texels: max(|u − u_exact|, |v − v_exact|) at sampled pixels",
        unit_short: "texels",
        setup: format!(
            "{} quads spanning 64×64 texels (texture offset up to 192), 1–5 units wide, at \
             depths 2–20 in a 240×240 view (focus 120 px), facing the camera within about \
             70°; U and V need not be orthogonal. 16 interior points per quad, projected in \
             f64; their (u, v) are chosen first, so the reference is exact. The mapping is \
             evaluated with `ScreenMapping::uv` in the same representation.",
            cases.len()
        ),
        rows,
        plot_mean: false,
        recommendation,
    }
}

// ---------------------------------------------------------- texture mapping

/// A textured quad in view space: texture point (u, v) lies at
/// `p + u·u_axis + v·v_axis`; the quad covers texels [0, 256)².
#[derive(Clone, Copy)]
struct Quad {
    p: Vec3<f64>,
    u_axis: Vec3<f64>,
    v_axis: Vec3<f64>,
}

impl Quad {
    fn new(corner: Vec3<f64>, right: Vec3<f64>, down: Vec3<f64>) -> Self {
        Self {
            p: corner,
            u_axis: right / 256.0,
            v_axis: down / 256.0,
        }
    }
    fn corners(&self) -> [(Vec3<f64>, Vec2<f64>); 4] {
        [(0.0, 0.0), (256.0, 0.0), (256.0, 256.0), (0.0, 256.0)]
            .map(|(u, v)| (self.p + self.u_axis * u + self.v_axis * v, Vec2::new(u, v)))
    }
}

fn quads() -> Vec<Quad> {
    vec![
        // A floor 1 unit below the eye from z = 0.6 to 30: strong
        // perspective, the case subdivision exists for.
        Quad::new(
            Vec3::new(-6.0, 1.0, 30.0),
            Vec3::new(12.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, -29.4),
        ),
        // A wall on the left receding from z = 1 to 20.
        Quad::new(
            Vec3::new(-3.0, -2.0, 1.0),
            Vec3::new(0.0, 0.0, 19.0),
            Vec3::new(0.0, 3.0, 0.0),
        ),
        // A quad turned 45° about the vertical, z 4 to 8.
        Quad::new(
            Vec3::new(0.5, -1.5, 4.0),
            Vec3::new(4.0, 0.0, 4.0),
            Vec3::new(0.0, 3.0, 0.0),
        ),
        // A quad parallel to the screen (affine is exact there).
        Quad::new(
            Vec3::new(-1.0, -3.0, 6.0),
            Vec3::new(2.5, 0.0, 0.0),
            Vec3::new(0.0, 2.5, 0.0),
        ),
    ]
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum TexMethod {
    Exact,
    Sub(u32),
    Affine,
    Auto,
}

impl TexMethod {
    fn name(self) -> String {
        match self {
            Self::Exact => "exact".into(),
            Self::Sub(n) => format!("sub{n}"),
            Self::Affine => "affine".into(),
            Self::Auto => "auto".into(),
        }
    }
}

/// The Cortex-M cell of a method: the span shader's instructions per
/// pixel from `docs/mcu/tables.md` where the QEMU fill benchmark has that
/// shader (exact, 16-pixel runs, affine), else a gap.
fn span_kernel(m: TexMethod) -> McuCell {
    match m {
        TexMethod::Exact => lookup_span("persp"),
        TexMethod::Sub(16) => lookup_span("persp16"),
        TexMethod::Affine => lookup_span("affine"),
        _ => NO_KERNEL,
    }
}

const TEX_METHODS: [TexMethod; 6] = [
    TexMethod::Exact,
    TexMethod::Sub(8),
    TexMethod::Sub(16),
    TexMethod::Sub(32),
    TexMethod::Affine,
    TexMethod::Auto,
];

/// Threshold of the automatic choice, in texels.
const AUTO_THRESHOLD: f64 = 1.0;

const EMPTY: u32 = u32::MAX;

/// The quads as triangles in `S`: positions and uv.
type Tri<S> = [(Vec3<S>, Vec2<S>); 3];

fn triangles<S: Scalar>(q: &Quad) -> [Tri<S>; 2] {
    let c = q.corners().map(|(p, t)| (v3::<S>(p), t.cast::<S>()));
    [[c[0], c[1], c[2]], [c[0], c[2], c[3]]]
}

fn draw_persp<S: Scalar, const N: u32>(
    pipe: &Pipeline<S>,
    fb: &mut Framebuffer<'_, u32>,
    tex: Texture<'_, u32>,
    tri: &Tri<S>,
) -> bool {
    let Some(sh) = PerspectiveTexture::<u32, RepeatPow2, N>::new(tex) else {
        return false;
    };
    let vs = tri.map(|(p, t)| Vertex::new(p, UvPerspective { u: t.x, v: t.y }));
    pipe.draw_polygon(fb, &mut NoDepth, &sh, &vs).is_ok()
}

fn draw_affine<S: Scalar>(
    pipe: &Pipeline<S>,
    fb: &mut Framebuffer<'_, u32>,
    tex: Texture<'_, u32>,
    tri: &Tri<S>,
) -> bool {
    let Some(sh) = AffineTexture::<u32, RepeatPow2>::new(tex) else {
        return false;
    };
    let vs = tri.map(|(p, t)| Vertex::new(p, Uv { u: t.x, v: t.y }));
    pipe.draw_polygon(fb, &mut NoDepth, &sh, &vs).is_ok()
}

/// Draws one triangle; returns false on a pipeline error.
fn draw<S: Scalar>(
    m: TexMethod,
    pipe: &Pipeline<S>,
    fb: &mut Framebuffer<'_, u32>,
    tex: Texture<'_, u32>,
    tri: &Tri<S>,
) -> bool {
    match m {
        TexMethod::Exact => draw_persp::<S, 1>(pipe, fb, tex, tri),
        TexMethod::Sub(8) => draw_persp::<S, 8>(pipe, fb, tex, tri),
        TexMethod::Sub(16) => draw_persp::<S, 16>(pipe, fb, tex, tri),
        TexMethod::Sub(_) => draw_persp::<S, 32>(pipe, fb, tex, tri),
        TexMethod::Affine => draw_affine(pipe, fb, tex, tri),
        TexMethod::Auto => {
            let z = tri.map(|(p, _)| p.z);
            let uv = tri.map(|(_, t)| t);
            match choose_mapping(z, uv, S::from_f64(AUTO_THRESHOLD)) {
                Mapping::Affine => draw_affine(pipe, fb, tex, tri),
                Mapping::Perspective => draw_persp::<S, 1>(pipe, fb, tex, tri),
            }
        }
    }
}

/// Texel index difference on the 256-texel torus.
fn wrapped(a: i64, b: i64) -> i64 {
    ((a - b + 128).rem_euclid(256) - 128).abs()
}

fn tex_rows<S: Scalar>(size: Size, quads: &[Quad], texels: &[u32]) -> Vec<Row> {
    let tex = Texture::new(texels, 256, 256, 256).expect("256×256 texture");
    let pipe = Pipeline::new(
        Projection::perspective(S::from_f64(FOCUS), W, W),
        W,
        W,
        S::from_f64(0.25),
        S::from_f64(1000.0),
        S::from_i32(16),
    )
    .expect("pipeline");
    let tris: Vec<(usize, Tri<S>)> = quads
        .iter()
        .enumerate()
        .flat_map(|(i, q)| triangles::<S>(q).map(|t| (i, t)))
        .collect();
    let mut buf = vec![EMPTY; usize::from(W) * usize::from(W)];
    let (pipe, tris) = (&pipe, &tris);
    let pending: Vec<Pending<'_>> = TEX_METHODS
        .iter()
        .map(|&m| {
            // Error: each quad alone, so every pixel knows its quad.
            let mut errs = Vec::new();
            let mut failed = 0;
            let mut off = 0usize;
            for (qi, q) in quads.iter().enumerate() {
                buf.fill(EMPTY);
                let mut fb = Framebuffer::new(&mut buf, W, W, usize::from(W)).expect("fb");
                for (_, t) in tris.iter().filter(|(i, _)| *i == qi) {
                    if !draw(m, pipe, &mut fb, tex, t) {
                        failed += 1;
                    }
                }
                for (k, &c) in buf.iter().enumerate() {
                    if c == EMPTY {
                        continue;
                    }
                    let (x, y) = (
                        (k % usize::from(W)) as f64 + 0.5,
                        (k / usize::from(W)) as f64 + 0.5,
                    );
                    let (u, v) = exact_uv(q.p, q.u_axis, q.v_axis, x, y);
                    let (tu, tv) = (i64::from(c & 0xffff), i64::from(c >> 16));
                    let e = wrapped(tu, u.floor() as i64).max(wrapped(tv, v.floor() as i64));
                    if e > 0 {
                        off += 1;
                    }
                    errs.push(e as f64);
                }
            }
            // Time: the whole frame; ns per covered pixel.
            let pixels = errs.len().max(1) as f64;
            // Each benchmark draws into its own frame.
            let mut frame_buf = vec![EMPTY; usize::from(W) * usize::from(W)];
            let b = bench(size, vec![()], pixels, move |_| {
                let mut fb = Framebuffer::new(&mut frame_buf, W, W, usize::from(W)).expect("fb");
                let mut ok = true;
                for (_, t) in tris {
                    ok &= draw(m, pipe, &mut fb, tex, t);
                }
                ok
            });
            let mut note = format!(
                "{:.1}% of {} pixels off by ≥ 1 texel",
                100.0 * off as f64 / pixels,
                errs.len()
            );
            if failed > 0 {
                note.push_str(&format!("; {failed} triangles not drawn"));
            }
            let row = Row::new(
                format!("{}, {}", S::NAME, m.name()),
                &errs,
                span_kernel(m),
                note,
            );
            (row, b)
        })
        .collect();
    // Round-robin over the six methods of this representation.
    finish(size, pending)
}

/// Perspective texture mapping through the whole pipeline, per method.
pub fn texture_mapping(size: Size) -> Table {
    let quads = quads();
    // Texel (u, v) holds u | v << 16, so the frame records which texel
    // each pixel sampled.
    let texels: Vec<u32> = (0..256u32 * 256)
        .map(|i| (i % 256) | ((i / 256) << 16))
        .collect();
    let mut rows = tex_rows::<f32>(size, &quads, &texels);
    rows.extend(tex_rows::<I16F16>(size, &quads, &texels));
    let mean = |s: &str| mean_err(&rows, s);
    // Share of pixels off by a texel or more, from the notes.
    let off = |s: &str| {
        find(&rows, s)
            .and_then(|r| r.note.split('%').next()?.parse::<f64>().ok())
            .unwrap_or(f64::NAN)
    };
    let longest_ok = [8, 16, 32]
        .iter()
        .copied()
        .filter(|n| off(&format!("f32, sub{n}")) <= 10.0)
        .max();
    // Span-loop cost on a Cortex-M0 (no divide instruction), where the
    // choice matters most.
    let mcu = |m: TexMethod| match span_kernel(m) {
        McuCell::Measured { v6m, .. } => v6m,
        McuCell::Gap(_) => f64::NAN,
    };
    let m0 = format!(
        "On a Cortex-M0-class core, which has no divide instruction, the span loop costs {} \
         instructions per pixel exact, {} with 16-pixel runs and {} affine \
         (`docs/mcu/tables.md`, span loop only): {}× and {}× the exact cost. On this \
         host 16-pixel runs take {}× the exact time.",
        g(mcu(TexMethod::Exact)),
        g(mcu(TexMethod::Sub(16))),
        g(mcu(TexMethod::Affine)),
        g(mcu(TexMethod::Sub(16)) / mcu(TexMethod::Exact)),
        g(mcu(TexMethod::Affine) / mcu(TexMethod::Exact)),
        g(ns(&rows, "f32, sub16") / ns(&rows, "f32, exact")),
    );
    let sub_advice = match longest_ok {
        Some(n) => format!(
            "Where the exact divide is too slow, {n}-pixel runs are the longest that keep \
             more than 90% of pixels on the exact texel ({}% off), at {}× the exact time on \
             this host. {m0} Polygons that face the camera are best left to the automatic \
             choice.",
            g(off(&format!("f32, sub{n}"))),
            g(ns(&rows, &format!("f32, sub{n}")) / ns(&rows, "f32, exact"))
        ),
        None => format!(
            "Every subdivision puts more than 10% of pixels on a wrong texel here, so \
             keep the exact divide for steep polygons. {m0}"
        ),
    };
    let recommendation = format!(
        "Exact per-pixel division is within {} texel of the exact texel index (mean {}; \
         the I16F16 pipeline shows the same residue, so it comes from the shared integer \
         rasterizer, with 28.4 vertices and 16.16 varyings, not from the scalar) at {} ns/pixel in f32. \
         Subdividing every 8 / 16 / 32 pixels raises the maximum to {} / {} / {} texels \
         (means {} / {} / {}) at {} / {} / {} ns/pixel. Affine mapping is off by up to {} \
         texels on the steep floor and wall (128 is the largest difference a 256-texel wrap \
         can show, i.e. an unrelated texel; mean {}). The automatic choice (threshold {} \
         texel on the bound of `affine_error_bound`) keeps exact accuracy ({} max) and only \
         uses affine where the bound allows, here at {} ns/pixel. The I16F16 pipeline gives \
         the same picture (exact: {} max). {}",
        g(max_err(&rows, "f32, exact")),
        g(mean("f32, exact")),
        g(ns(&rows, "f32, exact")),
        g(max_err(&rows, "f32, sub8")),
        g(max_err(&rows, "f32, sub16")),
        g(max_err(&rows, "f32, sub32")),
        g(mean("f32, sub8")),
        g(mean("f32, sub16")),
        g(mean("f32, sub32")),
        g(ns(&rows, "f32, sub8")),
        g(ns(&rows, "f32, sub16")),
        g(ns(&rows, "f32, sub32")),
        g(max_err(&rows, "f32, affine")),
        g(mean("f32, affine")),
        AUTO_THRESHOLD,
        g(max_err(&rows, "f32, auto")),
        g(ns(&rows, "f32, auto")),
        g(max_err(&rows, "I16F16, exact")),
        sub_advice,
    );
    Table {
        id: "texture_mapping",
        title: "Perspective texture mapping (pipeline + raster)",
        op: "one covered pixel (frame time of all quads / covered pixels)",
        unit: "texels: max(|Δu|, |Δv|) of the sampled texel index against the exact texel",
        unit_short: "texels",
        setup: "Four 256×256-texel quads in a 240×240 view (focus 120 px): a floor from z = \
                0.6 to 30, a receding wall, a quad turned 45° and one parallel to the screen; \
                each drawn as two triangles through `Pipeline::draw_polygon` (clip, project to \
                28.4, scan-convert) into a u32 frame with a texture whose texels encode their \
                own (u, v), nearest sampling with wrap. Reference: the texel under each pixel \
                center, from an f64 ray–plane intersection (independent of core's mapping \
                code). `auto` = `choose_mapping` per triangle (affine, else exact). The f64 \
                pipeline is left out: the rasterizer's fixed-point varyings, not the scalar, \
                set the floor."
            .into(),
        rows,
        plot_mean: true,
        recommendation,
    }
}
