//! The world→screen pipeline after the object→view transform: clip in
//! view space, project to 28.4 sub-pixel screen coordinates, scan-convert.
//!
//! ```text
//! view-space polygon ─► Frustum::clip ─► Pipeline::project ─► raster::fill_polygon ─► Target
//!   Vertex<S, A>        (Sutherland–       (28.4 x, y; depth       (spans)
//!                        Hodgman)            key; varyings)
//! ```
//!
//! The vertex format `A` is chosen at compile time (see [`vertex`]); the
//! scalar `S` is any [`Scalar`], so the same code runs in `f32` and
//! I16F16.
//!
//! # Volume
//!
//! [`Pipeline::new`] builds a [`Frustum`] of six planes: near (mandatory,
//! keeps `z > 0` for the perspective divide), far, and four side planes
//! placed `guard` pixels outside the viewport. The side planes keep every
//! projected coordinate within the viewport plus guard band, far inside
//! the scan converter's coordinate limit; the guard band moves the
//! clipper's rounded intersection points off screen, where only the
//! scan converter's exact scissor decides coverage.
//!
//! # Depth keys
//!
//! Keys are 0 at the near plane and 65535 at the far plane, affine in
//! what is linear in screen space: in `1/z` for perspective
//! (`key = (1/near − 1/z) / (1/near − 1/far)`), in `z` for parallel
//! projection.

mod clip;
pub mod mesh;
pub mod vertex;

pub use clip::{
    ClipError, ClippedPolygon, Frustum, MAX_CLIPPED_VERTICES, MAX_INPUT_VERTICES, MAX_PLANES, Plane,
};
pub use mesh::{MeshTriangle, MeshVertex, OUTCODE_UNUSABLE};
pub use vertex::{
    Attributes, Intensity, IntensityUv, Uv, UvPerspective, Varyings, Vertex, VertexXyz, VertexXyzI,
    VertexXyzIUv, VertexXyzUv, VertexXyzUvP,
};

use crate::camera::{Projection, ProjectionKind};
use crate::math::Vec3;
use crate::raster::{
    DepthTest, FillOutcome, SUBPIXEL_BITS, ScreenVertex, SpanShader, fill_polygon,
};
use crate::scalar::Scalar;
use crate::target::Target;
use core::fmt;

/// A clipped, projected polygon ready for
/// [`crate::raster::fill_polygon`]: at most
/// [`MAX_CLIPPED_VERTICES`] vertices.
pub type ScreenPolygon<const VARYINGS: usize> =
    heapless::Vec<ScreenVertex<VARYINGS>, MAX_CLIPPED_VERTICES>;

/// Why a [`Pipeline`] could not be built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum PipelineError {
    /// A parameter is NaN or ±∞, or a plane coefficient overflows.
    NonFinite,
    /// Not `0 < near < far`.
    BadDepthRange,
    /// The focus distance or scale is not positive, or `guard` is negative.
    BadProjection,
}

impl fmt::Display for PipelineError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NonFinite => f.write_str("pipeline parameter is not finite or overflows"),
            Self::BadDepthRange => f.write_str("need 0 < near < far"),
            Self::BadProjection => {
                f.write_str("focus/scale must be positive and the guard band non-negative")
            }
        }
    }
}

impl core::error::Error for PipelineError {}

/// Why a polygon was not drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum DrawError {
    /// Clipping failed.
    Clip(ClipError),
    /// A clipped vertex could not be projected (overflow in the scalar
    /// type, e.g. saturated fixed point).
    Projection,
}

impl fmt::Display for DrawError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Clip(e) => write!(f, "clipping failed: {e}"),
            Self::Projection => f.write_str("a clipped vertex could not be projected"),
        }
    }
}

impl core::error::Error for DrawError {
    fn source(&self) -> Option<&(dyn core::error::Error + 'static)> {
        match self {
            Self::Clip(e) => Some(e),
            Self::Projection => None,
        }
    }
}

/// Which faces [`Pipeline::draw_polygon`] drops.
///
/// A face is *front-facing* when its vertices run counter-clockwise as
/// seen from the eye (the OBJ and glTF convention, right-hand rule about
/// the outward normal). On screen, with y down, that is a negative
/// shoelace area.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Cull {
    /// Draw both sides.
    #[default]
    None,
    /// Drop faces turned away from the eye (closed meshes).
    Back,
    /// Drop faces turned towards the eye.
    Front,
}

