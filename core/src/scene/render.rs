//! The raster path over a prepared scene: [`Renderer::project`] once per
//! frame, then [`Frame::draw`] once per band (or once for a whole frame).
//!
//! Per frame and object, each vertex is transformed to view space and
//! projected exactly once, with its clip outcode, into the caller's
//! scratch ([`MeshVertex`]). Per triangle, [`Frame::draw`] then
//!
//! 1. rejects it if it lies wholly outside one plane, or (when all three
//!    vertices are inside the volume) outside the band's rows;
//! 2. culls it in screen space by its winding (i32 cross product);
//! 3. lights it (flat shading: one dot product with the prepared face
//!    normal), and scan-converts it.
//!
//! Only triangles that cross a plane of the volume (near, far when
//! [`Renderer::with_far_clip`] asks for it, or a side plane's guard band) are rebuilt in view space and
//! go through Sutherland–Hodgman clipping. The guard band is 16 pixels
//! for textured objects and reaches ±1024 pixels (the scan converter's
//! 32-bit walk) for flat and Gouraud ones (see `widen_guard_band`).

use super::material::PreparedLight;
use super::prepared::{ObjectFrame, PreparedMesh, PreparedObject};
use super::{Color, Light, Material, Scene, SceneError, View};
#[cfg(feature = "perspective")]
use crate::math::Vec2;
#[cfg(feature = "perspective")]
use crate::pipeline::Attributes;
#[cfg(feature = "gouraud")]
use crate::pipeline::Intensity;
#[cfg(feature = "texture")]
use crate::pipeline::Uv;
#[cfg(feature = "perspective")]
use crate::pipeline::UvPerspective;
use crate::pipeline::{MeshVertex, OUTCODE_UNUSABLE, Pipeline, Varyings, Vertex};
#[cfg(feature = "texture")]
use crate::raster::AffineTexture;
#[cfg(feature = "gouraud")]
use crate::raster::Gouraud;
#[cfg(feature = "perspective")]
use crate::raster::PerspectiveTexture;
use crate::raster::{
    DepthTest, FillOutcome, Flat, SMALL_COORD_LIMIT, ScalableColor, ScreenVertex, SpanShader,
    fill_polygon, fill_small_triangle,
};
use crate::scalar::Scalar;
use crate::target::{Rect, Target};
#[cfg(feature = "texture")]
use crate::texture::RepeatPow2;
#[cfg(feature = "perspective")]
use crate::texture::{Mapping, choose_mapping};

/// Guard band of the clip volume, in pixels.
const GUARD: i32 = 16;

/// What [`Frame::draw`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RasterStats {
    /// Triangles considered (every triangle of every object, per call).
    pub triangles: u32,
    /// Triangles that emitted spans.
    pub drawn: u32,
    /// Triangles dropped by face culling (in a band's call, of those
    /// that reach the band's rows).
    pub culled: u32,
    /// Triangles that went through the clipper.
    pub clipped: u32,
    /// Triangles the pipeline could not draw (clip or projection
    /// overflow, e.g. saturated fixed point, or a vertex index beyond the
    /// mesh); the rest is still drawn.
    pub errors: u32,
}

/// The per-view part of a prepared scene: camera, projection and clip
/// volume, light and background, in scalar `S`. Build it once; change the
/// camera or the light between frames.
///
/// # Examples
///
/// A built-in scene rendered into a 240×240 RGB565 frame in I16F16:
///
/// ```
/// # #[cfg(feature = "demo")] {
/// use sightline::math::Vec3;
/// use sightline::pipeline::MeshVertex;
/// use sightline::raster::NoDepth;
/// use sightline::scalar::I16F16;
/// use sightline::scene::{builtin, Color, PreparedObject, Renderer};
/// use sightline::target::Framebuffer;
///
/// let scene = &builtin::CUBE;
/// let need = scene.storage();
/// let mut vec3s = vec![Vec3::<I16F16>::ZERO; need.vec3s];
/// let mut objects = vec![PreparedObject::EMPTY; need.objects];
/// let objects = scene.prepare(&mut vec3s, &mut objects).unwrap();
/// let renderer = Renderer::<I16F16>::new(scene, 240, 240).unwrap();
///
/// let mut pixels = vec![Color::new(0, 0, 0); 240 * 240];
/// let mut fb = Framebuffer::new(&mut pixels, 240, 240, 240).unwrap();
/// let mut scratch = vec![MeshVertex::default(); need.vertices];
/// let frame = renderer.project(objects, &mut scratch).unwrap();
/// let stats = frame.draw(&mut fb, &mut NoDepth);
/// assert!(stats.drawn > 0);
/// # }
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Renderer<S> {
    view: View<S>,
    pipeline: Pipeline<S>,
    near: S,
    far: S,
    light: PreparedLight<S>,
    background: Color,
}

