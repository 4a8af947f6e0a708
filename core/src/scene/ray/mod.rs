//! The ray path: one ray per pixel center, nearest hit over the scene's
//! meshes (watertight triangle test) and spheres, shaded **at the hit**
//! with the material model the raster path uses too (color ramp, texel
//! fetch), but none of its interpolation.
//!
//! Each ray is carried into each object's space (the inverse pose) and
//! tested against the object's box; then the nearest triangle of the
//! object is found by one of two searches, which give the same triangle
//! and the same hit bit for bit (same space, same watertight test, ties
//! to the lower index; tested):
//! - [`RayScene::new`] (no storage, no `grid` feature needed): every
//!   triangle of the object;
//! - [`RayScene::with_grid`] (feature `grid`): a uniform
//!   [`Grid`](crate::ray::Grid) per object, built once in caller storage
//!   (`grid.rs`).
//!
//! Shading at a hit on triangle (A, B, C) with barycentric weights
//! (u, v, w) from the watertight test:
//! - flat: the face normal, lit ([`Material::Flat`]);
//! - Gouraud: `I = u·I_A + v·I_B + w·I_C` from the vertex intensities,
//!   then quantized;
//! - texture: `(s, t) = u·uv_A + v·uv_B + w·uv_C` in texels, floored and
//!   fetched. For a planar triangle this is exactly the texture-mapping
//!   vectors' value at the hit point (the mapping is affine in object
//!   space, and so is the barycentric combination), so it is
//!   perspective-correct by construction.

#[cfg(feature = "grid")]
mod grid;

#[cfg(feature = "grid")]
pub use grid::{RayBuffers, RayStorage, RayTriangle};

use super::material::{self, PreparedLight};
#[cfg(feature = "sphere")]
use super::vec3;
use super::{Color, MAX_RAY_OBJECTS, Material, Scene, SceneError, View};
use crate::math::{Affine3, Mat3, Vec3};
use crate::raster::ScalableColor;
#[cfg(feature = "sphere")]
use crate::ray::Sphere;
use crate::ray::{Aabb, Ray, RayCamera, ShearedRay, Triangle, TriangleHit};
use crate::scalar::Scalar;
use crate::target::Target;
use crate::texture::RepeatPow2;

#[derive(Clone, Copy, Debug)]
struct RayObject<S> {
    to_object: Affine3<S>,
    rot: Mat3<S>,
    scale: S,
    bounds: Option<Aabb<S>>,
}

/// A scene prepared for ray casting at one image size: the ray camera,
/// each object's inverse pose and bounding box, the spheres, and with
/// [`Self::with_grid`] the world-space triangles in a uniform grid. Cheap
/// to share between threads (`Sync` when `S` is); every query is `&self`.
///
/// ```
/// # #[cfg(feature = "demo")] {
/// use sightline::scene::{builtin, Color, RayBuffers, RayScene, RayTriangle};
/// use sightline::target::Framebuffer;
///
/// let scene = &builtin::CUBE;
/// let view = scene.view::<f32>(80, 60).unwrap();
/// // Caller storage for the per-object grids, sized by a const fn.
/// let need = scene.ray_storage();
/// let mut triangles = vec![RayTriangle::EMPTY; need.triangles];
/// let (mut cells, mut items) = (vec![0u32; need.cells], vec![0u32; need.items]);
/// let buffers = RayBuffers { triangles: &mut triangles, cells: &mut cells, items: &mut items };
/// let rays = RayScene::with_grid(scene, &view, buffers).unwrap();
///
/// let mut pixels = vec![Color::new(0, 0, 0); 80 * 60];
/// rays.render(&mut Framebuffer::new(&mut pixels, 80, 60, 80).unwrap());
/// // The cube is in the middle of the picture, the background at a corner.
/// assert_ne!(pixels[30 * 80 + 40], scene.background);
/// assert_eq!(pixels[0], scene.background);
/// // Without storage the same picture comes from testing every triangle.
/// let plain = RayScene::new(scene, &view).unwrap();
/// assert_eq!(plain.pixel(40, 30), pixels[30 * 80 + 40]);
/// # }
/// ```
#[derive(Clone, Debug)]
pub struct RayScene<'a, S> {
    scene: Scene<'a>,
    camera: RayCamera<S>,
    inv_focus: S,
    objects: heapless::Vec<RayObject<S>, MAX_RAY_OBJECTS>,
    #[cfg(feature = "sphere")]
    spheres: heapless::Vec<Sphere<S>, MAX_RAY_OBJECTS>,
    light: PreparedLight<S>,
    /// One entry per object after [`Self::with_grid`], none after
    /// [`Self::new`].
    #[cfg(feature = "grid")]
    grids: heapless::Vec<Option<grid::ObjectGrid<'a, S>>, MAX_RAY_OBJECTS>,
}

