//! Bounding volumes: axis-aligned boxes with the slab test, bounding
//! spheres, and [`Bounded`], which puts either around any shape so that a
//! miss costs one bound test.
//!
//! Both volumes implement [`BoundingVolume`]; its test is **conservative**:
//! it may report a ray that just misses the volume, never the reverse, so
//! a bounded shape returns exactly the hits of the unbounded one.
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
use super::checked::sub3;
use super::nearest::{Intersect, SurfaceHit};
use crate::math::Vec3;
use crate::scalar::Scalar;
use core::fmt;

/// Why an [`Aabb`] could not be built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
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
    pub fn around_sphere(center: Vec3<S>, radius: S) -> Self {
        let r = Vec3::splat(radius.abs());
        Self {
            min: center - r,
            max: center + r,
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

/// A volume that can cheaply rule out a ray.
pub trait BoundingVolume<S: Scalar> {
    /// `false` only if the ray meets no point of the volume at `t > t_min`
    /// (conservative: `true` may be a near miss).
    fn may_hit(&self, ray: &Ray<S>, t_min: S) -> bool;
}

impl<S: Scalar> BoundingVolume<S> for Aabb<S> {
    #[inline]
    fn may_hit(&self, ray: &Ray<S>, t_min: S) -> bool {
        self.intersect_range(ray, t_min, S::MAX).is_some()
    }
}

/// A shape with a bounding volume (in the shape's space) tested first: an
/// [`Aabb`] by default, or a [`BoundingSphere`].
#[derive(Clone, Copy, Debug)]
pub struct Bounded<S, P, B = Aabb<S>> {
    /// The volume; must contain the shape's surface.
    pub bounds: B,
    /// The shape.
    pub shape: P,
    _scalar: core::marker::PhantomData<S>,
}

impl<S, P, B> Bounded<S, P, B> {
    /// `shape` inside `bounds`.
    #[must_use]
    pub const fn new(bounds: B, shape: P) -> Self {
        Self {
            bounds,
            shape,
            _scalar: core::marker::PhantomData,
        }
    }
}

impl<S: Scalar, P: Intersect<S>, B: BoundingVolume<S>> Intersect<S> for Bounded<S, P, B> {
    fn intersect_ray(&self, ray: &Ray<S>, t_min: S) -> Option<SurfaceHit<S>> {
        if !self.bounds.may_hit(ray, t_min) {
            return None;
        }
        self.shape.intersect_ray(ray, t_min)
    }
}

/// Why a [`BoundingSphere`] could not be built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum BoundingSphereError {
    /// A coordinate or the radius is NaN or ±∞, or the radius is negative.
    NonFinite,
    /// No points were given.
    Empty,
    /// A difference of two points overflows the scalar (fixed point).
    Overflow,
}

impl fmt::Display for BoundingSphereError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NonFinite => f.write_str("bounding sphere input is NaN, infinite or negative"),
            Self::Empty => f.write_str("no points to bound"),
            Self::Overflow => f.write_str("point differences overflow the scalar"),
        }
    }
}

impl core::error::Error for BoundingSphereError {}

/// A closed bounding sphere `|X − C| ≤ r` (r ≥ 0).
///
/// [`BoundingSphere::from_points`] uses Ritter's algorithm (J. Ritter, "An
/// Efficient Bounding Sphere", *Graphics Gems*, 1990): two passes, at most
/// about 5–20 % larger than the minimal sphere in practice, no guarantee
/// of minimality. A final pass sets the radius to the largest distance
/// from the center, padded by a few ulps, so every point is inside despite
/// rounding.
///
/// The ray test ([`BoundingVolume::may_hit`]) works in the frame scaled by
/// `s = max(‖Q − C‖_∞, r)` with a unit direction, so every intermediate is
/// a few units at most (the scaling of [`Sphere`](super::Sphere), after
/// Ray Tracing Gems ch. 7): it rejects when the distance from the center
/// to the ray's line exceeds `r` by more than 8 ulps of `s`, or when
/// the origin is outside and the ray points away. A fixed-point difference
/// that overflows is not used to reject.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoundingSphere<S> {
    center: Vec3<S>,
    radius: S,
}

