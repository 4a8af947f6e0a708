//! Whole frames of the built-in scenes, fill-rate polygons and the W1/W2
//! bunny workloads, written once for the firmware and the host.
//!
//! This file is shared: the firmware (`tests/mcu/src/main.rs`) and the host
//! test `tests/tests/mcu_frames.rs` both include it, so the frame hashes the
//! host computes come from exactly the code that runs on the MCU. It
//! depends only on `core`, `sightline` and `embedded-graphics`, and on
//! sightline's `full` feature set.
//!
//! - [`render_scene`]: a built-in scene at [`WIDTH`]×[`HEIGHT`] through
//!   bands of [`BAND_ROWS`] rows with a band-sized u16 depth buffer; the
//!   raster path for every scene but `spheres`, which is the ray path's
//!   (spheres are ray-only). Each finished row goes to a callback.
//! - [`fill`]: one fill-rate polygon per span shader, covering all 240 rows
//!   and the full or half width, filled [`FILL_REPEAT`] times.
//! - [`Workload`]: W1/W2 (`/work/shared/WORKLOADS.md`) on the built-in
//!   quantised bunny.

use core::hint::black_box;
use embedded_graphics::pixelcolor::{IntoStorage, Rgb565, RgbColor};
use sightline::camera::{Camera, Projection};
use sightline::math::Vec3;
use sightline::pipeline::{
    Cull, Intensity, MeshVertex, Pipeline, ScreenPolygon, Uv, UvPerspective, Varyings, Vertex,
};
use sightline::raster::{
    AffineTexture, DepthBuffer, Flat, Gouraud, NoDepth, PerspectiveTexture, RepeatPow2,
    ScreenVertex, Shade, Texture, fill_polygon,
};
use sightline::scalar::{I16F16, Scalar};
use sightline::scene::builtin::{
    self, BUNNY_NORMALS, BUNNY_POSITIONS, BUNNY_SCALE, BUNNY_TRIANGLES,
};
use sightline::scene::{self, Color, RayScene, Scene, SceneError};
use sightline::target::{Band, Framebuffer};
use sightline::transform::{Euler, Pose};

/// Frame width in pixels.
pub const WIDTH: u16 = 320;
/// Frame height in pixels.
pub const HEIGHT: u16 = 240;
/// Rows per band of [`render_scene`].
pub const BAND_ROWS: u16 = 40;
/// Pixels of one band.
pub const BAND_PIXELS: usize = WIDTH as usize * BAND_ROWS as usize;
/// Pixels of one frame.
pub const FRAME_PIXELS: usize = WIDTH as usize * HEIGHT as usize;

/// The scenes [`render_scene`] draws, by built-in name, in output order.
pub const SCENES: [&str; 5] = ["cube", "bunny", "corridor", "corridor-affine", "spheres"];

