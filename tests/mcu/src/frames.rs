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
//!   and the full or half width, filled [`FILL_REPEAT`] times;
//!   [`fill_hash`] hashes the full-width frame.
//! - [`Workload`]: W1/W2 (`/work/shared/WORKLOADS.md`) on the built-in
//!   quantized bunny.

use core::hint::black_box;
use embedded_graphics::pixelcolor::{IntoStorage, Rgb565, RgbColor};
use sightline::camera::{Camera, Projection};
use sightline::math::Vec3;
use sightline::pipeline::{
    Intensity, MeshVertex, Pipeline, ScreenPolygon, Uv, UvPerspective, Varyings, Vertex,
};
use sightline::raster::{
    AffineTexture, DepthBuffer, Flat, Gouraud, NoDepth, PerspectiveTexture, ScalableColor,
    ScreenVertex, fill_polygon,
};
use sightline::scalar::{I16F16, Scalar};
use sightline::scene::builtin::{self, BUNNY_NORMALS, BUNNY_POSITIONS, BUNNY_TRIANGLES};
use sightline::scene::{
    Color, Light, Material, PreparedMesh, PreparedObject, RayScene, Renderer, Scene, SceneError,
    Storage, View,
};
use sightline::target::{Band, Framebuffer};
use sightline::texture::{RepeatPow2, Texture};
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

/// The largest [`Scene::storage`] of the scenes in [`SCENES`], field by
/// field: what [`render_scene`] needs for any of them.
pub const STORAGE: Storage = Storage::for_any(&builtin::ALL);

/// Renders built-in scene `name` in scalar `S` at [`WIDTH`]×[`HEIGHT`]:
/// prepared once into `vec3s` (at least [`STORAGE`]`.vec3s`), projected
/// once into `scratch` (at least [`STORAGE`]`.vertices`), then drawn band
/// by band in `color` and `depth` (each at least [`BAND_PIXELS`] long),
/// calling `row(y, pixels)` for every finished row top to bottom. Returns
/// FNV-1a over all pixels in row order. `spheres` is drawn by the ray path
/// (spheres are ray-only).
///
/// # Errors
/// An unknown name gives [`SceneError::BadProjection`]; otherwise the
/// scene's own error (the built-in scenes have none).
pub fn render_scene<S: Scalar>(
    name: &str,
    vec3s: &mut [Vec3<S>],
    scratch: &mut [MeshVertex<1>],
    color: &mut [Color],
    depth: &mut [u16],
    mut row: impl FnMut(u16, &[Color]),
) -> Result<u64, SceneError> {
    let mut h = Fnv::new();
    scene_frames::<S>(name, 1, vec3s, scratch, color, depth, |y, px| {
        h.pixels(px);
        row(y, px);
    })?;
    Ok(h.0)
}

/// Renders built-in scene `name` `frames` times through the public scene
/// API, as [`render_scene`] does once: prepared and set up once, then per
/// frame projected once and drawn band by band, `row(y, pixels)` called
/// for every finished row. The `sf` command measures instructions per
/// frame with it (N frames minus 0 frames).
pub fn scene_frames<S: Scalar>(
    name: &str,
    frames: u32,
    vec3s: &mut [Vec3<S>],
    scratch: &mut [MeshVertex<1>],
    color: &mut [Color],
    depth: &mut [u16],
    mut row: impl FnMut(u16, &[Color]),
) -> Result<(), SceneError> {
    let scene: &Scene<'_> = builtin::by_name(name).ok_or(SceneError::BadProjection)?;
    let ray = if name == "spheres" {
        let view = scene.view::<S>(WIDTH, HEIGHT)?;
        Some(RayScene::new(scene, &view)?)
    } else {
        None
    };
    let mut objects = [PreparedObject::EMPTY; STORAGE.objects];
    let objects = scene.prepare(vec3s, &mut objects)?;
    let renderer = Renderer::<S>::new(scene, WIDTH, HEIGHT)?;
    let (color, depth) = (&mut color[..BAND_PIXELS], &mut depth[..BAND_PIXELS]);
    let w = WIDTH as usize;
    for _ in 0..frames {
        let frame = renderer.project(&mut *objects, &mut *scratch)?;
        for y0 in (0..HEIGHT).step_by(BAND_ROWS as usize) {
            let rows = BAND_ROWS.min(HEIGHT - y0);
            let n = w * rows as usize;
            let bad = |_| SceneError::BadProjection;
            let mut band = Band::new(&mut color[..n], WIDTH, rows, w, y0 as i32).map_err(bad)?;
            match &ray {
                Some(r) => r.render(&mut band),
                None => {
                    let mut z = DepthBuffer::new(&mut depth[..n], WIDTH, rows, w, y0 as i32)
                        .map_err(bad)?;
                    z.clear();
                    frame.draw(&mut band, &mut z);
                }
            }
            for r in 0..rows as usize {
                row(y0 + r as u16, &color[r * w..(r + 1) * w]);
            }
        }
    }
    Ok(())
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
/// pixels written by the last fill (counted in the color buffer against
/// the cleared color), or `None` for an unknown mode.
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
    // Counted without a branch, so that the count costs the same however
    // many pixels were drawn and cancels in the full-minus-half difference
    // (the per-pixel figures are the shader's alone): `x + 0xFFFF` carries
    // into bit 16 exactly when the pixel is not black (0).
    Some(
        black_box(&*color)
            .iter()
            .map(|&c| (u32::from(c.into_storage()) + 0xFFFF) >> 16)
            .sum(),
    )
}

