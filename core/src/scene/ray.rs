//! The ray path: one ray per pixel centre, nearest hit over the scene's
//! meshes (watertight triangle test in object space) and spheres, shaded
//! with the same material model as the raster path.

use super::shade::{self, Lighting};
#[cfg(feature = "sphere")]
use super::vec3;
use super::{Color, MAX_RAY_OBJECTS, Material, Scene, SceneError, View};
use crate::math::{Affine3, Mat3, Vec3};
use crate::raster::{PERSPECTIVE_Q_BITS, SUBPIXEL_BITS, Shade, VARYING_FRAC_BITS};
#[cfg(feature = "sphere")]
use crate::ray::Sphere;
use crate::ray::{Aabb, Ray, RayCamera, ShearedRay, Triangle};
use crate::scalar::Scalar;
use crate::target::Target;

#[derive(Clone, Copy, Debug)]
struct RayObject<S> {
    to_object: Affine3<S>,
    /// The raster path's object→view transform, for screen-space Gouraud.
    to_view: Affine3<S>,
    rot: Mat3<S>,
    scale: S,
    bounds: Option<Aabb<S>>,
}

/// A scene prepared for ray casting at one image size: the ray camera,
/// each object's inverse pose and bounding box, the spheres. Cheap to
/// share between threads (`Sync` when `S` is); every query is `&self`.
#[derive(Clone, Debug)]
pub struct RayScene<'a, S> {
    scene: Scene<'a>,
    camera: RayCamera<S>,
    projection: crate::camera::Projection<S>,
    inv_focus: S,
    objects: heapless::Vec<RayObject<S>, MAX_RAY_OBJECTS>,
    #[cfg(feature = "sphere")]
    spheres: heapless::Vec<Sphere<S>, MAX_RAY_OBJECTS>,
    light: Lighting<S>,
}

enum HitKind<S> {
    Triangle {
        object: usize,
        tri: usize,
        w: [S; 3],
    },
    #[cfg(feature = "sphere")]
    Sphere { sphere: usize, point: Vec3<S> },
}