impl<S: Scalar> BoundingSphere<S> {
    /// The sphere with the given center and radius.
    ///
    /// # Errors
    /// [`BoundingSphereError::NonFinite`] for NaN, ±∞ or a negative radius.
    pub fn new(center: Vec3<S>, radius: S) -> Result<Self, BoundingSphereError> {
        if !(center.is_finite() && radius.is_finite() && radius >= S::ZERO) {
            return Err(BoundingSphereError::NonFinite);
        }
        Ok(Self { center, radius })
    }

    /// Ritter's bounding sphere of the points (see the type docs).
    ///
    /// # Errors
    /// [`BoundingSphereError::Empty`], [`BoundingSphereError::NonFinite`],
    /// and [`BoundingSphereError::Overflow`] when a difference of two
    /// points overflows fixed point.
    pub fn from_points(points: &[Vec3<S>]) -> Result<Self, BoundingSphereError> {
        let (&x, _) = points.split_first().ok_or(BoundingSphereError::Empty)?;
        if !points.iter().all(|p| p.is_finite()) {
            return Err(BoundingSphereError::NonFinite);
        }
        let dist = |a: Vec3<S>, b: Vec3<S>| -> Result<S, BoundingSphereError> {
            Ok(sub3(a, b).ok_or(BoundingSphereError::Overflow)?.length())
        };
        let farthest = |from: Vec3<S>| -> Result<Vec3<S>, BoundingSphereError> {
            let (mut best, mut bd) = (from, S::ZERO);
            for &p in points {
                let d = dist(p, from)?;
                if d > bd {
                    (best, bd) = (p, d);
                }
            }
            Ok(best)
        };
        // Pass 1: a diameter guess from two far-apart points.
        let y = farthest(x)?;
        let z = farthest(y)?;
        let mut center = (y + z) * S::HALF;
        let mut radius = dist(z, y)? * S::HALF;
        // Pass 2: grow to take in each point outside, moving the center
        // towards it so the old sphere stays inside the new one.
        for &p in points {
            let d = dist(p, center)?;
            if d > radius {
                let r = (radius + d) * S::HALF;
                let k = (d - radius) * S::HALF / d;
                let off = sub3(p, center).ok_or(BoundingSphereError::Overflow)?;
                center += off * k;
                radius = r;
            }
        }
        // Pass 3: the exact largest distance from the chosen center, then
        // a pad of a few ulps (relative, and one absolute step for fixed
        // point) against the rounding of the distances.
        let mut r = S::ZERO;
        for &p in points {
            r = r.max_of(dist(p, center)?);
        }
        let r = r + r * S::EPSILON * S::from_i32(8) + S::EPSILON * S::TWO;
        Self::new(center, r)
    }

    /// The center.
    #[must_use]
    pub fn center(&self) -> Vec3<S> {
        self.center
    }

    /// The radius.
    #[must_use]
    pub fn radius(&self) -> S {
        self.radius
    }
}

impl<S: Scalar> BoundingVolume<S> for BoundingSphere<S> {
    fn may_hit(&self, ray: &Ray<S>, _t_min: S) -> bool {
        let Some(f) = sub3(ray.origin(), self.center) else {
            return true; // overflow: do not reject
        };
        let s = f.max_abs().max_of(self.radius);
        if s == S::ZERO {
            return true;
        }
        let (f, r) = (f / s, self.radius / s);
        // A direction of the largest component ±1 first, so that fixed
        // point does not lose a small direction when squaring it.
        let d = ray.dir();
        let Some(d) = (d / d.max_abs()).try_normalize() else {
            return true;
        };
        // Lengths (`Vec3::length` scales by the largest component), not
        // squares: in fixed point a small r² would vanish.
        let pad = S::EPSILON * S::from_i32(8);
        let b = f.dot(d);
        let l = f - d * b;
        if l.length() > r + pad {
            return false; // the line passes outside
        }
        // Origin outside and the ray pointing away: both roots negative.
        !(f.length() > r + pad && b > pad)
    }
}
