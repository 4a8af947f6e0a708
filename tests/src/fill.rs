//! Fill-rate workloads: one large polygon filled per frame with each span
//! shader, to measure the per-pixel cost apart from set-up.
//!
//! The polygon is a quad on a plane tilted away from the eye (view depth
//! 1 at the bottom of the screen to 4 at the top), projected through the
//! pipeline once at set-up so that it covers the whole 320×240 viewport:
//! 76 800 pixels per frame, with strong perspective (the texture is
//! foreshortened 4:1). Depth modes shift every vertex key one unit nearer
//! each frame, so every pixel passes the less-than test every frame
//! without clearing the depth buffer (the clear would swamp the figure).

use crate::workload::{HEIGHT, WIDTH};
use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
use sightline::camera::Projection;
use sightline::math::Vec3;
use sightline::pipeline::{Intensity, Pipeline, Uv, UvPerspective, Varyings, Vertex};
use sightline::raster::{
    AffineTexture, DepthBuffer, Flat, Gouraud, NoDepth, PerspectiveTexture, ScalableColor,
    ScreenVertex, fill_polygon,
};
use sightline::target::Framebuffer;
use sightline::texture::{RepeatPow2, Texture};

/// Which shader fills the polygon.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FillMode {
    /// `Flat`, no depth buffer.
    Flat,
    /// `Flat` with the u16 depth buffer.
    FlatDepth,
    /// `Gouraud` with the depth buffer.
    GouraudDepth,
    /// `AffineTexture` (64×64, power-of-two repeat), no depth.
    Affine,
    /// `PerspectiveTexture<_, _, 1>`: exact mode, no depth.
    Perspective,
    /// `PerspectiveTexture<_, _, 16>`: divisions every 16 pixels, no depth.
    Perspective16,
}

impl FillMode {
    /// All modes, in table order.
    pub const ALL: [Self; 6] = [
        Self::Flat,
        Self::FlatDepth,
        Self::GouraudDepth,
        Self::Affine,
        Self::Perspective,
        Self::Perspective16,
    ];

    /// The command-line name.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Flat => "flat",
            Self::FlatDepth => "flat-depth",
            Self::GouraudDepth => "gouraud-depth",
            Self::Affine => "affine",
            Self::Perspective => "persp",
            Self::Perspective16 => "persp16",
        }
    }

    /// The mode called `name`.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|m| m.name() == name)
    }
}

/// Texture side (texels).
pub const TEX: u16 = 64;

/// Set-up for the fill-rate frames: the projected quad in every vertex
/// format, a texture, a ramp and the buffers.
#[derive(Debug)]
pub struct FillBench {
    mode: FillMode,
    flat: Vec<ScreenVertex<0>>,
    lit: Vec<ScreenVertex<1>>,
    uv: Vec<ScreenVertex<2>>,
    uvp: Vec<ScreenVertex<3>>,
    texels: Vec<Rgb565>,
    ramp: [Rgb565; 256],
    /// RGB565 pixels.
    pub color: Vec<Rgb565>,
    depth: Vec<u16>,
    frame: u32,
}

fn project<A: Varyings<f32, K>, const K: usize>(
    pipe: &Pipeline<f32>,
    attr: impl Fn(usize) -> A,
) -> Vec<ScreenVertex<K>> {
    // Bottom edge at depth 1, top edge at depth 4, both exactly the
    // viewport's width: x = ±0.8·z, y = ±0.6·z at focus 200.
    let corners = [
        (-0.8, 0.6, 1.0),
        (0.8, 0.6, 1.0),
        (3.2, -2.4, 4.0),
        (-3.2, -2.4, 4.0),
    ];
    let poly: Vec<Vertex<f32, A>> = corners
        .iter()
        .enumerate()
        .map(|(i, &(x, y, z))| Vertex::new(Vec3::new(x, y, z), attr(i)))
        .collect();
    pipe.project_polygon(&poly)
        .ok()
        .flatten()
        .map(|p| p.to_vec())
        .unwrap_or_default()
}

/// The polygon with every depth key `f` units nearer (a copy of at most
/// a few vertices per frame).
fn nearer<const K: usize>(p: &[ScreenVertex<K>], f: u32) -> Vec<ScreenVertex<K>> {
    p.iter()
        .map(|&s| ScreenVertex {
            z: s.z.saturating_sub(f as u16),
            ..s
        })
        .collect()
}

