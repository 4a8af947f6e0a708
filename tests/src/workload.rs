//! Benchmark workloads W1 (flat) and W2 (Gouraud): the Stanford bunny
//! rendered at 320×240 RGB565 with a u16 depth buffer, exactly as defined
//! in `docs/raster-workloads.md` (the peers' definitions), through
//! sightline's own camera, pose, pipeline and raster API.
//!
//! The workload's eye space is right-handed with y up, looking down −z.
//! sightline's view space is (x, −y, −z) of that, which is exactly what
//! [`Camera::from_angles`] at the origin with zero angles produces, so the
//! frame-k transform `T(0, 0, −2.6)·Ry(2πk/N)` is the object pose
//! `Pose { origin: (0, 0, −2.6), yaw: 2πk/N }` seen by that camera.

use crate::obj::{self, Mesh};
use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
use sightline::camera::{Camera, Projection};
use sightline::math::Vec3;
use sightline::pipeline::MeshVertex;
use sightline::raster::{DepthBuffer, ScalableColor};
use sightline::scalar::Scalar;
use sightline::scene::{Light, Material, PreparedMesh, PreparedObject, Renderer, View};
use sightline::target::Framebuffer;
use sightline::transform::{Euler, Pose};

/// Viewport width in pixels.
pub const WIDTH: u16 = 320;
/// Viewport height in pixels.
pub const HEIGHT: u16 = 240;
/// Focal length in pixels.
pub const FOCUS: f64 = 200.0;
/// Bounding-box center of the bunny, subtracted before scaling.
pub const CENTER: [f64; 3] = [-0.0048125, 4.8257995, 0.040403];
/// Divisor that makes the bunny's largest axis span exactly [−1, 1].
pub const SCALE: f64 = 4.9536625;
/// Distance of the model from the eye.
pub const DISTANCE: f64 = 2.6;
/// The bunny OBJ, embedded so the workload needs no data path at run time.
pub const BUNNY_OBJ: &str = include_str!("../data/bunny.obj");

/// Which workload.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shading {
    /// W1: one color per triangle from the face normal.
    Flat,
    /// W2: per-vertex intensities from vertex normals, interpolated.
    Gouraud,
}

/// The workload's gray for `v = floor(255·I)` as sightline's material
/// model makes it: white scaled by `v/255` per channel, rounded down
/// (WORKLOADS.md's `(v>>3, v>>2, v>>3)` differs by at most one step per
/// channel and costs the same).
#[must_use]
pub fn gray565(v: u8) -> Rgb565 {
    Rgb565::WHITE.scale(v)
}

/// The bunny, normalized, with face and vertex normals (computed in f64
/// and converted once).
#[derive(Clone, Debug)]
pub struct Model<S> {
    /// Normalized positions.
    pub positions: Vec<Vec3<S>>,
    /// Triangles (CCW outward).
    pub triangles: Vec<[u16; 3]>,
    /// Unit face normals.
    pub face_normals: Vec<Vec3<S>>,
    /// Unit vertex normals (area-weighted).
    pub vertex_normals: Vec<Vec3<S>>,
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn normalize(a: [f64; 3]) -> [f64; 3] {
    let l = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    if l > 0.0 {
        [a[0] / l, a[1] / l, a[2] / l]
    } else {
        [0.0; 3]
    }
}

impl<S: Scalar> Model<S> {
    /// Normalizes `mesh` as W1/W2 define and computes the normals.
    #[must_use]
    pub fn from_mesh(mesh: &Mesh) -> Self {
        let p: Vec<[f64; 3]> = mesh
            .positions
            .iter()
            .map(|&q| {
                let d = sub(q, CENTER);
                [d[0] / SCALE, d[1] / SCALE, d[2] / SCALE]
            })
            .collect();
        let mut vn = vec![[0.0f64; 3]; p.len()];
        let mut face_normals = Vec::with_capacity(mesh.triangles.len());
        for t in &mesh.triangles {
            let [a, b, c] = t.map(|i| p[i as usize]);
            // |cross| is twice the area: summing it weights by area.
            let n = cross(sub(b, a), sub(c, a));
            face_normals.push(v3(normalize(n)));
            for &i in t {
                let s = &mut vn[i as usize];
                for k in 0..3 {
                    s[k] += n[k];
                }
            }
        }
        Self {
            positions: p.into_iter().map(v3).collect(),
            triangles: mesh
                .triangles
                .iter()
                .map(|t| t.map(|k| u16::try_from(k).expect("fewer than 65536 vertices")))
                .collect(),
            face_normals,
            vertex_normals: vn.into_iter().map(|n| v3(normalize(n))).collect(),
        }
    }