/// What the ray through a pixel sees, before the color is looked up:
/// which surface, and the material model's input there. The color is
/// [`RayScene::color`] of it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum RaySample {
    /// Nothing is hit: the scene's background.
    Background,
    /// Sphere `sphere`, lit at intensity step `level` (0..=255).
    Sphere {
        /// Sphere index in the scene.
        sphere: usize,
        /// The quantized intensity `⌊255·I⌋`.
        level: u8,
    },
    /// A flat or Gouraud triangle of object `object`, lit at intensity
    /// step `level` (0..=255).
    Lit {
        /// Object index in the scene.
        object: usize,
        /// The quantized intensity `⌊255·I⌋`.
        level: u8,
    },
    /// A textured triangle of object `object`, showing texel
    /// `(u, v)` (before tiling).
    Texel {
        /// Object index in the scene.
        object: usize,
        /// Texel column.
        u: i32,
        /// Texel row.
        v: i32,
    },
}

impl<'a, S: Scalar> RayScene<'a, S> {
    /// Prepares `scene` for `view` (which must use a perspective
    /// projection), without acceleration beyond a box per object.
    ///
    /// # Errors
    /// [`Scene::validate`]'s errors; [`SceneError::RayCamera`] for a
    /// parallel projection; [`SceneError::TooManyObjects`];
    /// [`SceneError::BadPose`] / [`SceneError::BadSphere`].
    pub fn new(scene: &Scene<'a>, view: &View<S>) -> Result<Self, SceneError> {
        scene.validate()?;
        let camera =
            RayCamera::from_camera(&view.camera, &view.projection, view.width, view.height)
                .map_err(SceneError::RayCamera)?;
        let focus = match view.projection.kind {
            crate::camera::ProjectionKind::Perspective { focus } => focus,
            crate::camera::ProjectionKind::Parallel { .. } => {
                return Err(SceneError::RayCamera(
                    crate::ray::RayCameraError::NotPerspective,
                ));
            }
        };
        let mut objects = heapless::Vec::new();
        for (o, obj) in scene.objects.iter().enumerate() {
            let pose = material::pose::<S>(&obj.pose);
            let to_object = crate::solve::invert_affine(&pose.object_to_world())
                .map_err(|_| SceneError::BadPose { object: o })?;
            let scale = S::from_f32(obj.mesh.scale);
            let bounds = bounds(obj.mesh.positions, scale);
            objects
                .push(RayObject {
                    to_object,
                    rot: pose.angles.to_mat3(),
                    scale,
                    bounds,
                })
                .map_err(|_| SceneError::TooManyObjects)?;
        }
        #[cfg(not(feature = "sphere"))]
        if !scene.spheres.is_empty() {
            return Err(SceneError::FeatureDisabled { feature: "sphere" });
        }
        #[cfg(feature = "sphere")]
        let mut spheres = heapless::Vec::new();
        #[cfg(feature = "sphere")]
        for (k, s) in scene.spheres.iter().enumerate() {
            let sp = Sphere::new(vec3(s.center), S::from_f32(s.radius))
                .map_err(|_| SceneError::BadSphere { sphere: k })?;
            spheres.push(sp).map_err(|_| SceneError::TooManyObjects)?;
        }
        Ok(Self {
            scene: *scene,
            camera,
            inv_focus: S::ONE / focus,
            objects,
            #[cfg(feature = "sphere")]
            spheres,
            light: PreparedLight::new(&scene.light),
            #[cfg(feature = "grid")]
            grids: heapless::Vec::new(),
        })
    }

    /// Image width in pixels.
    #[must_use]
    pub fn width(&self) -> u16 {
        self.camera.width
    }

    /// Image height in pixels.
    #[must_use]
    pub fn height(&self) -> u16 {
        self.camera.height
    }

