//! Axis-aligned bounding boxes with the slab test, and [`Bounded`], which
//! puts a box around any shape so that a miss costs one box test.
//!
//! The slab test (Kay and Kajiya 1986; the robust form of Williams, Barrus,
//! Morley and Shirley, "An Efficient and Robust Ray–Box Intersection
//! Algorithm", JGT 2005) intersects the ray's parameter interval with the
//! three slabs `min_k ≤ Q_k + t·d_k ≤ max_k`. Here:
//! - an axis with `d_k = 0` is handled without dividing: the ray is inside
//!   the slab for all t or for none;
//! - the result is **conservative**: the interval is widened by a few ulps
//!   (as Ize, "Robust BVH Ray Traversal", JCGT 2013, widens t_far), and a
//!   fixed-point axis whose arithmetic overflows is not used to reject.
//!   A box may thus report a ray that just misses it, never the reverse.

use super::Ray;
use super::nearest::{Intersect, SurfaceHit};
use crate::math::Vec3;
use crate::scalar::Scalar;
use core::fmt;

/// Why an [`Aabb`] could not be built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AabbError {
    /// A coordinate is NaN or ±∞.
    NonFinite,
    /// `min` exceeds `max` on some axis, or no points were given.
    Empty,
}

impl fmt::Display for AabbError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NonFinite => f.write_str("box coordinate is NaN or infinity"),
            Self::Empty => f.write_str("box is empty (min > max, or no points)"),
        }
    }
}

impl core::error::Error for AabbError {}

/// An axis-aligned box `[min, max]` (closed).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb<S> {
    min: Vec3<S>,
    max: Vec3<S>,
}

impl<S: Scalar> Aabb<S> {
    /// The box with the given corners.
    ///
    /// # Errors
    /// [`AabbError::NonFinite`], [`AabbError::Empty`] when `min > max` on an
    /// axis.
    pub fn new(min: Vec3<S>, max: Vec3<S>) -> Result<Self, AabbError> {
        if !(min.is_finite() && max.is_finite()) {
            return Err(AabbError::NonFinite);
        }
        if min.x > max.x || min.y > max.y || min.z > max.z {
            return Err(AabbError::Empty);
        }
        Ok(Self { min, max })
    }

    /// The smallest box containing the points.
    ///
    /// # Errors
    /// [`AabbError::NonFinite`]; [`AabbError::Empty`] for no points.
    pub fn from_points(points: &[Vec3<S>]) -> Result<Self, AabbError> {
        let (&first, rest) = points.split_first().ok_or(AabbError::Empty)?;
        let mut b = Self::new(first, first)?;
        for &p in rest {
            b = b.union(&Self::new(p, p)?);
        }
        Ok(b)
    }

    /// The box around a sphere.
    #[must_use]
    pub fn around_sphere(centre: Vec3<S>, radius: S) -> Self {
        let r = Vec3::splat(radius.abs());
        Self {
            min: centre - r,
            max: centre + r,
        }
    }

    /// The lower corner.
    #[must_use]
    pub fn min(&self) -> Vec3<S> {
        self.min
    }

    /// The upper corner.
    #[must_use]
    pub fn max(&self) -> Vec3<S> {
        self.max
    }

    /// The smallest box containing both.
    #[must_use]
    pub fn union(&self, o: &Self) -> Self {
        Self {
            min: Vec3::new(
                self.min.x.min_of(o.min.x),
                self.min.y.min_of(o.min.y),
                self.min.z.min_of(o.min.z),
            ),
            max: Vec3::new(
                self.max.x.max_of(o.max.x),
                self.max.y.max_of(o.max.y),
                self.max.z.max_of(o.max.z),
            ),
        }
    }

    /// The (conservative) parameter interval `[t_near, t_far]` in which the
    /// ray is inside the box, clipped to `[t_min, t_max]`; `None` when it
    /// is empty.
    #[must_use]
    pub fn intersect_range(&self, ray: &Ray<S>, t_min: S, t_max: S) -> Option<(S, S)> {
        let q = ray.origin().to_array();
        let d = ray.dir().to_array();
        let lo = self.min.to_array();
        let hi = self.max.to_array();
        let (mut t0, mut t1) = (t_min, t_max);
        for k in 0..3 {
            if d[k] == S::ZERO {
                // Parallel to the slab: inside for all t or for none.
                if q[k] < lo[k] || q[k] > hi[k] {
                    return None;
                }
                continue;
            }
            let (Some(a), Some(b)) = (lo[k].checked_sub(q[k]), hi[k].checked_sub(q[k])) else {
                continue; // fixed-point overflow: do not reject on this axis
            };
            let (mut ta, mut tb) = (a / d[k], b / d[k]);
            if ta > tb {
                core::mem::swap(&mut ta, &mut tb);
            }
            // Widen by a few ulps so rounding never loses a grazing hit.
            let pad = |t: S| t.abs() * S::EPSILON * S::from_i32(4) + S::EPSILON * S::TWO;
            if ta.is_finite() {
                ta -= pad(ta);
            }
            if tb.is_finite() {
                tb += pad(tb);
            }
            t0 = t0.max_of(ta);
            t1 = t1.min_of(tb);
            if t0 > t1 {
                return None;
            }
        }
        Some((t0, t1))
    }
}

/// A shape with a bounding box (in the shape's space) tested first.
#[derive(Clone, Copy, Debug)]
pub struct Bounded<S, P> {
    /// The box; must contain the shape's surface.
    pub bounds: Aabb<S>,
    /// The shape.
    pub shape: P,
}

impl<S: Scalar, P: Intersect<S>> Intersect<S> for Bounded<S, P> {
    fn intersect_ray(&self, ray: &Ray<S>, t_min: S) -> Option<SurfaceHit<S>> {
        self.bounds.intersect_range(ray, t_min, S::MAX)?;
        self.shape.intersect_ray(ray, t_min)
    }
}