    /// The bunny from the embedded OBJ.
    ///
    /// # Panics
    /// If the embedded file does not parse (a build error, tested).
    #[must_use]
    pub fn bunny() -> Self {
        Self::from_mesh(&obj::parse(BUNNY_OBJ).expect("embedded bunny.obj parses"))
    }
}

fn v3<S: Scalar>(a: [f64; 3]) -> Vec3<S> {
    Vec3::new(S::from_f64(a[0]), S::from_f64(a[1]), S::from_f64(a[2]))
}

/// Everything a frame needs besides the buffers: the prepared bunny, the
/// renderer (camera, projection, clip volume, light) and the per-frame
/// scratch, set up once; frames go through the public prepared-scene API
/// ([`Renderer::project`], [`sightline::scene::Frame::draw`]) as every
/// other caller's do.
#[derive(Debug)]
pub struct Workload<'m, S> {
    renderer: Renderer<S>,
    object: [PreparedObject<'m, S>; 1],
    scratch: Vec<MeshVertex<1>>,
}

/// The color and depth buffers of one 320×240 frame.
#[derive(Clone, Debug)]
pub struct Frame {
    /// RGB565 pixels, row-major.
    pub color: Vec<Rgb565>,
    /// Depth keys, row-major.
    pub depth: Vec<u16>,
}

impl Default for Frame {
    fn default() -> Self {
        let n = WIDTH as usize * HEIGHT as usize;
        Self {
            color: vec![gray565(0); n],
            depth: vec![u16::MAX; n],
        }
    }
}

impl<'m, S: Scalar> Workload<'m, S> {
    /// Sets up W1 or W2 for `model`.
    ///
    /// # Panics
    /// Never for the constants used here (the pipeline parameters are
    /// valid) and a model from [`Model::from_mesh`].
    #[must_use]
    pub fn new(model: &'m Model<S>, shading: Shading) -> Self {
        let (faces, verts, material): (&[Vec3<S>], &[Vec3<S>], _) = match shading {
            Shading::Flat => (&model.face_normals, &[], Material::Flat(Rgb565::WHITE)),
            Shading::Gouraud => (&[], &model.vertex_normals, Material::Gouraud(Rgb565::WHITE)),
        };
        let mesh = PreparedMesh::new(&model.positions, &model.triangles, faces, verts, &[], true)
            .expect("the model is a valid closed mesh");
        let object = PreparedObject::new(mesh, Self::pose(0, 1), material).expect("a valid object");
        let s = S::from_f64;
        let view = View {
            // At the origin, zero angles: looks along world −Z with +Y up,
            // i.e. the workload's eye space, flipped to view axes.
            camera: Camera::from_angles(Vec3::ZERO, Euler::ZERO),
            projection: Projection::perspective(s(FOCUS), WIDTH, HEIGHT),
            width: WIDTH,
            height: HEIGHT,
        };
        // L = (1, 1, 1)/√3 towards the light in eye space, which is world
        // space for this camera.
        let light = Light {
            direction: [1.0, 1.0, 1.0],
            ambient: 0.2,
            diffuse: 0.8,
        };
        // Near 0.5 and far 10 as glFrustum(−0.4, 0.4, −0.3, 0.3, 0.5, 10).
        let renderer =
            Renderer::from_view(view, s(0.5), s(10.0), &light, gray565(0)).expect("valid pipeline");
        Self {
            renderer,
            object: [object],
            scratch: vec![MeshVertex::default(); model.positions.len()],
        }
    }

    /// The object pose of frame `k` of `n`: yaw 2πk/n at (0, 0, −2.6).
    #[must_use]
    pub fn pose(k: u32, n: u32) -> Pose<S> {
        let yaw = 2.0 * core::f64::consts::PI * k as f64 / n.max(1) as f64;
        Pose::new(
            Vec3::new(S::ZERO, S::ZERO, S::from_f64(-DISTANCE)),
            Euler::new(S::ZERO, S::ZERO, S::from_f64(yaw)),
        )
    }

    /// Renders frame `k` of `n` into `frame`, clearing it first (color by
    /// the draw, depth here). Returns the number of triangles drawn (not
    /// culled, not empty).
    pub fn render(&mut self, k: u32, n: u32, frame: &mut Frame) -> u32 {
        let (w, h) = (WIDTH, HEIGHT);
        let Ok(mut fb) = Framebuffer::new(&mut frame.color, w, h, w as usize) else {
            return 0;
        };
        let Ok(mut depth) = DepthBuffer::new(&mut frame.depth, w, h, w as usize, 0) else {
            return 0;
        };
        depth.clear();
        self.object[0].pose = Self::pose(k, n);
        // Without the clipper, as the MCU workload draws it
        // (tests/mcu/src/frames.rs): the bunny stays in the view volume.
        match self.renderer.project(&mut self.object, &mut self.scratch) {
            Ok(f) => f.draw_unclipped(&mut fb, &mut depth).map_or(0, |s| s.drawn),
            Err(_) => 0,
        }
    }
}

/// `floor(255·I)` for I in [0, 1].
#[must_use]
pub fn intensity_byte<S: Scalar>(i: S) -> u8 {
    (i.to_f32() * 255.0).clamp(0.0, 255.0) as u8
}

/// Pixels covered in a rendered frame and their bounding box.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Coverage {
    /// Non-background pixels (every lit pixel has v ≥ 51, so none is 0).
    pub pixels: u32,
    /// `(x_min, y_min, x_max, y_max)`, inclusive, or `None` if empty.
    pub bbox: Option<(u16, u16, u16, u16)>,
}

impl Frame {
    /// The covered pixels of the last rendered frame.
    #[must_use]
    pub fn coverage(&self) -> Coverage {
        let bg = gray565(0);
        let mut pixels = 0;
        let mut bbox: Option<(u16, u16, u16, u16)> = None;
        for (i, &c) in self.color.iter().enumerate() {
            if c != bg {
                pixels += 1;
                let (x, y) = ((i % WIDTH as usize) as u16, (i / WIDTH as usize) as u16);
                bbox = Some(match bbox {
                    None => (x, y, x, y),
                    Some((a, b, c, d)) => (a.min(x), b.min(y), c.max(x), d.max(y)),
                });
            }
        }
        Coverage { pixels, bbox }
    }
}