impl<S: Scalar> Renderer<S> {
    /// The camera, projection, clip volume (`scene.near`; `scene.far` only
    /// with [`with_far_clip`](Self::with_far_clip)), light and background
    /// of `scene` for a `width`×`height` image.
    ///
    /// # Errors
    /// [`SceneError::NonFinite`] for a NaN or infinite number in the
    /// camera, projection, light or depth range; [`SceneError::Camera`],
    /// [`SceneError::BadProjection`], [`SceneError::Pipeline`].
    pub fn new(scene: &Scene<'_>, width: u16, height: u16) -> Result<Self, SceneError> {
        scene.validate_view()?;
        let view = scene.view::<S>(width, height)?;
        Self::for_scene(scene, view)
    }

    /// As [`Renderer::new`], but seen through a `camera` you built
    /// yourself instead of the scene's [`CameraSpec`](super::CameraSpec):
    /// a firmware that builds its camera with one direct constructor
    /// links no camera solver (see [`Scene::view_with`]).
    ///
    /// # Errors
    /// As [`Renderer::new`]; [`SceneError::NonFinite`] names the camera
    /// for a camera with a non-finite entry, whatever the scene's
    /// [`Scene::camera`] holds (it is not used).
    pub fn with_camera(
        scene: &Scene<'_>,
        camera: crate::camera::Camera<S>,
        width: u16,
        height: u16,
    ) -> Result<Self, SceneError> {
        scene.validate_view_except_camera()?;
        let view = scene.view_with(camera, width, height)?;
        Self::for_scene(scene, view)
    }

    /// The scene's depth range, light and background seen through `view`.
    fn for_scene(scene: &Scene<'_>, view: View<S>) -> Result<Self, SceneError> {
        Self::from_view(
            view,
            S::from_f32(scene.near),
            S::from_f32(scene.far),
            &scene.light,
            scene.background,
        )
    }

    /// A renderer for a camera and projection you built yourself (for
    /// example a focus distance in pixels), clipping at view depths
    /// `near` and `far`.
    ///
    /// # Errors
    /// [`SceneError::NonFinite`] for a non-finite light,
    /// [`SceneError::Pipeline`] for a bad depth range or projection.
    pub fn from_view(
        view: View<S>,
        near: S,
        far: S,
        light: &Light,
        background: Color,
    ) -> Result<Self, SceneError> {
        let light = PreparedLight::from_light(light)?;
        Self::from_prepared(view, near, far, light, background)
    }

    /// [`Renderer::from_view`] with a light already in `S`: together with
    /// [`Camera::from_world_to_view`](crate::camera::Camera::from_world_to_view)
    /// and [`PreparedMesh::new`], a renderer built from `const` data (as
    /// `scene::export`, feature `export`, writes it) does no `f32`
    /// arithmetic.
    ///
    /// # Errors
    /// [`SceneError::NonFinite`] for a light with a NaN or infinite part
    /// (floats only), [`SceneError::Pipeline`] for a bad depth range or
    /// projection.
    pub fn from_prepared(
        view: View<S>,
        near: S,
        far: S,
        light: PreparedLight<S>,
        background: Color,
    ) -> Result<Self, SceneError> {
        if !light.is_finite() {
            return Err(SceneError::NonFinite { what: "light" });
        }
        let pipeline = Pipeline::new(
            view.projection,
            view.width,
            view.height,
            near,
            far,
            S::from_i32(GUARD),
        )
        .map_err(SceneError::Pipeline)?;
        Ok(Self {
            view,
            pipeline,
            near,
            far,
            light,
            background,
        })
    }

    /// The same renderer clipping at the far plane too (`on`), or not
    /// (the default: geometry beyond `far` is drawn, its depth key
    /// saturated at the far value). See [`Pipeline::with_far_clip`].
    #[cfg(feature = "clip-far")]
    #[must_use]
    pub fn with_far_clip(mut self, on: bool) -> Self {
        self.pipeline = self.pipeline.with_far_clip(on);
        self
    }