    /// The ray through the center of pixel (i, j), with its direction
    /// scaled by 1/focus (about unit length: keeps fixed point in range).
    #[must_use]
    pub fn pixel_ray(&self, i: u16, j: u16) -> Option<Ray<S>> {
        let c = |k: u16| S::from_i32(k as i32) + S::HALF;
        let p = self.camera.screen_point(c(i), c(j));
        let d = (p - self.camera.viewer) * self.inv_focus;
        Ray::new(self.camera.viewer, d).ok()
    }

    /// The color of pixel (i, j).
    #[must_use]
    pub fn pixel(&self, i: u16, j: u16) -> Color {
        self.color(self.pixel_sample(i, j))
    }

    /// What the ray of pixel (i, j) sees ([`Self::pixel`] is its color).
    #[must_use]
    pub fn pixel_sample(&self, i: u16, j: u16) -> RaySample {
        match self.pixel_ray(i, j) {
            Some(ray) => self.sample(&ray),
            None => RaySample::Background,
        }
    }

    /// Renders row `j` into `row` (its first `min(width, row.len())`
    /// pixels). Rows are independent: render them in any order or in
    /// parallel.
    pub fn render_row(&self, j: u16, row: &mut [Color]) {
        for (i, px) in row.iter_mut().enumerate().take(self.width() as usize) {
            *px = self.pixel(i as u16, j);
        }
    }

    /// Renders every pixel of the target's clip rectangle that lies in the
    /// image.
    pub fn render<T: Target<Color = Color>>(&self, target: &mut T) {
        let r = target.clip_rect();
        let x0 = r.x0.max(0);
        let x1 = r.x1.min(self.width() as i32);
        if x1 <= x0 {
            return;
        }
        for y in r.y0.max(0)..r.y1.min(self.height() as i32) {
            let mut x = x0;
            target.fill_with(y, x0, (x1 - x0) as u32, || {
                let c = self.pixel(x as u16, y as u16);
                x += 1;
                c
            });
        }
    }

    /// Shades the nearest hit of `ray`, or the background.
    #[must_use]
    pub fn trace(&self, ray: &Ray<S>) -> Color {
        self.color(self.sample(ray))
    }

    /// The color the material model gives `sample` (the background for a
    /// sample that names no surface of this scene).
    #[must_use]
    pub fn color(&self, sample: RaySample) -> Color {
        let bg = self.scene.background;
        match sample {
            RaySample::Background => bg,
            RaySample::Sphere { sphere, level } => self
                .scene
                .spheres
                .get(sphere)
                .map_or(bg, |s| s.color.scale(level)),
            RaySample::Lit { object, level } => match self.scene.objects.get(object) {
                Some(o) => match o.material {
                    Material::Flat(c) | Material::Gouraud(c) => c.scale(level),
                    Material::Texture { .. } => bg,
                },
                None => bg,
            },
            RaySample::Texel { object, u, v } => match self.scene.objects.get(object) {
                Some(o) => match o.material {
                    Material::Texture { texture, .. } => texture.sample::<RepeatPow2>(u, v),
                    _ => bg,
                },
                None => bg,
            },
        }
    }

    /// What `ray` sees: its nearest hit with `t > 0`, shaded.
    #[must_use]
    pub fn sample(&self, ray: &Ray<S>) -> RaySample {
        let tri = self.nearest_by_object(ray);
        #[cfg(feature = "sphere")]
        if let Some(s) = self.nearer_sphere(ray, tri.map(|(_, _, h)| h.t)) {
            return s;
        }
        match tri {
            Some((object, t, h)) => self.shade_triangle(object, t, &h),
            None => RaySample::Background,
        }
    }

    /// The nearest sphere hit strictly nearer than `best_t` (triangles win
    /// ties), lit with the sphere normal.
    #[cfg(feature = "sphere")]
    fn nearer_sphere(&self, ray: &Ray<S>, mut best_t: Option<S>) -> Option<RaySample> {
        let mut hit: Option<(usize, S)> = None;
        for (k, s) in self.spheres.iter().enumerate() {
            if let Some(t) = s.intersect(ray, S::ZERO) {
                if best_t.is_none_or(|b| t < b) {
                    best_t = Some(t);
                    hit = Some((k, t));
                }
            }
        }
        let (k, t) = hit?;
        let s = self.spheres.get(k)?;
        let level = material::quantize_intensity(self.light.intensity(s.normal_at(ray.at(t))));
        Some(RaySample::Sphere { sphere: k, level })
    }

