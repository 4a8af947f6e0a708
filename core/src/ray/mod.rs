//! Screen→world ray casting: rays, a ray-casting camera, primitives, and the
//! nearest hit over a set of posed objects.
//!
//! The module follows the ray-casting section of the viewing-process
//! chapter: a camera is a screen center O, per-pixel screen vectors u
//! (right) and v (down) and a viewer V; the ray for a pixel runs from V
//! through the pixel's center on the screen, `X = Q + t·d` with `t > 0`.
//!
//! Every concept lives in its own submodule, the same way for each
//! primitive (construction with a small error enum, then `intersect`); the
//! types are re-exported here. The submodule docs hold the details (e.g.
//! the polygon [boundary policy](polygon#boundary-policy)).
//!
//! | file | what it holds |
//! |---|---|
//! | `mod.rs` | [`Ray`], [`RayError`] |
//! | `screen.rs` | [`RayCamera`]: pixel and column rays, from (O, u, v, V) or from a [`Camera`](crate::camera::Camera) + perspective [`Projection`](crate::camera::Projection) |
//! | `plane.rs` | [`Plane`] and line–plane intersection |
//! | `polygon.rs` | [`Polygon`]: precomputed plane, dominant axis and 2D edge equations; three inclusion tests ([`InclusionTest`]) and the boundary policy |
//! | `slab.rs` | [`SlabIndex`]: the fourth inclusion test, slabs with binary search, in caller-supplied storage |
//! | `sphere.rs` | [`Sphere`] with the stable quadratic of Ray Tracing Gems ch. 7 |
//! | `triangle.rs` | [`Triangle`], [`Mesh`] and the watertight test of Woop, Benthin and Wald (JCGT 2013) |
//! | `nearest.rs` | [`Intersect`], [`Object`] (shape + pose), [`nearest_hit`] and the [`Hit`] record |
//! | `bounds.rs` | [`Aabb`] with a conservative slab test, [`BoundingSphere`] (Ritter) with a conservative scaled test; [`Bounded`] puts either around any shape |
//! | `grid.rs` | [`Grid`]: uniform grid in caller storage, Amanatides–Woo 3D DDA, [`Mailbox`], early exit |
//! | `column.rs` | the column caster: [`GridMap`], [`ColumnCamera`], 2D Amanatides–Woo DDA, perpendicular distance, textured walls, drawn into any [`Target`](crate::target::Target) |
//! | `wide.rs` (private) | overflow-checked dot products and the higher-precision fallbacks |
//!
//! # Examples
//!
//! One camera for both paths; cast the center pixel at a posed sphere
//! (needs the `sphere` feature).
//!
//! ```
//! # #[cfg(feature = "sphere")]
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! use sightline::camera::{Camera, Projection};
//! use sightline::math::{Affine3, Vec3};
//! use sightline::ray::{nearest_hit, Object, RayCamera, Sphere};
//!
//! let camera = Camera::<f32>::look_at(Vec3::ZERO, Vec3::new(0.0, 0.0, -10.0), Vec3::Y)?;
//! let projection = Projection::perspective(100.0, 64, 48);
//! let caster = RayCamera::from_camera(&camera, &projection, 64, 48)?;
//!
//! let ball = Object::new(
//!     Sphere::new(Vec3::ZERO, 1.0)?,
//!     Affine3::from_translation(Vec3::new(0.0, 0.0, -10.0)),
//! )?;
//! let ray = caster.pixel_ray(32, 24).expect("finite camera");
//! let hit = nearest_hit(&ray, &[ball], 0.0).expect("the ball is straight ahead");
//! assert_eq!(hit.id, 0);
//! assert!((hit.point.z + 9.0).abs() < 1e-2); // front of the ball
//! assert!(hit.object_point.z > 0.99); // object space, for texturing
//! # Ok(())
//! # }
//! # #[cfg(not(feature = "sphere"))]
//! # fn main() {}
//! ```
//!
//! # Distances
//!
//! `t` is measured in units of `|d|`; it is a distance when `d` is a unit
//! vector. Every `intersect` takes a lower bound `t_min` and reports only
//! hits with `t > t_min` (use zero for "in front of the origin").
//!
//! # Bad input
//!
//! Nothing here panics. Constructors reject NaN, ±∞, zero directions and
//! degenerate shapes with an error enum; an intersection whose arithmetic
//! would divide by zero, become non-finite, or overflow fixed point (the
//! checked path of [`Scalar`]) is reported as no hit.

