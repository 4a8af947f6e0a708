//! Planes and line–plane intersection.

use super::Ray;
use super::wide::{dot3_checked, sub3};
use crate::math::Vec3;
use crate::scalar::Scalar;
use core::fmt;

/// Why a [`Plane`] could not be built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PlaneError {
    /// An input is NaN or ±∞.
    NonFinite,
    /// The normal is the zero vector.
    ZeroNormal,
    /// The three points are collinear (or coincide): the cross product of
    /// the edge vectors is zero.
    Collinear,
}

impl fmt::Display for PlaneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NonFinite => f.write_str("plane input contains NaN or infinity"),
            Self::ZeroNormal => f.write_str("plane normal is the zero vector"),
            Self::Collinear => f.write_str("plane points are collinear"),
        }
    }
}

impl core::error::Error for PlaneError {}

/// A plane through `point` with unit `normal`: the points X with
/// `normal·(X − point) = 0`.
///
/// # Guarantees
/// The point is finite and the normal is finite and unit length (to the
/// rounding of `S`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane<S> {
    point: Vec3<S>,
    normal: Vec3<S>,
}

impl<S: Scalar> Plane<S> {
    /// The plane through `point` with the given (not necessarily unit)
    /// normal; the normal is normalised.
    ///
    /// # Errors
    /// [`PlaneError::NonFinite`], [`PlaneError::ZeroNormal`].
    pub fn new(point: Vec3<S>, normal: Vec3<S>) -> Result<Self, PlaneError> {
        if !(point.is_finite() && normal.is_finite()) {
            return Err(PlaneError::NonFinite);
        }
        let normal = normal.try_normalize().ok_or(PlaneError::ZeroNormal)?;
        Ok(Self { point, normal })
    }

    /// The plane through three points, normal `(b − a) × (c − a)`
    /// (counter-clockwise points seen from the side the normal points to).
    ///
    /// # Errors
    /// [`PlaneError::NonFinite`]; [`PlaneError::Collinear`] when the cross
    /// product is zero or (fixed point) the edge vectors overflow.
    pub fn from_points(a: Vec3<S>, b: Vec3<S>, c: Vec3<S>) -> Result<Self, PlaneError> {
        if !(a.is_finite() && b.is_finite() && c.is_finite()) {
            return Err(PlaneError::NonFinite);
        }
        let e1 = sub3(b, a).ok_or(PlaneError::Collinear)?;
        let e2 = sub3(c, a).ok_or(PlaneError::Collinear)?;
        // Scale both edges to at most 1 first so the cross product cannot
        // overflow fixed point; the direction is unchanged.
        let s1 = e1.max_abs();
        let s2 = e2.max_abs();
        if s1 == S::ZERO || s2 == S::ZERO {
            return Err(PlaneError::Collinear);
        }
        let n = (e1 / s1).cross(e2 / s2);
        Self::new(a, n).map_err(|_| PlaneError::Collinear)
    }

    /// A point on the plane.
    #[must_use]
    pub fn point(&self) -> Vec3<S> {
        self.point
    }

    /// The unit normal.
    #[must_use]
    pub fn normal(&self) -> Vec3<S> {
        self.normal
    }

    /// Signed distance `normal·(p − point)`; `None` on overflow.
    #[must_use]
    pub fn signed_distance(&self, p: Vec3<S>) -> Option<S> {
        dot3_checked(self.normal, sub3(p, self.point)?)
    }

    /// The parameter `t > t_min` at which the ray meets the plane:
    /// `t = n·(P − Q) / n·d`.
    ///
    /// Returns `None` when the ray is parallel to the plane or lies in it
    /// (`n·d == 0` exactly: no division is attempted), when the hit is at
    /// `t ≤ t_min`, or when the quotient overflows or is not finite (a
    /// nearly parallel ray whose hit is beyond the representable range).
    #[must_use]
    pub fn intersect(&self, ray: &Ray<S>, t_min: S) -> Option<S> {
        let denom = dot3_checked(self.normal, ray.dir())?;
        if denom == S::ZERO {
            return None;
        }
        let num = dot3_checked(self.normal, sub3(self.point, ray.origin())?)?;
        let t = num.checked_div(denom)?;
        (t > t_min).then_some(t)
    }
}