    /// The nearest triangle hit, (object, triangle in the object's mesh,
    /// hit with its barycentric weights): every object in its own space,
    /// its box first, then its grid or every triangle.
    fn nearest_by_object(&self, ray: &Ray<S>) -> Option<(usize, usize, TriangleHit<S>)> {
        let mut best: Option<(usize, usize, TriangleHit<S>)> = None;
        for (o, (obj, desc)) in self.objects.iter().zip(self.scene.objects).enumerate() {
            let Ok(local) = Ray::new(
                obj.to_object.transform_point3(ray.origin()),
                obj.to_object.transform_vector3(ray.dir()),
            ) else {
                continue;
            };
            let best_t = best.map_or(S::MAX, |(_, _, h)| h.t);
            if let Some(b) = &obj.bounds {
                if b.intersect_range(&local, S::ZERO, best_t).is_none() {
                    continue;
                }
            }
            #[cfg(feature = "grid")]
            if let Some(Some(g)) = self.grids.get(o) {
                if let Some((t_i, h)) = g.nearest(&local) {
                    if best.is_none_or(|(_, _, b)| h.t < b.t) {
                        best = Some((o, t_i, h));
                    }
                }
                continue;
            }
            let Some(sheared) = ShearedRay::new(&local) else {
                continue;
            };
            let mesh = desc.mesh;
            for (t_i, &tri) in mesh.triangles.iter().enumerate() {
                let p = tri.map(|k| material::position(mesh, obj.scale, k));
                let Some(h) = Triangle::new(p[0], p[1], p[2]).intersect_sheared(&sheared, S::ZERO)
                else {
                    continue;
                };
                if best.is_none_or(|(_, _, b)| h.t < b.t) {
                    best = Some((o, t_i, h));
                }
            }
        }
        best
    }

    /// The material model at a hit on triangle `tri` of object `object`.
    fn shade_triangle(&self, object: usize, tri: usize, h: &TriangleHit<S>) -> RaySample {
        let (Some(obj), Some(desc)) = (self.objects.get(object), self.scene.objects.get(object))
        else {
            return RaySample::Background;
        };
        let mesh = desc.mesh;
        let Some(&t) = mesh.triangles.get(tri) else {
            return RaySample::Background;
        };
        let w = [h.u, h.v, h.w];
        match desc.material {
            Material::Flat(_) => {
                let level = material::face_normal(mesh, &obj.rot, t)
                    .map_or(0, |n| material::quantize_intensity(self.light.intensity(n)));
                RaySample::Lit { object, level }
            }
            Material::Gouraud(_) => {
                let i = material::vertex_intensities(mesh, &obj.rot, &self.light, t);
                let level = material::quantize_intensity(i[0] * w[0] + i[1] * w[1] + i[2] * w[2]);
                RaySample::Lit { object, level }
            }
            Material::Texture { .. } => {
                let uv = t.map(|k| material::uv::<S>(mesh, k));
                let u = uv[0].0 * w[0] + uv[1].0 * w[1] + uv[2].0 * w[2];
                let v = uv[0].1 * w[0] + uv[1].1 * w[1] + uv[2].1 * w[2];
                RaySample::Texel {
                    object,
                    u: material::texel(u),
                    v: material::texel(v),
                }
            }
        }
    }
}

/// The object-space box around the positions, one step wider on every
/// side (so flat meshes have a box too).
fn bounds<S: Scalar>(positions: &[[i16; 3]], scale: S) -> Option<Aabb<S>> {
    let first = positions.first()?;
    let (mut lo, mut hi) = (*first, *first);
    for p in positions {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let c = |v: i16, d: i32| S::from_i32(v as i32 + d) * scale;
    let a = Vec3::new(c(lo[0], -1), c(lo[1], -1), c(lo[2], -1));
    let b = Vec3::new(c(hi[0], 1), c(hi[1], 1), c(hi[2], 1));
    // A negative scale swaps the corners.
    let lo = Vec3::new(a.x.min_of(b.x), a.y.min_of(b.y), a.z.min_of(b.z));
    let hi = Vec3::new(a.x.max_of(b.x), a.y.max_of(b.y), a.z.max_of(b.z));
    Aabb::new(lo, hi).ok()
}