    /// Camera, projection and image size.
    #[must_use]
    pub fn view(&self) -> &View<S> {
        &self.view
    }

    /// Replaces the camera (the projection and clip volume stay).
    pub fn set_camera(&mut self, camera: crate::camera::Camera<S>) {
        self.view.camera = camera;
    }

    /// Replaces the light.
    ///
    /// # Errors
    /// [`SceneError::NonFinite`] if a value is NaN or infinite; the light
    /// is unchanged then.
    pub fn set_light(&mut self, light: &Light) -> Result<(), SceneError> {
        if !super::light_is_finite(light) {
            return Err(SceneError::NonFinite { what: "light" });
        }
        self.light = PreparedLight::new(light);
        Ok(())
    }

    /// The light, in `S`.
    #[must_use]
    pub fn light(&self) -> PreparedLight<S> {
        self.light
    }

    /// The view depths of the near and far planes.
    #[must_use]
    pub fn depth_range(&self) -> (S, S) {
        (self.near, self.far)
    }

    /// Whether it clips at the far plane (only ever with feature
    /// `clip-far`, when asked with `with_far_clip`).
    #[must_use]
    pub fn clips_far(&self) -> bool {
        self.pipeline.clips_far()
    }

    /// The background color [`Frame::draw`] fills with.
    #[must_use]
    pub fn background(&self) -> Color {
        self.background
    }

    /// Transforms and projects every vertex of every object exactly once,
    /// at the objects' current poses, into `scratch` (at least as many
    /// entries as the objects have vertices; [`Scene::storage`] says how
    /// many). The returned frame draws them, once or band by band.
    ///
    /// Each entry's outcode is taken against the object's guard band: a
    /// vertex of a flat or Gouraud object that lies past the 16-pixel
    /// band only through the side planes, within ±1024 pixels of the
    /// viewport's origin, is recorded as inside, so that its triangles
    /// are drawn from their exact projection (scissored) instead of
    /// being cut by the clipper; textured objects keep the 16-pixel band.
    /// The frame also notes whether any triangle needs the clipper
    /// ([`Frame::needs_clipping`]).
    ///
    /// # Errors
    /// [`SceneError::ScratchTooSmall`]; nothing is projected then.
    pub fn project<'f, 'a>(
        &'f self,
        objects: &'f mut [PreparedObject<'a, S>],
        scratch: &'f mut [MeshVertex<1>],
    ) -> Result<Frame<'f, 'a, S>, SceneError> {
        let needed: usize = objects.iter().map(|o| o.mesh.positions().len()).sum();
        if scratch.len() < needed {
            return Err(SceneError::ScratchTooSmall {
                needed,
                given: scratch.len(),
            });
        }
        let mut first = 0;
        let mut clipping = None;
        for (index, obj) in objects.iter_mut().enumerate() {
            let rot = obj.pose.angles.to_mat3();
            let to_world = crate::math::Affine3::new(rot, obj.pose.origin);
            let to_view = self.view.camera.world_to_view().mul_affine(&to_world);
            let light = self.light.in_object(&rot).for_normals();
            let mesh = obj.mesh;
            let n = mesh.positions().len();
            let out = &mut scratch[first..first + n];
            let pipe = &self.pipeline;
            let points = to_view.for_points();
            let pos = |k: usize| points.apply(mesh.positions()[k]);
            // The OR of the object's outcodes, for `needs_clipper`.
            let mut outside = 0;
            match obj.material {
                #[cfg(feature = "gouraud")]
                Material::Gouraud(_) => {
                    for (k, o) in out.iter_mut().enumerate() {
                        // `get`: the object's material may have been changed to one
                        // this mesh has no normals for (they are pub fields).
                        let n = mesh.vertex_normals().get(k).copied().unwrap_or_default();
                        let i = light.intensity(n);
                        *o = pipe.project_vertex(&Vertex::new(pos(k), Intensity(i)));
                        outside |= o.outcode;
                    }
                }
                #[cfg(feature = "perspective")]
                Material::Texture { mode, .. } if mode != super::TextureMode::Affine => {
                    for (k, o) in out.iter_mut().enumerate() {
                        *o = pipe.project_vertex(&Vertex::new(pos(k), DepthQ));
                        outside |= o.outcode;
                    }
                }
                _ => {
                    for (k, o) in out.iter_mut().enumerate() {
                        let v = pipe.project_vertex::<(), 0>(&Vertex::new(pos(k), ()));
                        *o = MeshVertex {
                            outcode: v.outcode,
                            screen: ScreenVertex::new(v.screen.x, v.screen.y, v.screen.z, [0]),
                        };
                        outside |= v.outcode;
                    }
                }
            }
            if outside != 0 && draws_sides(&obj.material) {
                outside = widen_guard_band(pipe, out);
            }
            if clipping.is_none() && outside != 0 && needs_clipper(out, mesh.triangles()) {
                clipping = Some(index);
            }
            obj.frame = Some(ObjectFrame {
                to_view,
                light,
                first,
            });
            first += n;
        }
        Ok(Frame {
            renderer: self,
            objects,
            vertices: scratch,
            clipping,
        })
    }
}