/// Projection, clip volume and depth mapping for one viewport.
///
/// # Examples
///
/// A Gouraud-shaded triangle in view space, half behind the near plane,
/// drawn with a depth buffer into a 240×240 Rgb565 frame:
///
/// ```
/// # #[cfg(all(feature = "gouraud", feature = "depth"))] {
/// use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
/// use sightline::camera::Projection;
/// use sightline::math::Vec3;
/// use sightline::pipeline::{Intensity, Pipeline, Vertex};
/// use sightline::raster::{DepthBuffer, Gouraud, ScalableColor};
/// use sightline::target::Framebuffer;
///
/// let mut pixels = [Rgb565::BLACK; 240 * 240];
/// let mut keys = [u16::MAX; 240 * 240];
/// let mut fb = Framebuffer::new(&mut pixels, 240, 240, 240).unwrap();
/// let mut depth = DepthBuffer::new(&mut keys, 240, 240, 240, 0).unwrap();
///
/// let pipe = Pipeline::new(Projection::perspective(200.0f32, 240, 240), 240, 240, 0.1, 100.0, 16.0)
///     .unwrap();
/// let ramp = Rgb565::GREEN.ramp();
/// let v = |x, y, z, i| Vertex::new(Vec3::new(x, y, z), Intensity(i));
/// let tri = [v(-1.0, 0.5, -1.0, 0.0), v(1.0, 0.5, 3.0, 1.0), v(-1.0, -0.5, 3.0, 0.5)];
/// pipe.draw_polygon(&mut fb, &mut depth, &Gouraud::new(&ramp), &tri).unwrap();
/// assert!(fb.as_slice().iter().any(|&p| p != Rgb565::BLACK));
/// # }
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pipeline<S> {
    projection: Projection<S>,
    frustum: Frustum<S>,
    /// Depth key fraction = `(a − depth)·scale` (perspective, depth = 1/z)
    /// or `(depth − a)·scale` (parallel, depth = z).
    depth_a: S,
    depth_scale: S,
    near: S,
    cull: Cull,
    /// The side planes as a 28.4 screen rectangle `[x0, x1] × [y0, y1]`
    /// (viewport plus guard band), for outcodes of projected vertices.
    guard_rect: [i32; 4],
    /// Every coordinate of `guard_rect` lies within ±(2^14 − 1): a
    /// triangle with all three vertices inside the volume then has edge
    /// vectors below 2^15, and its winding is an exact `i32` cross product.
    guard_small: bool,
    /// The far plane, for [`with_far_clip`](Self::with_far_clip).
    #[cfg(feature = "clip-far")]
    far_plane: Plane<S>,
}

