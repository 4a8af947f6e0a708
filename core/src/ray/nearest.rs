//! Nearest hit over a set of posed objects, with a hit record that carries
//! what shading and texturing need.
//!
//! Each [`Object`] holds a shape in its own object space and its
//! object→world transform (for example a [`Pose`](crate::transform::Pose)'s
//! [`object_to_world`](crate::transform::Pose::object_to_world)), and the
//! inverse computed once with [`solve::invert_affine`]. A world ray is
//! carried into object space by the inverse; an affine map keeps the ray
//! parameter, so `t` compares across objects unchanged, and the
//! object-space hit point (for texture coordinates) comes for free.

#[cfg(feature = "sphere")]
use super::Sphere;
use super::checked::point_at;
use super::{Mesh, Plane, Polygon, Ray, SlabIndex, Triangle};
use crate::math::{Affine3, Vec3};
use crate::scalar::Scalar;
use crate::solve::{self, SolveError};
use core::fmt;

/// A hit on a shape, in the shape's own space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceHit<S> {
    /// Ray parameter.
    pub t: S,
    /// Geometric unit normal (not flipped toward the ray).
    pub normal: Vec3<S>,
    /// Which part of the shape was hit (triangle index of a mesh; 0
    /// otherwise).
    pub part: usize,
}

/// A shape a ray can hit.
pub trait Intersect<S: Scalar> {
    /// The nearest hit with `t > t_min`, or `None`. Must not panic.
    fn intersect_ray(&self, ray: &Ray<S>, t_min: S) -> Option<SurfaceHit<S>>;
}

impl<S: Scalar, T: Intersect<S> + ?Sized> Intersect<S> for &T {
    fn intersect_ray(&self, ray: &Ray<S>, t_min: S) -> Option<SurfaceHit<S>> {
        (**self).intersect_ray(ray, t_min)
    }
}

impl<S: Scalar> Intersect<S> for Plane<S> {
    fn intersect_ray(&self, ray: &Ray<S>, t_min: S) -> Option<SurfaceHit<S>> {
        let t = self.intersect(ray, t_min)?;
        Some(SurfaceHit {
            t,
            normal: self.normal(),
            part: 0,
        })
    }
}

#[cfg(feature = "sphere")]
impl<S: Scalar> Intersect<S> for Sphere<S> {
    fn intersect_ray(&self, ray: &Ray<S>, t_min: S) -> Option<SurfaceHit<S>> {
        let t = self.intersect(ray, t_min)?;
        let p = point_at(ray.origin(), ray.dir(), t)?;
        Some(SurfaceHit {
            t,
            normal: self.normal_at(p),
            part: 0,
        })
    }
}

impl<S: Scalar, const N: usize> Intersect<S> for Polygon<S, N> {
    fn intersect_ray(&self, ray: &Ray<S>, t_min: S) -> Option<SurfaceHit<S>> {
        let t = self.intersect(ray, t_min)?;
        Some(SurfaceHit {
            t,
            normal: self.plane().normal(),
            part: 0,
        })
    }
}

impl<S: Scalar, const N: usize> Intersect<S> for SlabIndex<'_, S, N> {
    fn intersect_ray(&self, ray: &Ray<S>, t_min: S) -> Option<SurfaceHit<S>> {
        let poly = self.polygon();
        let t = poly.plane().intersect(ray, t_min)?;
        let x = point_at(ray.origin(), ray.dir(), t)?;
        self.contains(poly.project(x)).then_some(SurfaceHit {
            t,
            normal: poly.plane().normal(),
            part: 0,
        })
    }
}

impl<S: Scalar> Intersect<S> for Triangle<S> {
    fn intersect_ray(&self, ray: &Ray<S>, t_min: S) -> Option<SurfaceHit<S>> {
        let h = self.intersect(ray, t_min)?;
        Some(SurfaceHit {
            t: h.t,
            normal: self.normal()?,
            part: 0,
        })
    }
}