/// Whether [`Frame::draw`] sends a triangle of `tris` to the clipper: one
/// with a vertex outside some plane of the view volume (or unusable) and
/// no plane with all three outside (those it drops at once). The caller
/// ORs the outcodes while it projects and asks only when some vertex is
/// outside, so a mesh wholly inside (the common case) costs no scan of
/// its triangles. An index out of range is not a clipping matter (both
/// draws count it as an error).
#[cold]
#[inline(never)]
fn needs_clipper(verts: &[MeshVertex<1>], tris: &[[u16; 3]]) -> bool {
    tris.iter().any(|tri| {
        let (mut or, mut and) = (0, u8::MAX);
        for &k in tri {
            let Some(v) = verts.get(k as usize) else {
                return false;
            };
            or |= v.outcode;
            and &= v.outcode;
        }
        or != 0 && and & !OUTCODE_UNUSABLE == 0
    })
}

/// Whether this material's triangles may reach past the 16-pixel guard
/// band unclipped ([`widen_guard_band`]): flat and Gouraud ones.
fn draws_sides(material: &Material<'_>) -> bool {
    matches!(material, Material::Flat(_) | Material::Gouraud(_))
}

/// For a flat or Gouraud object, the side planes' guard band reaches the
/// scan converter's 32-bit walk, ±[`SMALL_COORD_LIMIT`] (2^14 in 28.4,
/// ±1024 pixels from the viewport's origin): a vertex outside the
/// 16-pixel band only through side planes (in front of the eye, so it
/// has its exact projection) and within that range is marked inside.
/// Its triangles are then drawn from their exact projection, which the
/// scan converter scissors, instead of being cut by the clipper, which
/// rounds the new vertices; a floor that reaches a little past the
/// sides, as in the built-in cube scene, needs no clipper. Returns the
/// OR of the outcodes left.
///
/// Textured objects keep the 16-pixel band: a texture plane fitted to
/// vertices far off screen loses accuracy where it is seen (drawn that
/// way, the corridor's agreement with the ray path fell from 98.01 % to
/// 97.79 % of pixels equal in I16F16, `tests/tests/scenes.rs`).
#[cold]
#[inline(never)]
fn widen_guard_band<S: Scalar>(pipe: &Pipeline<S>, verts: &mut [MeshVertex<1>]) -> u8 {
    let lim = SMALL_COORD_LIMIT.unsigned_abs();
    let unprojected = pipe.unprojected_outcodes();
    let mut or = 0;
    for v in verts {
        if v.outcode & unprojected == 0
            && v.screen.x.unsigned_abs() <= lim
            && v.screen.y.unsigned_abs() <= lim
        {
            v.outcode = 0;
        }
        or |= v.outcode;
    }
    or
}

/// The perspective varying `q = near/z` alone: what a perspective texture
/// needs per vertex besides the mesh's texture coordinates.
#[cfg(feature = "perspective")]
#[derive(Clone, Copy, Debug)]
struct DepthQ;

#[cfg(feature = "perspective")]
impl<S: Scalar> Attributes<S> for DepthQ {
    fn lerp(self, _other: Self, _t: S) -> Self {
        self
    }
    fn is_finite(&self) -> bool {
        true
    }
}

#[cfg(feature = "perspective")]
impl<S: Scalar> Varyings<S, 1> for DepthQ {
    fn to_varyings(&self, q: S) -> [i32; 1] {
        let q = q.clamp_to(S::ZERO, S::ONE);
        [q.to_subpixel(crate::raster::PERSPECTIVE_Q_BITS)
            .unwrap_or(1)
            .max(1)]
    }
}