impl<S: Scalar> Pipeline<S> {
    /// A pipeline for a `width`×`height` viewport with `projection`,
    /// clipping at `near` and `far` (view-space z) and `guard` pixels
    /// outside the viewport's sides.
    ///
    /// Side-plane normals are divided by the focus distance (or scale) so
    /// that their coefficients stay near 1: fixed point keeps its range
    /// for the coordinates.
    ///
    /// # Errors
    /// See [`PipelineError`].
    pub fn new(
        projection: Projection<S>,
        width: u16,
        height: u16,
        near: S,
        far: S,
        guard: S,
    ) -> Result<Self, PipelineError> {
        let (cx, cy) = (projection.center.x, projection.center.y);
        let f = match projection.kind {
            ProjectionKind::Parallel { scale } => scale,
            ProjectionKind::Perspective { focus } => focus,
        };
        if ![near, far, guard, cx, cy, f].iter().all(|v| v.is_finite()) {
            return Err(PipelineError::NonFinite);
        }
        if !(near > S::ZERO && far > near) {
            return Err(PipelineError::BadDepthRange);
        }
        if !(f > S::ZERO && guard >= S::ZERO) {
            return Err(PipelineError::BadProjection);
        }
        let nf = PipelineError::NonFinite;
        let w = S::from_i32(width as i32);
        let h = S::from_i32(height as i32);
        // Screen bounds with the guard band, relative to the center, in
        // units of f: x_s ≥ −g ⇔ x/z + (cx + g)/f ≥ 0 (perspective) or
        // x + (cx + g)/s ≥ 0 (parallel).
        let left = cx
            .checked_add(guard)
            .and_then(|v| v.checked_div(f))
            .ok_or(nf)?;
        let right = w
            .checked_add(guard)
            .and_then(|v| v.checked_sub(cx))
            .and_then(|v| v.checked_div(f))
            .ok_or(nf)?;
        let top = cy
            .checked_add(guard)
            .and_then(|v| v.checked_div(f))
            .ok_or(nf)?;
        let bottom = h
            .checked_add(guard)
            .and_then(|v| v.checked_sub(cy))
            .and_then(|v| v.checked_div(f))
            .ok_or(nf)?;
        let (o, z) = (S::ONE, S::ZERO);
        let near_p = Plane::new(Vec3::new(z, z, o), -near);
        #[cfg(feature = "clip-far")]
        let far_p = Plane::new(Vec3::new(z, z, -o), far);
        let (sides, depth_a, depth_scale) = match projection.kind {
            ProjectionKind::Perspective { .. } => {
                let inv_near = o.checked_div(near).ok_or(nf)?;
                let inv_far = o.checked_div(far).ok_or(nf)?;
                let range = inv_near.checked_sub(inv_far).ok_or(nf)?;
                let scale = o.checked_div(range).ok_or(nf)?;
                (
                    [
                        Plane::new(Vec3::new(o, z, left), z),
                        Plane::new(Vec3::new(-o, z, right), z),
                        Plane::new(Vec3::new(z, o, top), z),
                        Plane::new(Vec3::new(z, -o, bottom), z),
                    ],
                    inv_near,
                    scale,
                )
            }
            ProjectionKind::Parallel { .. } => {
                let range = far.checked_sub(near).ok_or(nf)?;
                let scale = o.checked_div(range).ok_or(nf)?;
                (
                    [
                        Plane::new(Vec3::new(o, z, z), left),
                        Plane::new(Vec3::new(-o, z, z), right),
                        Plane::new(Vec3::new(z, o, z), top),
                        Plane::new(Vec3::new(z, -o, z), bottom),
                    ],
                    near,
                    scale,
                )
            }
        };
        // Geometry beyond `far` is not cut off unless the caller asks for
        // it with `with_far_clip` (feature `clip-far`): its depth keys
        // saturate at the far value (65535).
        let frustum = Frustum::from_planes(&[near_p, sides[0], sides[1], sides[2], sides[3]]);
        // Saturating: a guard band beyond the 28.4 range only widens the
        // rectangle (the side planes stay the ones the clipper uses).
        let sub = |v: S| v.to_subpixel(SUBPIXEL_BITS).unwrap_or(i32::MAX);
        let g = sub(guard);
        let guard_rect = [-g, sub(w).saturating_add(g), -g, sub(h).saturating_add(g)];
        Ok(Self {
            projection,
            frustum,
            depth_a,
            depth_scale,
            near,
            cull: Cull::None,
            guard_rect,
            guard_small: guard_rect.iter().all(|c| c.unsigned_abs() < 1 << 14),
            #[cfg(feature = "clip-far")]
            far_plane: far_p,
        })
    }

    /// The same pipeline clipping at the far plane too (`on`), or not.
    ///
    /// A new pipeline does not clip at `far`: geometry beyond it is drawn,
    /// with its depth key saturated at the far value, so the nearest
    /// surface still wins. With `on`, geometry beyond `far` is cut off by
    /// the clipper like geometry in front of `near`.
    #[cfg(feature = "clip-far")]
    #[must_use]
    pub fn with_far_clip(mut self, on: bool) -> Self {
        let p = self.frustum.planes();
        // Planes are [near, (far,) left, right, top, bottom].
        let sides = [
            p[p.len() - 4],
            p[p.len() - 3],
            p[p.len() - 2],
            p[p.len() - 1],
        ];
        self.frustum = if on {
            Frustum::from_planes(&[p[0], self.far_plane, sides[0], sides[1], sides[2], sides[3]])
        } else {
            Frustum::from_planes(&[p[0], sides[0], sides[1], sides[2], sides[3]])
        };
        self
    }

    /// Whether the pipeline clips at the far plane (see
    /// [`with_far_clip`](Self::with_far_clip)).
    #[must_use]
    pub fn clips_far(&self) -> bool {
        self.frustum.planes().len() == 6
    }

    /// The same pipeline with face culling `cull` (default [`Cull::None`]).
    #[must_use]
    pub fn with_cull(mut self, cull: Cull) -> Self {
        self.cull = cull;
        self
    }

    /// Whether the guard-band rectangle lies within ±(2^14 − 1) in 28.4
    /// (see the field): then every triangle whose vertices are all inside
    /// the volume is within the scan converter's 32-bit walk.
    pub(crate) fn guard_small(&self) -> bool {
        self.guard_small
    }

    /// The clip volume.
    #[must_use]
    pub fn frustum(&self) -> &Frustum<S> {
        &self.frustum
    }

    /// The projection.
    #[must_use]
    pub fn projection(&self) -> &Projection<S> {
        &self.projection
    }