impl<S: Scalar> Intersect<S> for Mesh<'_, S> {
    fn intersect_ray(&self, ray: &Ray<S>, t_min: S) -> Option<SurfaceHit<S>> {
        let (i, h) = self.intersect(ray, t_min)?;
        Some(SurfaceHit {
            t: h.t,
            normal: self.triangle(i)?.normal()?,
            part: i,
        })
    }
}

/// Why an [`Object`] could not be built.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum ObjectError {
    /// The object→world transform is singular (or ill-conditioned, or
    /// overflows) and has no usable inverse.
    Singular(SolveError),
}

impl fmt::Display for ObjectError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Singular(e) => write!(f, "object transform has no inverse: {e}"),
        }
    }
}

impl core::error::Error for ObjectError {
    fn source(&self) -> Option<&(dyn core::error::Error + 'static)> {
        match self {
            Self::Singular(e) => Some(e),
        }
    }
}

/// A shape in object space placed in the world.
#[derive(Clone, Copy, Debug)]
pub struct Object<S, P> {
    /// The shape, in object coordinates.
    pub shape: P,
    to_world: Affine3<S>,
    to_object: Affine3<S>,
}

impl<S: Scalar, P: Intersect<S>> Object<S, P> {
    /// Places `shape` with the given object→world transform; its inverse
    /// is computed here, once.
    ///
    /// # Errors
    /// [`ObjectError::Singular`] when the transform cannot be inverted.
    pub fn new(shape: P, object_to_world: Affine3<S>) -> Result<Self, ObjectError> {
        let to_object = solve::invert_affine(&object_to_world).map_err(ObjectError::Singular)?;
        Ok(Self {
            shape,
            to_world: object_to_world,
            to_object,
        })
    }

    /// The object→world transform.
    #[must_use]
    pub fn object_to_world(&self) -> &Affine3<S> {
        &self.to_world
    }

    /// The world→object transform.
    #[must_use]
    pub fn world_to_object(&self) -> &Affine3<S> {
        &self.to_object
    }

    /// The nearest hit on this object with `t > t_min`, as a [`Hit`] with
    /// `id` 0.
    #[must_use]
    pub fn intersect(&self, ray: &Ray<S>, t_min: S) -> Option<Hit<S>> {
        let local = Ray::new(
            self.to_object.transform_point3(ray.origin()),
            self.to_object.transform_vector3(ray.dir()),
        )
        .ok()?;
        let h = self.shape.intersect_ray(&local, t_min)?;
        // Normals transform by the inverse transpose of the linear part.
        let n = self.to_object.matrix.transpose().mul_vec3(h.normal);
        Some(Hit {
            id: 0,
            part: h.part,
            t: h.t,
            point: point_at(ray.origin(), ray.dir(), h.t)?,
            normal: n.try_normalize()?,
            object_point: point_at(local.origin(), local.dir(), h.t)?,
        })
    }
}

/// The record of the nearest hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit<S> {
    /// Index of the object in the slice given to [`nearest_hit`].
    pub id: usize,
    /// Part of the object (triangle index for meshes, else 0).
    pub part: usize,
    /// Ray parameter (in units of the world ray's |d|).
    pub t: S,
    /// World-space hit point `Q + t·d`.
    pub point: Vec3<S>,
    /// World-space unit geometric normal.
    pub normal: Vec3<S>,
    /// Object-space hit point (the world point through the object's
    /// inverse transform), for texture coordinates.
    pub object_point: Vec3<S>,
}

/// The nearest hit with `t > t_min` over `objects`. Ties in `t` go to the
/// lower index (objects are tested in order and a later one must be
/// strictly nearer to replace the current best), so the result is
/// deterministic.
#[must_use]
pub fn nearest_hit<S: Scalar, P: Intersect<S>>(
    ray: &Ray<S>,
    objects: &[Object<S, P>],
    t_min: S,
) -> Option<Hit<S>> {
    let mut best: Option<Hit<S>> = None;
    for (id, obj) in objects.iter().enumerate() {
        if let Some(mut h) = obj.intersect(ray, t_min) {
            if best.is_none_or(|b| h.t < b.t) {
                h.id = id;
                best = Some(h);
            }
        }
    }
    best
}