/// One frame of a prepared scene, projected: draw it whole or band by
/// band. Drawing changes nothing in the frame, so every band sees the same
/// vertices, and a frame drawn in bands equals the frame drawn whole.
#[derive(Debug)]
pub struct Frame<'f, 'a, S> {
    renderer: &'f Renderer<S>,
    objects: &'f [PreparedObject<'a, S>],
    vertices: &'f [MeshVertex<1>],
    /// The first object with a triangle for the clipper ([`needs_clipper`]).
    clipping: Option<usize>,
}

/// [`Tri::rows`] for the band of rows `r0..r1`.
fn band_heights(r0: i32, r1: i32) -> (i32, i32) {
    (
        r0.saturating_mul(16).saturating_add(8),
        r1.saturating_mul(16).saturating_sub(7),
    )
}

/// Whether a triangle with these 28.4 vertex heights covers none of the
/// rows [`band_heights`] gave `rows` for: all three at or above the
/// first, or all at or below the second: four compares for a typical
/// triangle. The rows from the min/max of the three heights, in the same
/// place (after the winding then), cost ARMv6-M W1/W2 5.134 M / 6.144 M
/// instructions per frame, this 5.116 M / 6.124 M. Tested before the
/// winding: in 40-row bands
/// the bunny scene frame took 9.78 M instructions with the winding first
/// and 9.23 M with this first; a whole-frame W1 frame takes 0.3 % more
/// (5.10 M -> 5.12 M), W2 0.04 % less (`bash tests/mcu/run`).
#[inline(always)]
fn misses_rows(y: [i32; 3], (above, below): (i32, i32)) -> bool {
    (y[0] <= above && y[1] <= above && y[2] <= above)
        || (y[0] >= below && y[1] >= below && y[2] >= below)
}

/// One triangle's path through [`Frame::draw`] (with `CLIP`) or
/// [`Frame::draw_unclipped`].
struct Tri<'m, 'v, S, const CLIP: bool> {
    mesh: &'m PreparedMesh<'m, S>,
    frame: &'m ObjectFrame<S>,
    verts: &'v [MeshVertex<1>],
    pipe: &'m Pipeline<S>,
    /// The band's rows `r0..r1` as two 28.4 heights: a triangle covers
    /// rows whose centers lie in `[y_min, y_max)` (the raster's fill
    /// rule), so it misses the band exactly when `y_max ≤ 16·r0 + 8` or
    /// `y_min ≥ 16·r1 − 7`. (Saturated: a band beyond ±2^27 rows lies
    /// past every vertex inside the volume.)
    rows: (i32, i32),
}

impl<S: Scalar, const CLIP: bool> Tri<'_, '_, S, CLIP> {
    /// Draws triangle `tri`: `inside(k, vertex)` gives the varyings of an
    /// unclipped vertex, `attr(k)` the view-space attributes of a vertex
    /// to clip, `shader(t)` the shader once the triangle is known to be
    /// visible.
    ///
    /// Without `CLIP` (for [`Frame::draw_unclipped`], which has checked
    /// that no triangle needs it) the clipper is left out: a triangle that
    /// needed it would be counted as an error, and the inside ones take
    /// [`fill_small_triangle`], which leaves out the polygon walk.
    #[allow(clippy::too_many_arguments)]
    #[inline]
    fn draw<T, Z, A, Sh, const VARYINGS: usize>(
        &self,
        target: &mut T,
        depth: &mut Z,
        stats: &mut RasterStats,
        tri: [u16; 3],
        inside: impl Fn(u16, &MeshVertex<1>) -> [i32; VARYINGS],
        attr: impl Fn(u16) -> A,
        shader: impl FnOnce(&[ScreenVertex<VARYINGS>]) -> Sh,
    ) where
        T: Target,
        Z: DepthTest,
        A: Varyings<S, VARYINGS>,
        Sh: SpanShader<VARYINGS, Color = T::Color>,
    {
        stats.triangles += 1;
        // By reference: the cull test reads only x, y and the outcode
        // (copying three vertices cost about 50 instructions per triangle
        // on ARMv6-M). A prepared mesh's indices are checked when it is
        // prepared; one out of range here (a mesh edited since) is an
        // error, not a draw.
        let get = |k: u16| self.verts.get(k as usize);
        let (Some(a), Some(b), Some(c)) = (get(tri[0]), get(tri[1]), get(tri[2])) else {
            stats.errors += 1;
            return;
        };
        let outcome = if a.outcode | b.outcode | c.outcode == 0 {
            if misses_rows([a.screen.y, b.screen.y, c.screen.y], self.rows) {
                return;
            }
            // Culled before the varyings are gathered; the vertices are
            // built in place (an array `map` here compiled to two memcpy
            // calls per triangle on ARMv6-M).
            let xy = |v: &MeshVertex<1>| (v.screen.x, v.screen.y);
            if !self.pipe.keep_inside(xy(a), xy(b), xy(c)) {
                stats.culled += 1;
                return;
            }
            let sv = |k: u16, v: &MeshVertex<1>| {
                ScreenVertex::new(v.screen.x, v.screen.y, v.screen.z, inside(k, v))
            };
            let s = [sv(tri[0], a), sv(tri[1], b), sv(tri[2], c)];
            if CLIP {
                fill_polygon(target, depth, &shader(&s), &s)
            } else {
                fill_small_triangle(target, depth, &shader(&s), &s)
            }
        } else if a.outcode & b.outcode & c.outcode & !OUTCODE_UNUSABLE != 0 {
            return;
        } else if !CLIP {
            stats.errors += 1;
            return;
        } else {
            stats.clipped += 1;
            let poly = tri.map(|k| {
                let p = self.mesh.positions()[k as usize];
                Vertex::new(self.frame.to_view.transform_point3(p), attr(k))
            });
            match self.pipe.project_polygon(&poly) {
                Ok(Some(s)) => fill_polygon(target, depth, &shader(&s), &s),
                Ok(None) => {
                    stats.culled += 1;
                    return;
                }
                Err(_) => {
                    stats.errors += 1;
                    return;
                }
            }
        };
        if outcome == FillOutcome::Drawn {
            stats.drawn += 1;
        }
    }
}