/// The hash of the whole frame [`fill`] leaves for `mode` at full width:
/// each of the quad's 240 spans is 320 pixels long, so they all take
/// the long-span routes (on ARMv6-M the split depth loops and
/// Gouraud's run loop) that the scenes' shorter spans seldom reach. Every
/// depth fill passes every pixel (see [`fill`]), so the frame is the last
/// fill's colors. `None` for an unknown mode.
pub fn fill_hash(mode: &str, color: &mut [Color], depth: &mut [u16]) -> Option<u64> {
    fill(mode, false, color, depth)?;
    let mut h = Fnv::new();
    h.pixels(color.get(..FRAME_PIXELS)?);
    Some(h.0)
}

// ---------------------------------------------------------------- W1 / W2

/// Vertices of the built-in bunny.
pub const BUNNY_VERTS: usize = BUNNY_POSITIONS.len();

/// Frames per turn in W1/W2 (frame `k` of it yaws the model by 2πk/N).
pub const WORKLOAD_TURN: u32 = 200;
/// Frame step of the instruction-count variant (every 10th frame: 20
/// frames per turn).
pub const WORKLOAD_STEP: u32 = 10;

/// `Vec3` storage [`Workload::new`] needs: positions and normals.
pub const WORKLOAD_VEC3S: usize = BUNNY_VERTS + BUNNY_TRIANGLES.len();

/// W1/W2 on the built-in quantized bunny (`scene::builtin::BUNNY_*`, the
/// same 1839 vertices and 3674 triangles as `data/bunny.obj`, stored as
/// i16 with 1/2048 unit steps, and its stored unit vertex normals), drawn
/// through the public prepared-scene API ([`Renderer`], [`PreparedObject`])
/// as every other caller draws: the mesh is centered on its bounding box
/// and scaled so its largest axis spans [−1, 1], as WORKLOADS.md defines;
/// face normals come from the quantized positions. Camera, pose, culling
/// (the bunny is closed), light and clears are WORKLOADS.md's; the gray is
/// the material model's white scaled by `⌊255·I⌋/255`.
#[derive(Debug)]
pub struct Workload<'a, S> {
    renderer: Renderer<S>,
    object: [PreparedObject<'a, S>; 1],
}

/// The workload's gray: `v = floor(255·I)`, RGB565 `(v>>3, v>>2, v>>3)`.
pub fn gray565(v: u8) -> Color {
    Rgb565::new(v >> 3, v >> 2, v >> 3)
}