impl<'a, S: Scalar> RayScene<'a, S> {
    /// Prepares `scene` for `view` (which must use a perspective
    /// projection).
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
            let pose = shade::pose::<S>(&obj.pose);
            let to_object = pose
                .object_to_world()
                .try_inverse()
                .map_err(|_| SceneError::BadPose { object: o })?;
            let scale = S::from_f32(obj.mesh.scale);
            let bounds = bounds(obj.mesh.positions, scale);
            objects
                .push(RayObject {
                    to_object,
                    to_view: view.camera.object_to_view(&pose),
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
            let sp = Sphere::new(vec3(s.centre), S::from_f32(s.radius))
                .map_err(|_| SceneError::BadSphere { sphere: k })?;
            spheres.push(sp).map_err(|_| SceneError::TooManyObjects)?;
        }
        Ok(Self {
            scene: *scene,
            camera,
            projection: view.projection,
            inv_focus: S::ONE / focus,
            objects,
            #[cfg(feature = "sphere")]
            spheres,
            light: Lighting::new(&scene.light),
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

    /// The ray through the centre of pixel (i, j), with its direction
    /// scaled by 1/focus (about unit length: keeps fixed point in range).
    #[must_use]
    pub fn pixel_ray(&self, i: u16, j: u16) -> Option<Ray<S>> {
        let c = |k: u16| S::from_i32(k as i32) + S::HALF;
        let p = self.camera.screen_point(c(i), c(j));
        let d = (p - self.camera.viewer) * self.inv_focus;
        Ray::new(self.camera.viewer, d).ok()
    }

    /// The colour of pixel (i, j).
    #[must_use]
    pub fn pixel(&self, i: u16, j: u16) -> Color {
        match self.pixel_ray(i, j) {
            Some(ray) => self.trace_at(&ray, Some((i, j))),
            None => self.scene.background,
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
        self.trace_at(ray, None)
    }

    fn trace_at(&self, ray: &Ray<S>, pixel: Option<(u16, u16)>) -> Color {
        let mut best_t: Option<S> = None;
        let mut best: Option<HitKind<S>> = None;
        for (o, (obj, desc)) in self.objects.iter().zip(self.scene.objects).enumerate() {
            let Ok(local) = Ray::new(
                obj.to_object.transform_point3(ray.origin()),
                obj.to_object.transform_vector3(ray.dir()),
            ) else {
                continue;
            };
            if let Some(b) = &obj.bounds {
                if b.intersect_range(&local, S::ZERO, best_t.unwrap_or(S::MAX))
                    .is_none()
                {
                    continue;
                }
            }
            let Some(sheared) = ShearedRay::new(&local) else {
                continue;
            };
            let mesh = desc.mesh;
            for (t_i, &tri) in mesh.triangles.iter().enumerate() {
                let p = tri.map(|k| shade::position(mesh, obj.scale, k));
                let Some(h) = Triangle::new(p[0], p[1], p[2]).intersect_sheared(&sheared, S::ZERO)
                else {
                    continue;
                };
                if best_t.is_none_or(|b| h.t < b) {
                    best_t = Some(h.t);
                    best = Some(HitKind::Triangle {
                        object: o,
                        tri: t_i,
                        w: [h.u, h.v, h.w],
                    });
                }
            }
        }
        #[cfg(feature = "sphere")]
        for (k, s) in self.spheres.iter().enumerate() {
            if let Some(t) = s.intersect(ray, S::ZERO) {
                if best_t.is_none_or(|b| t < b) {
                    best_t = Some(t);
                    best = Some(HitKind::Sphere {
                        sphere: k,
                        point: ray.at(t),
                    });
                }
            }
        }
        match best {
            None => self.scene.background,
            #[cfg(feature = "sphere")]
            Some(HitKind::Sphere { sphere, point }) => {
                let (Some(s), Some(desc)) =
                    (self.spheres.get(sphere), self.scene.spheres.get(sphere))
                else {
                    return self.scene.background;
                };
                let q = shade::quantise_intensity(self.light.intensity(s.normal_at(point)));
                desc.color.scale(q)
            }
            Some(HitKind::Triangle { object, tri, w }) => {
                self.shade_triangle(object, tri, w, pixel)
            }
        }
    }

    fn shade_triangle(
        &self,
        object: usize,
        tri: usize,
        w: [S; 3],
        pixel: Option<(u16, u16)>,
    ) -> Color {
        let (Some(obj), Some(desc)) = (self.objects.get(object), self.scene.objects.get(object))
        else {
            return self.scene.background;
        };
        let mesh = desc.mesh;
        let Some(&t) = mesh.triangles.get(tri) else {
            return self.scene.background;
        };
        match desc.material {
            Material::Flat(color) => {
                let q = shade::face_normal(mesh, &obj.rot, t)
                    .map_or(0, |n| shade::quantise_intensity(self.light.intensity(n)));
                color.scale(q)
            }
            Material::Gouraud(color) => {
                let i = shade::vertex_intensities(mesh, &obj.rot, &self.light, t);
                let screen = pixel.and_then(|(px, py)| {
                    let p = t.map(|k| {
                        let v = obj
                            .to_view
                            .transform_point3(shade::position(mesh, obj.scale, k));
                        self.projection.project(v).and_then(|(s, _)| {
                            Some((
                                s.x.to_subpixel(SUBPIXEL_BITS)?,
                                s.y.to_subpixel(SUBPIXEL_BITS)?,
                            ))
                        })
                    });
                    let c = (px as i32 * 16 + 8, py as i32 * 16 + 8);
                    screen_lerp([p[0]?, p[1]?, p[2]?], c, i.map(shade::intensity_varying))
                });
                match screen {
                    Some(v) => color.scale((v >> VARYING_FRAC_BITS).clamp(0, 255) as u8),
                    None => {
                        let v = i[0] * w[0] + i[1] * w[1] + i[2] * w[2];
                        color.scale(shade::quantise_intensity(v))
                    }
                }
            }
            Material::Texture { texture, .. } => {
                let uv = t.map(|k| shade::uv::<S>(mesh, k));
                if let Some(c) =
                    pixel.and_then(|(px, py)| self.perspective_uv(obj, mesh, t, uv, px, py))
                {
                    return texture.sample(c.0, c.1);
                }
                let u = uv[0].0 * w[0] + uv[1].0 * w[1] + uv[2].0 * w[2];
                let v = uv[0].1 * w[0] + uv[1].1 * w[1] + uv[2].1 * w[2];
                texture.sample(shade::texel(u), shade::texel(v))
            }
        }
    }
}

impl<S: Scalar> RayScene<'_, S> {
    /// The texel the raster path's exact perspective mapping reads at
    /// pixel (px, py): the planes of `u·q`, `v·q` (16.16) and `q = near/z`
    /// (8.24) over the 28.4 vertices, divided as the shader divides
    /// (`raster::persp_div::divide`), floored.
    fn perspective_uv(
        &self,
        obj: &RayObject<S>,
        mesh: &super::MeshData<'_>,
        t: [u16; 3],
        uv: [(S, S); 3],
        px: u16,
        py: u16,
    ) -> Option<(i32, i32)> {
        let inv_near = S::ONE.checked_div(S::from_f32(self.scene.near))?;
        let mut p = [(0, 0); 3];
        let mut vs = [[0i32; 3]; 3];
        for c in 0..3 {
            let v = obj
                .to_view
                .transform_point3(shade::position(mesh, obj.scale, t[c]));
            let (s, depth) = self.projection.project(v)?;
            p[c] = (
                s.x.to_subpixel(SUBPIXEL_BITS)?,
                s.y.to_subpixel(SUBPIXEL_BITS)?,
            );
            let q = (depth / inv_near).clamp_to(S::ZERO, S::ONE);
            let qv = q.to_subpixel(PERSPECTIVE_Q_BITS).unwrap_or(1).max(1);
            vs[0][c] = shade::texel_varying(uv[c].0 * q);
            vs[1][c] = shade::texel_varying(uv[c].1 * q);
            vs[2][c] = qv;
        }
        let range = (-(1 << 29), (1 << 29) - 1);
        let centre = (px as i32 * 16 + 8, py as i32 * 16 + 8);
        let uq = screen_lerp_in(p, centre, vs[0], range)?;
        let vq = screen_lerp_in(p, centre, vs[1], range)?;
        let q = screen_lerp_in(p, centre, vs[2], range)?;
        // The raster shader's divide, so both paths read the same texel.
        let (u, v) = crate::raster::persp_div::divide(&[uq, vq, q]);
        let texel =
            |x: i64| (x >> VARYING_FRAC_BITS).clamp(i32::MIN as i64, i32::MAX as i64) as i32;
        Some((texel(u), texel(v)))
    }
}

/// The value at 28.4 point `c` of the plane through values `a` at the
/// 28.4 vertices `p` (linear in screen space, as the raster path's
/// Gouraud varyings); `None` for a zero-area triangle.
fn screen_lerp(p: [(i32, i32); 3], c: (i32, i32), a: [i32; 3]) -> Option<i32> {
    screen_lerp_in(p, c, a, (0, (256 << VARYING_FRAC_BITS) - 1))
}

fn screen_lerp_in(
    p: [(i32, i32); 3],
    c: (i32, i32),
    a: [i32; 3],
    (lo, hi): (i32, i32),
) -> Option<i32> {
    let (x0, y0) = (p[0].0 as i128, p[0].1 as i128);
    let e1 = (p[1].0 as i128 - x0, p[1].1 as i128 - y0);
    let e2 = (p[2].0 as i128 - x0, p[2].1 as i128 - y0);
    let area = e1.0 * e2.1 - e1.1 * e2.0;
    if area == 0 {
        return None;
    }
    let da1 = a[1] as i128 - a[0] as i128;
    let da2 = a[2] as i128 - a[0] as i128;
    let nx = da1 * e2.1 - da2 * e1.1;
    let ny = da2 * e1.0 - da1 * e2.0;
    let num = nx * (c.0 as i128 - x0) + ny * (c.1 as i128 - y0);
    // Round to nearest, as the raster path's gradients do.
    let d = if (num < 0) == (area < 0) {
        (num + area / 2) / area
    } else {
        (num - area / 2) / area
    };
    let v = a[0] as i128 + d;
    Some(v.clamp(lo as i128, hi as i128) as i32)
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