impl<S: Scalar> Frame<'_, '_, S> {
    /// Fills the target's clip rectangle with the background, then draws
    /// every triangle of every object with `depth` deciding visibility.
    /// Works with any [`Target`]: a [`Band`](crate::target::Band) and a
    /// band-sized depth buffer draw one strip; only the triangles that
    /// reach the band's rows get any set-up.
    ///
    /// # Panics
    /// Never; nothing is written outside the target.
    pub fn draw<T, Z>(&self, target: &mut T, depth: &mut Z) -> RasterStats
    where
        T: Target<Color = Color>,
        Z: DepthTest,
    {
        self.draw_with::<T, Z, true>(target, depth)
    }

    /// Whether a triangle of this frame crosses a plane of the view
    /// volume (or uses a vertex that cannot be projected), so that
    /// [`Self::draw`] clips it and [`Self::draw_unclipped`] refuses the
    /// frame. The side planes lie at the guard band: 16 pixels past the
    /// viewport for textured objects, ±1024 pixels from its origin for
    /// flat and Gouraud ones (see [`Renderer::project`]). Triangles
    /// wholly outside one plane need no clipper (they are dropped).
    /// Decided once per frame, in [`Renderer::project`], at the cost of
    /// one OR per vertex; the triangles of an object are scanned only
    /// when one of its vertices lies outside.
    #[must_use]
    pub fn needs_clipping(&self) -> bool {
        self.clipping.is_some()
    }

    /// [`Self::draw`] without the clipper: the same pixels and the same
    /// stats, for a frame that does not [need clipping](Self::needs_clipping)
    /// on a viewport whose guard band lies within ±1024 pixels (up to
    /// 1007 pixels a side with the 16-pixel band). Every triangle then
    /// takes the scan converter's 32-bit triangle walk. A firmware whose
    /// scene stays in view calls only this and links neither the clipper
    /// nor the polygon walk: the flat cube firmware of `tests/mcu` does
    /// (the size table in the [crate docs](crate) has its figures).
    ///
    /// # Errors
    /// [`SceneError::NeedsClipping`] (naming the first object with such
    /// a triangle) or [`SceneError::ViewportTooLarge`]. Nothing is drawn
    /// then, not even the background.
    ///
    /// # Panics
    /// Never; nothing is written outside the target.
    pub fn draw_unclipped<T, Z>(
        &self,
        target: &mut T,
        depth: &mut Z,
    ) -> Result<RasterStats, SceneError>
    where
        T: Target<Color = Color>,
        Z: DepthTest,
    {
        if let Some(object) = self.clipping {
            return Err(SceneError::NeedsClipping { object });
        }
        if !self.renderer.pipeline.guard_small() {
            return Err(SceneError::ViewportTooLarge);
        }
        Ok(self.draw_with::<T, Z, false>(target, depth))
    }