impl<'a, S: Scalar> Workload<'a, S> {
    /// Prepares W1 (`gouraud == false`) or W2 into `storage` (at least
    /// [`WORKLOAD_VEC3S`] long); `None` if the pipeline cannot be built.
    pub fn new(gouraud: bool, storage: &'a mut [Vec3<S>]) -> Option<Self> {
        let mut lo = [i16::MAX; 3];
        let mut hi = [i16::MIN; 3];
        for p in &BUNNY_POSITIONS {
            for a in 0..3 {
                lo[a] = lo[a].min(p[a]);
                hi[a] = hi[a].max(p[a]);
            }
        }
        // Center and half-extent in quantization steps (exact in f32).
        let c: [f32; 3] = core::array::from_fn(|a| (lo[a] as f32 + hi[a] as f32) * 0.5);
        let half = (0..3)
            .map(|a| (hi[a] as f32 - lo[a] as f32) * 0.5)
            .fold(0.0, f32::max);
        let (positions, normals) = storage.get_mut(..WORKLOAD_VEC3S)?.split_at_mut(BUNNY_VERTS);
        for (out, p) in positions.iter_mut().zip(&BUNNY_POSITIONS) {
            *out = Vec3::new(
                S::from_f32((p[0] as f32 - c[0]) / half),
                S::from_f32((p[1] as f32 - c[1]) / half),
                S::from_f32((p[2] as f32 - c[2]) / half),
            );
        }
        let (faces, verts): (&[Vec3<S>], &[Vec3<S>]) = if gouraud {
            let unit = 1.0 / 32767.0;
            let out = &mut normals[..BUNNY_VERTS];
            for (o, n) in out.iter_mut().zip(&BUNNY_NORMALS) {
                *o = Vec3::new(
                    S::from_f32(n[0] as f32 * unit),
                    S::from_f32(n[1] as f32 * unit),
                    S::from_f32(n[2] as f32 * unit),
                );
            }
            (&[], out)
        } else {
            builtin::BUNNY_MESH.face_normals_into(normals);
            (normals, &[])
        };
        let mesh = PreparedMesh::new(positions, &BUNNY_TRIANGLES, faces, verts, &[], true).ok()?;
        let white = Rgb565::WHITE;
        let material = if gouraud {
            Material::Gouraud(white)
        } else {
            Material::Flat(white)
        };
        let object = PreparedObject::new(mesh, Pose::default(), material).ok()?;
        let view = View {
            camera: Camera::from_angles(Vec3::ZERO, Euler::ZERO),
            projection: Projection::perspective(S::from_i32(200), WIDTH, HEIGHT),
            width: WIDTH,
            height: HEIGHT,
        };
        // L = (1,1,1)/√3 towards the light in the workload's eye space,
        // which is world space for this camera (at the origin, zero angles).
        let light = Light {
            direction: [1.0, 1.0, 1.0],
            ambient: 0.2,
            diffuse: 0.8,
        };
        // Near 0.5 and far 10 as glFrustum(−0.4, 0.4, −0.3, 0.3, 0.5, 10).
        let renderer =
            Renderer::from_view(view, S::from_f32(0.5), S::from_i32(10), &light, gray565(0))
                .ok()?;
        Some(Self {
            renderer,
            object: [object],
        })
    }

    /// Renders frame `k` of [`WORKLOAD_TURN`] into whole-frame buffers
    /// (color cleared to the background by the draw, depth cleared here),
    /// with `scratch` (at least [`BUNNY_VERTS`]) for the projected
    /// vertices. Returns the triangles drawn.
    pub fn frame(
        &mut self,
        k: u32,
        color: &mut [Color],
        depth: &mut [u16],
        scratch: &mut [MeshVertex<1>],
    ) -> u32 {
        let (w, h) = (WIDTH, HEIGHT);
        let Ok(mut fb) = Framebuffer::new(&mut color[..FRAME_PIXELS], w, h, w as usize) else {
            return 0;
        };
        let Ok(mut z) = DepthBuffer::new(&mut depth[..FRAME_PIXELS], w, h, w as usize, 0) else {
            return 0;
        };
        z.clear();
        let yaw = core::f32::consts::TAU * k as f32 / WORKLOAD_TURN as f32;
        self.object[0].pose = Pose::new(
            Vec3::new(S::ZERO, S::ZERO, S::from_f32(-2.6)),
            Euler::new(S::ZERO, S::ZERO, S::from_f32(yaw)),
        );
        // The bunny never leaves the view volume (../shared/WORKLOADS.md:
        // the near plane is never crossed, and it stays on screen), so the
        // frame is drawn without the clipper, as a firmware whose scene
        // stays in view draws it (`Frame::draw_unclipped`: the same pixels
        // as `Frame::draw`, which core's `bunny_draws_the_same_unclipped`
        // checks).
        match self.renderer.project(&mut self.object, scratch) {
            Ok(frame) => frame.draw_unclipped(&mut fb, &mut z).map_or(0, |s| s.drawn),
            Err(_) => 0,
        }
    }
}