pub mod bounds;
pub(crate) mod checked;
#[cfg(feature = "column")]
pub mod column;
#[cfg(feature = "grid")]
pub mod grid;
pub mod nearest;
pub mod plane;
pub mod polygon;
pub mod screen;
pub mod slab;
#[cfg(feature = "sphere")]
pub mod sphere;
pub mod triangle;

pub use bounds::{Aabb, AabbError, Bounded, BoundingSphere, BoundingSphereError, BoundingVolume};
#[cfg(feature = "column")]
pub use column::{
    Column, ColumnCamera, ColumnError, ColumnStyle, GridMap, Side, WallHit, cast_columns,
    draw_columns, render_columns,
};
#[cfg(feature = "grid")]
pub use grid::{Grid, GridError, Mailbox};
pub use nearest::{Hit, Intersect, Object, ObjectError, SurfaceHit, nearest_hit};
pub use plane::{Plane, PlaneError};
pub use polygon::{Edge2, InclusionTest, Polygon, PolygonError};
pub use screen::{RayCamera, RayCameraError};
pub use slab::{SlabError, SlabIndex};
#[cfg(feature = "sphere")]
pub use sphere::{Roots, Sphere, SphereError};
pub use triangle::{Mesh, MeshError, ShearedRay, Triangle, TriangleHit};

use crate::math::Vec3;
use crate::scalar::Scalar;
use core::fmt;

/// Why a [`Ray`] could not be built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum RayError {
    /// The origin or the direction has a NaN or infinite component.
    NonFinite,
    /// The direction is the zero vector.
    ZeroDirection,
}

impl fmt::Display for RayError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NonFinite => f.write_str("ray origin or direction contains NaN or infinity"),
            Self::ZeroDirection => f.write_str("ray direction is the zero vector"),
        }
    }
}

impl core::error::Error for RayError {}

/// A ray `X = Q + t·d`, `t > 0`, with a finite origin Q and a finite,
/// non-zero direction d (not necessarily unit length).
///
/// # Guarantees
/// Once built, `origin` and `dir` are finite and `dir` is not zero, so no
/// intersection routine has to check them again.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray<S> {
    origin: Vec3<S>,
    dir: Vec3<S>,
}

impl<S: Scalar> Ray<S> {
    /// The ray from `origin` along `dir`.
    ///
    /// # Errors
    /// [`RayError::NonFinite`] or [`RayError::ZeroDirection`].
    pub fn new(origin: Vec3<S>, dir: Vec3<S>) -> Result<Self, RayError> {
        if !(origin.is_finite() && dir.is_finite()) {
            return Err(RayError::NonFinite);
        }
        if dir.max_abs() == S::ZERO {
            return Err(RayError::ZeroDirection);
        }
        Ok(Self { origin, dir })
    }

    /// The ray from `from` through `through` (`d = through − from`, so the
    /// point `through` is at `t = 1`).
    ///
    /// # Errors
    /// As [`Self::new`]; [`RayError::ZeroDirection`] when the points
    /// coincide (or, for fixed point, their difference overflows).
    pub fn through(from: Vec3<S>, through: Vec3<S>) -> Result<Self, RayError> {
        if !(from.is_finite() && through.is_finite()) {
            return Err(RayError::NonFinite);
        }
        let d = checked::sub3(through, from).ok_or(RayError::ZeroDirection)?;
        Self::new(from, d)
    }

    /// The origin Q.
    #[must_use]
    pub fn origin(&self) -> Vec3<S> {
        self.origin
    }

    /// The direction d.
    #[must_use]
    pub fn dir(&self) -> Vec3<S> {
        self.dir
    }

    /// The point `Q + t·d` (saturating for fixed point).
    #[must_use]
    pub fn at(&self, t: S) -> Vec3<S> {
        self.origin + self.dir * t
    }
}

#[cfg(all(test, feature = "sphere"))]
mod tests;