/// FNV-1a, 64-bit.
#[derive(Clone, Copy, Debug)]
pub struct Fnv(pub u64);
impl Fnv {
    /// The offset basis.
    pub const fn new() -> Self {
        Self(0xcbf2_9ce4_8422_2325)
    }
    /// Hashes the two little-endian bytes of `v`.
    pub fn u16(&mut self, v: u16) {
        for b in v.to_le_bytes() {
            self.0 ^= b as u64;
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    /// Hashes pixels as RGB565 storage words.
    pub fn pixels(&mut self, px: &[Color]) {
        for &c in px {
            self.u16(c.into_storage());
        }
    }
}
impl Default for Fnv {
    fn default() -> Self {
        Self::new()
    }
}

/// Renders built-in scene `name` in scalar `S` at [`WIDTH`]×[`HEIGHT`],
/// band by band in `color` and `depth` (each at least [`BAND_PIXELS`]
/// long), calling `row(y, pixels)` for every finished row top to bottom.
/// Returns FNV-1a over all pixels in row order.
///
/// # Errors
/// An unknown name gives [`SceneError::BadProjection`]; otherwise the
/// scene's own error (the built-in scenes have none).
pub fn render_scene<S: Scalar>(
    name: &str,
    color: &mut [Color],
    depth: &mut [u16],
    mut row: impl FnMut(u16, &[Color]),
) -> Result<u64, SceneError> {
    let scene: &Scene<'_> = builtin::by_name(name).ok_or(SceneError::BadProjection)?;
    let view = scene.view::<S>(WIDTH, HEIGHT)?;
    let ray = if name == "spheres" {
        Some(RayScene::new(scene, &view)?)
    } else {
        None
    };
    let (color, depth) = (&mut color[..BAND_PIXELS], &mut depth[..BAND_PIXELS]);
    let mut h = Fnv::new();
    let w = WIDTH as usize;
    for y0 in (0..HEIGHT).step_by(BAND_ROWS as usize) {
        let rows = BAND_ROWS.min(HEIGHT - y0);
        let n = w * rows as usize;
        let bad = |_| SceneError::BadProjection;
        let mut band = Band::new(&mut color[..n], WIDTH, rows, w, y0 as i32).map_err(bad)?;
        match &ray {
            Some(r) => r.render(&mut band),
            None => {
                let mut z =
                    DepthBuffer::new(&mut depth[..n], WIDTH, rows, w, y0 as i32).map_err(bad)?;
                z.clear();
                scene::render_raster(scene, &view, &mut band, &mut z)?;
            }
        }
        for r in 0..rows as usize {
            let px = &color[r * w..(r + 1) * w];
            h.pixels(px);
            row(y0 + r as u16, px);
        }
    }
    Ok(h.0)
}

// ---------------------------------------------------------------- fill rate

/// The span shaders measured in instructions per pixel, by name.
pub const FILL_MODES: [&str; 7] = [
    "flat",
    "flat-depth",
    "gouraud-depth",
    "affine",
    "persp",
    "persp16",
    "persp16-depth",
];

/// Fills per run of [`fill`].
pub const FILL_REPEAT: u32 = 4;

/// Texture side of the fill-rate texture.
pub const FILL_TEX: u16 = 64;

/// The fill-rate texture: a 64×64 pattern.
pub fn fill_texels() -> [Color; FILL_TEX as usize * FILL_TEX as usize] {
    core::array::from_fn(|i| {
        let (x, y) = (i % FILL_TEX as usize, i / FILL_TEX as usize);
        Rgb565::new(
            (x >> 1) as u8,
            (y as u8) ^ (x as u8),
            ((x ^ y) & 31) as u8 | 1,
        )
    })
}

/// The fill-rate quad: a plane tilted away from the eye (view depth 1 at
/// the bottom of the screen, 4 at the top), `x = ±0.8·z/halve`, so that it
/// covers all 240 rows and 320 (or, halved, the middle 160) pixels of each
/// row: exactly 76 800 or 38 400 pixels. Texture coordinates repeat the
/// 64-texel texture 4 times across and along.
fn quad<A: Varyings<I16F16, K>, const K: usize>(
    halve: bool,
    attr: impl Fn(usize) -> A,
) -> ScreenPolygon<K> {
    let pipe = Pipeline::new(
        Projection::perspective(I16F16::from_i32(200), WIDTH, HEIGHT),
        WIDTH,
        HEIGHT,
        I16F16::from_f32(0.5),
        I16F16::from_i32(10),
        I16F16::from_i32(16),
    );
    let Ok(pipe) = pipe else {
        return ScreenPolygon::new();
    };
    let k = if halve { 0.4 } else { 0.8 };
    let corners = [
        (-k, 0.6, 1.0),
        (k, 0.6, 1.0),
        (4.0 * k, -2.4, 4.0),
        (-4.0 * k, -2.4, 4.0),
    ];
    let poly: [Vertex<I16F16, A>; 4] = core::array::from_fn(|i| {
        let (x, y, z) = corners[i];
        Vertex::new(
            Vec3::new(
                I16F16::from_f32(x),
                I16F16::from_f32(y),
                I16F16::from_f32(z),
            ),
            attr(i),
        )
    });
    match pipe.project_polygon(&poly) {
        Ok(Some(p)) => p,
        _ => ScreenPolygon::new(),
    }
}

fn uv(i: usize) -> (I16F16, I16F16) {
    let t = I16F16::from_i32(4 * FILL_TEX as i32);
    let z = I16F16::ZERO;
    [(z, z), (t, z), (t, t), (z, t)][i]
}

/// The polygon with every depth key `f` units nearer.
fn nearer<const K: usize>(p: &ScreenPolygon<K>, f: u32) -> ScreenPolygon<K> {
    p.iter()
        .map(|&s| ScreenVertex {
            z: s.z.saturating_sub(f as u16),
            ..s
        })
        .collect()
}

/// Fills the fill-rate quad of mode `mode` [`FILL_REPEAT`] times into the
/// whole-frame `color` and `depth` buffers (each at least
/// [`FRAME_PIXELS`] long), after clearing both. `halve` selects the
/// half-width quad. Depth modes move the quad one key unit nearer per
/// fill, so every pixel passes the less-than test every time. Returns the
/// pixels written by the last fill (counted in the colour buffer against
/// the cleared colour), or `None` for an unknown mode.
pub fn fill(mode: &str, halve: bool, color: &mut [Color], depth: &mut [u16]) -> Option<u32> {
    let (w, h) = (WIDTH, HEIGHT);
    let (color, depth) = (&mut color[..FRAME_PIXELS], &mut depth[..FRAME_PIXELS]);
    let texels = fill_texels();
    let tex = Texture::new(&texels, FILL_TEX, FILL_TEX, FILL_TEX as usize).ok()?;
    let ramp = Rgb565::GREEN.ramp();
    let mut fb = Framebuffer::new(&mut *color, w, h, w as usize).ok()?;
    let mut z = DepthBuffer::new(&mut *depth, w, h, w as usize, 0).ok()?;
    fb.clear(Rgb565::BLACK);
    z.clear();
    let n = FILL_REPEAT;
    match mode {
        "flat" => {
            let p = quad(halve, |_| ());
            for i in 0..n {
                let c = Rgb565::new(1 + i as u8, 20, 20);
                fill_polygon(&mut fb, &mut NoDepth, &Flat(c), black_box(&p));
            }
        }
        "flat-depth" => {
            let p = quad(halve, |_| ());
            for i in 0..n {
                let c = Rgb565::new(1 + i as u8, 20, 20);
                fill_polygon(&mut fb, &mut z, &Flat(c), &nearer(black_box(&p), i + 1));
            }
        }
        "gouraud-depth" => {
            let p = quad(halve, |i| {
                Intensity(I16F16::from_f32([0.2, 0.8, 1.0, 0.4][i]))
            });
            let sh = Gouraud::new(&ramp);
            for i in 0..n {
                fill_polygon(&mut fb, &mut z, &sh, &nearer(black_box(&p), i + 1));
            }
        }
        "affine" => {
            let p = quad(halve, |i| {
                let (u, v) = uv(i);
                Uv { u, v }
            });
            let sh = AffineTexture::<_, RepeatPow2>::new(tex)?;
            for _ in 0..n {
                fill_polygon(&mut fb, &mut NoDepth, &sh, black_box(&p));
            }
        }
        "persp" | "persp16" | "persp16-depth" => {
            let p = quad(halve, |i| {
                let (u, v) = uv(i);
                UvPerspective { u, v }
            });
            if mode == "persp" {
                let sh = PerspectiveTexture::<_, RepeatPow2, 1>::new(tex)?;
                for _ in 0..n {
                    fill_polygon(&mut fb, &mut NoDepth, &sh, black_box(&p));
                }
            } else {
                let sh = PerspectiveTexture::<_, RepeatPow2, 16>::new(tex)?;
                for i in 0..n {
                    if mode == "persp16" {
                        fill_polygon(&mut fb, &mut NoDepth, &sh, black_box(&p));
                    } else {
                        fill_polygon(&mut fb, &mut z, &sh, &nearer(black_box(&p), i + 1));
                    }
                }
            }
        }
        _ => return None,
    }
    Some(
        black_box(&*color)
            .iter()
            .filter(|&&c| c != Rgb565::BLACK)
            .count() as u32,
    )
}

// ---------------------------------------------------------------- W1 / W2

/// Vertices of the built-in bunny.
pub const BUNNY_VERTS: usize = BUNNY_POSITIONS.len();

/// Frames per turn in W1/W2 (frame `k` of it yaws the model by 2πk/N).
pub const WORKLOAD_TURN: u32 = 200;
/// Frame step of the instruction-count variant (every 10th frame: 20
/// frames per turn).
pub const WORKLOAD_STEP: u32 = 10;

/// W1/W2 on the built-in quantised bunny (`scene::builtin::BUNNY_*`, the
/// same 1839 vertices and 3674 triangles as `data/bunny.obj`, stored as
/// i16 with 1/2048 unit steps, and its stored unit vertex normals): the
/// mesh is centred on its bounding box and scaled so its largest axis
/// spans [−1, 1], as WORKLOADS.md defines; face normals come from the
/// quantised positions. Camera, pose, culling, light, clears and the
/// grey output are WORKLOADS.md's.
#[derive(Debug)]
pub struct Workload<S> {
    positions: [Vec3<S>; BUNNY_VERTS],
    normals: [Vec3<S>; BUNNY_VERTS],
    pipeline: Pipeline<S>,
    camera: Camera<S>,
    ramp: [Color; 256],
}

/// The workload's grey: `v = floor(255·I)`, RGB565 `(v>>3, v>>2, v>>3)`.
pub fn grey565(v: u8) -> Color {
    Rgb565::new(v >> 3, v >> 2, v >> 3)
}

impl<S: Scalar> Workload<S> {
    /// Sets up W1/W2 (`None` only if the pipeline cannot be built).
    pub fn new() -> Option<Self> {
        let mut lo = [i16::MAX; 3];
        let mut hi = [i16::MIN; 3];
        for p in &BUNNY_POSITIONS {
            for a in 0..3 {
                lo[a] = lo[a].min(p[a]);
                hi[a] = hi[a].max(p[a]);
            }
        }
        // Centre and half-extent in quantisation steps (exact in f32).
        let c: [f32; 3] = core::array::from_fn(|a| (lo[a] as f32 + hi[a] as f32) * 0.5);
        let half = (0..3)
            .map(|a| (hi[a] as f32 - lo[a] as f32) * 0.5)
            .fold(0.0, f32::max);
        let _ = BUNNY_SCALE; // the scale cancels in the normalisation
        let positions = core::array::from_fn(|k| {
            let p = BUNNY_POSITIONS[k];
            Vec3::new(
                S::from_f32((p[0] as f32 - c[0]) / half),
                S::from_f32((p[1] as f32 - c[1]) / half),
                S::from_f32((p[2] as f32 - c[2]) / half),
            )
        });
        let unit = 1.0 / 32767.0;
        let normals = core::array::from_fn(|k| {
            let n = BUNNY_NORMALS[k];
            Vec3::new(
                S::from_f32(n[0] as f32 * unit),
                S::from_f32(n[1] as f32 * unit),
                S::from_f32(n[2] as f32 * unit),
            )
        });
        let projection = Projection::perspective(S::from_i32(200), WIDTH, HEIGHT);
        let pipeline = Pipeline::new(
            projection,
            WIDTH,
            HEIGHT,
            S::from_f32(0.5),
            S::from_i32(10),
            S::from_i32(16),
        )
        .ok()?
        .with_cull(Cull::Back);
        Some(Self {
            positions,
            normals,
            pipeline,
            camera: Camera::from_angles(Vec3::ZERO, Euler::ZERO),
            ramp: core::array::from_fn(|i| grey565(i as u8)),
        })
    }

    /// Renders frame `k` of [`WORKLOAD_TURN`] of W1 (`gouraud == false`) or
    /// W2 into whole-frame buffers (cleared first), with `flat`/`lit` as
    /// per-vertex scratch. Returns the triangles drawn.
    #[allow(clippy::too_many_arguments)]
    pub fn frame(
        &self,
        gouraud: bool,
        k: u32,
        color: &mut [Color],
        depth: &mut [u16],
        flat: &mut [Vertex<S, ()>; BUNNY_VERTS],
        lit: &mut [Vertex<S, Intensity<S>>; BUNNY_VERTS],
        proj0: &mut [MeshVertex<0>; BUNNY_VERTS],
        proj1: &mut [MeshVertex<1>; BUNNY_VERTS],
    ) -> u32 {
        let (w, h) = (WIDTH, HEIGHT);
        let Ok(mut fb) = Framebuffer::new(&mut color[..FRAME_PIXELS], w, h, w as usize) else {
            return 0;
        };
        let Ok(mut z) = DepthBuffer::new(&mut depth[..FRAME_PIXELS], w, h, w as usize, 0) else {
            return 0;
        };
        fb.clear(grey565(0));
        z.clear();
        let yaw = core::f32::consts::TAU * k as f32 / WORKLOAD_TURN as f32;
        let pose = Pose::new(
            Vec3::new(S::ZERO, S::ZERO, S::from_f32(-2.6)),
            Euler::new(S::ZERO, S::ZERO, S::from_f32(yaw)),
        );
        let m = self.camera.object_to_view(&pose);
        // L = (1,1,1)/√3 in eye space is (1,−1,−1)/√3 in view space; dot
        // products are taken in object space with L_obj = Rᵀ·L_view.
        let k3 = S::from_f32(0.577_350_26);
        let l = m.matrix.transpose().mul_vec3(Vec3::new(k3, -k3, -k3));
        let (ambient, diffuse) = (S::from_f32(0.2), S::from_f32(0.8));
        let shade = |n: Vec3<S>| ambient + diffuse * n.dot(l).max_of(S::ZERO);
        let pipe = &self.pipeline;
        let mut drawn = 0;
        if gouraud {
            for ((v, &p), &n) in lit.iter_mut().zip(&self.positions).zip(&self.normals) {
                *v = Vertex::new(m.transform_point3(p), Intensity(shade(n)));
            }
            pipe.project_vertices(&lit[..], &mut proj1[..]);
            let sh = Gouraud::new(&self.ramp);
            for t in &BUNNY_TRIANGLES {
                let t = t.map(u32::from);
                if let Ok(Some(tri)) = pipe.mesh_triangle(&lit[..], &proj1[..], t) {
                    fill_polygon(&mut fb, &mut z, &sh, tri.as_slice());
                    drawn += 1;
                }
            }
        } else {
            for (v, &p) in flat.iter_mut().zip(&self.positions) {
                *v = Vertex::new(m.transform_point3(p), ());
            }
            pipe.project_vertices(&flat[..], &mut proj0[..]);
            for t in &BUNNY_TRIANGLES {
                let t = t.map(u32::from);
                if let Ok(Some(tri)) = pipe.mesh_triangle(&flat[..], &proj0[..], t) {
                    let n = self.face_normal(t);
                    let sh = Flat(grey565(scene::quantise_intensity(shade(n))));
                    fill_polygon(&mut fb, &mut z, &sh, tri.as_slice());
                    drawn += 1;
                }
            }
        }
        drawn
    }

    /// The unit face normal of triangle `t` (object space).
    fn face_normal(&self, t: [u32; 3]) -> Vec3<S> {
        let [a, b, c] = t.map(|i| self.positions[i as usize]);
        (b - a).cross(c - a).try_normalize().unwrap_or(Vec3::ZERO)
    }
}