    /// Projects a (clipped) view-space vertex to the scan converter's
    /// format: 28.4 position, depth key and varyings. `None` if the
    /// projection fails (behind the eye, overflow, non-finite).
    #[must_use]
    pub fn project<A: Varyings<S, VARYINGS>, const VARYINGS: usize>(
        &self,
        v: &Vertex<S, A>,
    ) -> Option<ScreenVertex<VARYINGS>> {
        let (p, depth) = self.projection.project(v.pos)?;
        let x = p.x.to_subpixel(SUBPIXEL_BITS)?;
        let y = p.y.to_subpixel(SUBPIXEL_BITS)?;
        let (frac, q) = match self.projection.kind {
            // q = near/z = near·(1/z): a multiply, not a division.
            ProjectionKind::Perspective { .. } => {
                ((self.depth_a - depth) * self.depth_scale, depth * self.near)
            }
            ProjectionKind::Parallel { .. } => ((depth - self.depth_a) * self.depth_scale, S::ONE),
        };
        // Clipping keeps the fraction in [0, 1] up to rounding.
        let key = frac
            .clamp_to(S::ZERO, S::ONE)
            .to_subpixel(16)
            .unwrap_or(0)
            .clamp(0, u16::MAX as i32) as u16;
        Some(ScreenVertex::new(x, y, key, v.attr.to_varyings(q)))
    }

    /// Clips and projects one convex view-space polygon to the scan
    /// converter's input, applying face culling: `Ok(None)` if culled.
    ///
    /// Clipping is exact in view space, but the clipped vertices snap to
    /// 28.4 screen positions: a sliver seen nearly edge-on (well below a
    /// pixel of area) can snap to a polygon that is not convex, or flip its
    /// orientation. [`fill_polygon`] covers such a polygon with one span
    /// per row between its chains, so it may cover a pixel its neighbour
    /// also covers; with a depth buffer the nearer one wins, without one
    /// the later one.
    ///
    /// For strip rendering, project each polygon once per frame and keep
    /// the results; then call [`fill_polygon`] per band, which rejects
    /// polygons outside the band after one comparison. The result may
    /// have fewer than three vertices (nothing visible).
    ///
    /// # Errors
    /// [`DrawError::Clip`] for non-finite or oversized input,
    /// [`DrawError::Projection`] if a clipped vertex cannot be projected.
    pub fn project_polygon<A, const VARYINGS: usize>(
        &self,
        poly: &[Vertex<S, A>],
    ) -> Result<Option<ScreenPolygon<VARYINGS>>, DrawError>
    where
        A: Varyings<S, VARYINGS>,
    {
        let clipped = self.frustum.clip(poly).map_err(DrawError::Clip)?;
        let mut screen = ScreenPolygon::new();
        for v in &clipped {
            let sv = self.project(v).ok_or(DrawError::Projection)?;
            // Cannot fail: `clipped` has the same capacity.
            screen
                .push(sv)
                .map_err(|_| DrawError::Clip(ClipError::TooManyVertices))?;
        }
        if !self.keep(&screen) {
            return Ok(None);
        }
        Ok(Some(screen))
    }

    /// Clips, projects and scan-converts one convex view-space polygon:
    /// [`Self::project_polygon`], then [`fill_polygon`].
    ///
    /// # Errors
    /// As [`Self::project_polygon`]; nothing is drawn then. Nothing panics
    /// and nothing is written outside `target`, whatever the input.
    pub fn draw_polygon<A, T, Z, Sh, const VARYINGS: usize>(
        &self,
        target: &mut T,
        depth: &mut Z,
        shader: &Sh,
        poly: &[Vertex<S, A>],
    ) -> Result<DrawOutcome, DrawError>
    where
        A: Varyings<S, VARYINGS>,
        T: Target,
        Z: DepthTest,
        Sh: SpanShader<VARYINGS, Color = T::Color>,
    {
        Ok(match self.project_polygon(poly)? {
            Some(screen) => DrawOutcome::Filled(fill_polygon(target, depth, shader, &screen)),
            None => DrawOutcome::Culled,
        })
    }
}

/// What [`Pipeline::draw_polygon`] did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DrawOutcome {
    /// The polygon reached the scan converter, with its outcome.
    Filled(FillOutcome),
    /// Dropped by face culling ([`Pipeline::with_cull`]) before scan
    /// conversion.
    Culled,
}

impl DrawOutcome {
    /// Whether spans were emitted ([`FillOutcome::Drawn`]).
    #[must_use]
    pub fn is_drawn(self) -> bool {
        self == Self::Filled(FillOutcome::Drawn)
    }
}

// Each test is gated on the stages it needs.
#[cfg(test)]
mod tests;