    /// [`Self::draw`]'s body; without `CLIP` the clipper is left out
    /// (see `Tri::draw`).
    #[inline(always)]
    fn draw_with<T, Z, const CLIP: bool>(&self, target: &mut T, depth: &mut Z) -> RasterStats
    where
        T: Target<Color = Color>,
        Z: DepthTest,
    {
        let mut clip: Rect = target.clip_rect();
        if let Some(r) = depth.clip_rect() {
            clip = clip.intersect(&r);
        }
        target.clear(self.renderer.background);
        let mut stats = RasterStats::default();
        if clip.is_empty() {
            return stats;
        }
        for obj in self.objects {
            let Some(fr) = &obj.frame else { continue };
            let mesh = &obj.mesh;
            let n = mesh.positions().len();
            let Some(verts) = self.vertices.get(fr.first..fr.first + n) else {
                continue;
            };
            let pipe = self.renderer.pipeline.with_cull(obj.cull);
            let t = Tri::<'_, '_, S, CLIP> {
                mesh,
                frame: fr,
                verts,
                pipe: &pipe,
                rows: band_heights(clip.y0, clip.y1),
            };
            let (target, depth, stats) = (&mut *target, &mut *depth, &mut stats);
            match obj.material {
                Material::Flat(color) => {
                    let light = &fr.light;
                    let faces = mesh.face_normals();
                    for (f, &tri) in mesh.triangles().iter().enumerate() {
                        let lit = |_: &[ScreenVertex<0>]| {
                            let n = faces.get(f).copied().unwrap_or_default();
                            Flat(color.scale(super::quantize_intensity(light.intensity(n))))
                        };
                        t.draw(target, depth, stats, tri, |_, _| [], |_| (), lit);
                    }
                }
                #[cfg(feature = "gouraud")]
                Material::Gouraud(color) => {
                    let ramp = color.ramp();
                    let shader = Gouraud::new(&ramp);
                    let light = &fr.light;
                    let normals = mesh.vertex_normals();
                    let attr = |k: u16| {
                        Intensity(
                            light.intensity(normals.get(k as usize).copied().unwrap_or_default()),
                        )
                    };
                    for &tri in mesh.triangles() {
                        t.draw(
                            target,
                            depth,
                            stats,
                            tri,
                            |_, v| v.screen.v,
                            attr,
                            |_| shader,
                        );
                    }
                }
                #[cfg(feature = "texture")]
                Material::Texture {
                    texture: tex,
                    #[cfg(feature = "perspective")]
                    mode,
                    ..
                } => {
                    // Without `perspective`, only Affine gets here: the
                    // others are refused before drawing.
                    let Some(affine) = AffineTexture::<_, RepeatPow2>::new(tex) else {
                        continue;
                    };
                    let uvs = mesh.uvs();
                    let uv = |k: u16| uvs.get(k as usize).copied().unwrap_or([0; 2]);
                    let texel = |t: i16| (t as i32) << 16;
                    let affine_in = |k: u16, _: &MeshVertex<1>| uv(k).map(texel);
                    let affine_attr = |k: u16| {
                        let [u, v] = uv(k);
                        Uv {
                            u: S::from_i32(u as i32),
                            v: S::from_i32(v as i32),
                        }
                    };
                    #[cfg(feature = "perspective")]
                    if mode != super::TextureMode::Affine {
                        let Some(exact) = PerspectiveTexture::<_, RepeatPow2, 1>::new(tex) else {
                            continue;
                        };
                        let persp_in = |k: u16, v: &MeshVertex<1>| {
                            let q = v.screen.v[0];
                            let [a, b] = uv(k).map(|t| {
                                let p = (t as i64 * q as i64)
                                    >> (crate::raster::PERSPECTIVE_Q_BITS - 16);
                                p.clamp(-(1 << 29), (1 << 29) - 1) as i32
                            });
                            [a, b, q]
                        };
                        let persp_attr = |k: u16| {
                            let [u, v] = uv(k);
                            UvPerspective {
                                u: S::from_i32(u as i32),
                                v: S::from_i32(v as i32),
                            }
                        };
                        let threshold = S::from_f32(super::AUTO_AFFINE_MAX_ERROR);
                        for &tri in mesh.triangles() {
                            if mode == super::TextureMode::Auto
                                && auto_is_affine(verts, tri, uv, threshold)
                            {
                                t.draw(target, depth, stats, tri, affine_in, affine_attr, |_| {
                                    affine
                                });
                            } else {
                                t.draw(target, depth, stats, tri, persp_in, persp_attr, |_| exact);
                            }
                        }
                        continue;
                    }
                    for &tri in mesh.triangles() {
                        t.draw(target, depth, stats, tri, affine_in, affine_attr, |_| {
                            affine
                        });
                    }
                }
                // Refused by `PreparedObject::new` (feature left out).
                #[allow(unreachable_patterns)]
                _ => {}
            }
        }
        stats
    }
}