impl FillBench {
    /// Sets up `mode`.
    ///
    /// # Panics
    /// Never for the constants used (valid pipeline and texture shapes).
    #[must_use]
    pub fn new(mode: FillMode) -> Self {
        let pipe = Pipeline::new(
            Projection::perspective(200.0f32, WIDTH, HEIGHT),
            WIDTH,
            HEIGHT,
            0.5,
            10.0,
            16.0,
        )
        .expect("valid pipeline");
        // Texture coordinates: 4 repeats across and along the quad.
        let uv = |i: usize| {
            let t = 4.0 * TEX as f32;
            [(0.0, 0.0), (t, 0.0), (t, t), (0.0, t)][i]
        };
        let n = WIDTH as usize * HEIGHT as usize;
        let texels = (0..TEX as usize * TEX as usize)
            .map(|i| {
                let (x, y) = (i % TEX as usize, i / TEX as usize);
                Rgb565::new(
                    (x >> 1) as u8,
                    (y as u8) ^ (x as u8),
                    ((x ^ y) & 31) as u8 | 1,
                )
            })
            .collect();
        Self {
            mode,
            flat: project(&pipe, |_| ()),
            // Affine in screen space (the quad is the screen rectangle), so
            // the plane through any three corners matches the fourth.
            lit: project(&pipe, |i| Intensity([0.2, 0.8, 1.0, 0.4][i])),
            uv: project(&pipe, |i| {
                let (u, v) = uv(i);
                Uv { u, v }
            }),
            uvp: project(&pipe, |i| {
                let (u, v) = uv(i);
                UvPerspective { u, v }
            }),
            texels,
            ramp: Rgb565::GREEN.ramp(),
            color: vec![Rgb565::BLACK; n],
            depth: vec![u16::MAX; n],
            frame: 0,
        }
    }

    /// Fills the quad once; returns the number of pixels it covers.
    ///
    /// # Panics
    /// Never for the buffers built in [`Self::new`].
    pub fn frame(&mut self) -> u32 {
        let (w, h) = (WIDTH, HEIGHT);
        let mut fb = Framebuffer::new(&mut self.color, w, h, w as usize).expect("frame shape");
        let mut depth = DepthBuffer::new(&mut self.depth, w, h, w as usize, 0).expect("shape");
        // One key unit nearer every frame: every pixel passes (see the
        // module docs); the keys start above 30 000, far from 0.
        self.frame = (self.frame + 1) % 30_000;
        let tex = Texture::new(&self.texels, TEX, TEX, TEX as usize).expect("texture shape");
        match self.mode {
            FillMode::Flat => {
                fill_polygon(&mut fb, &mut NoDepth, &Flat(Rgb565::CYAN), &self.flat);
            }
            FillMode::FlatDepth => {
                let p = nearer(&self.flat, self.frame);
                fill_polygon(&mut fb, &mut depth, &Flat(Rgb565::CYAN), &p);
            }
            FillMode::GouraudDepth => {
                let p = nearer(&self.lit, self.frame);
                fill_polygon(&mut fb, &mut depth, &Gouraud::new(&self.ramp), &p);
            }
            FillMode::Affine => {
                let sh = AffineTexture::<_, RepeatPow2>::new(tex).expect("power of two");
                fill_polygon(&mut fb, &mut NoDepth, &sh, &self.uv);
            }
            FillMode::Perspective => {
                let sh = PerspectiveTexture::<_, RepeatPow2, 1>::new(tex).expect("power of two");
                fill_polygon(&mut fb, &mut NoDepth, &sh, &self.uvp);
            }
            FillMode::Perspective16 => {
                let sh = PerspectiveTexture::<_, RepeatPow2, 16>::new(tex).expect("power of two");
                fill_polygon(&mut fb, &mut NoDepth, &sh, &self.uvp);
            }
        }
        WIDTH as u32 * HEIGHT as u32
    }

    /// Pixels of the last frame that differ from black (for tests).
    #[must_use]
    pub fn covered(&self) -> usize {
        self.color.iter().filter(|&&c| c != Rgb565::BLACK).count()
    }
}