/// [`TextureMode::Auto`](super::TextureMode::Auto)'s rule: affine when
/// all three vertices are in the volume (a clipped triangle is always
/// mapped perspectively) and [`choose_mapping`] finds the affine error
/// bound within `threshold` texels.
///
/// The bound needs the depths only through `(z_max − z_min)/z_min`, and
/// with `z = near/q` that equals `(q_max − q_min)/q_min` for the
/// vertices' perspective varyings q (8.24). So the q are passed as the
/// depths, shifted together so that the largest has 12 bits: the ratio
/// keeps 2⁻¹¹ relative precision where it decides (q close together),
/// and `4·z_min` stays inside I16F16.
#[cfg(feature = "perspective")]
fn auto_is_affine<S: Scalar>(
    verts: &[MeshVertex<1>],
    tri: [u16; 3],
    uv: impl Fn(u16) -> [i16; 2],
    threshold: S,
) -> bool {
    let mut q = [0i32; 3];
    for (qk, &k) in q.iter_mut().zip(&tri) {
        let Some(v) = verts.get(k as usize) else {
            return false;
        };
        if v.outcode != 0 {
            return false;
        }
        *qk = v.screen.v[0];
    }
    let hi = q[0].max(q[1]).max(q[2]);
    let shift = (32 - hi.max(1).leading_zeros()).saturating_sub(12);
    let z = q.map(|qk| S::from_i32(qk >> shift));
    let t = tri.map(|k| {
        let [u, v] = uv(k);
        Vec2::new(S::from_i32(u as i32), S::from_i32(v as i32))
    });
    choose_mapping(z, t, threshold) == Mapping::Affine
}

#[cfg(test)]
mod tests {
    use super::{band_heights, misses_rows};

    /// The band test is the rows-from-extremes test it replaced, exactly
    /// (`top = ⌈(y_min − 8)/16⌉`, `bottom` likewise from `y_max`: the band
    /// is missed when `bottom ≤ r0` or `top ≥ r1`), and it never drops a
    /// triangle that covers a row of the band by the fill rule counted
    /// out (a row's center `16r + 8` in `[y_min, y_max)`). Every band of
    /// one to four rows around the heights, and bands so far away that
    /// their heights saturate. (An empty band never gets here: `draw`
    /// returns first.)
    #[test]
    fn misses_rows_is_the_fill_rule() {
        let covers =
            |lo: i32, hi: i32, r0: i32, r1: i32| (r0..r1).any(|r| (lo..hi).contains(&(16 * r + 8)));
        for r0 in -4..5 {
            for r1 in r0 + 1..r0 + 5 {
                let rows = band_heights(r0, r1);
                for lo in -90..120 {
                    for hi in lo..lo + 40 {
                        let (top, bottom) = ((lo + 7) >> 4, (hi + 7) >> 4);
                        let want = bottom <= r0 || top >= r1;
                        let mid = (lo + hi) / 2;
                        for y in [[lo, mid, hi], [hi, lo, mid], [mid, hi, lo]] {
                            let got = misses_rows(y, rows);
                            assert_eq!(got, want, "{y:?} rows {r0}..{r1}");
                            assert!(!(got && covers(lo, hi, r0, r1)), "{y:?} rows {r0}..{r1}");
                        }
                    }
                }
            }
        }
        let far = [i32::MAX / 8, i32::MAX - 1, i32::MIN / 8, i32::MIN + 1];
        for r in far {
            for y in [[-(1 << 18), 0, 1 << 18], [5, 6, 7]] {
                let band = if r > 0 {
                    (r, r.saturating_add(3))
                } else {
                    (r, r + 3)
                };
                assert!(
                    misses_rows(y, band_heights(band.0, band.1)),
                    "{y:?} rows {r}"
                );
            }
        }
    }
}
